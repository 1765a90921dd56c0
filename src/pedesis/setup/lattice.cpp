#include "pedesis/setup/lattice.hpp"

#include "pedesis/core/error.hpp"
#include "pedesis/core/stage.hpp"

#include <algorithm>
#include <cmath>

namespace pedesis {

LatticeKind parse_lattice(const std::string& name, int dim) {
    if (dim == 2 && name == "square") return LatticeKind::square;
    if (dim == 2 && name == "hexagonal") return LatticeKind::hexagonal;
    if (dim == 3 && name == "sc") return LatticeKind::simple_cubic;
    if (dim == 3 && name == "fcc") return LatticeKind::fcc;
    throw InputError("unknown lattice '" + name + "' for dimension " + std::to_string(dim) +
                     (dim == 2 ? " (use square or hexagonal)" : " (use sc or fcc)"));
}

namespace {

// Basis of the conventional cell (in units of the cell) and its aspect ratios.
template <int D> struct Basis {
    std::vector<Vec<D>> sites;
    Vec<D> aspect; // cell edge along each axis relative to axis 0
};

template <int D> Basis<D> basis(LatticeKind kind) {
    Basis<D> b;
    b.aspect = Vec<D>::filled(1.0);
    if constexpr (D == 2) {
        if (kind == LatticeKind::square) {
            b.sites = {Vec<D>{{0.5, 0.5}}};
        } else {
            b.sites = {Vec<D>{{0.25, 0.25}}, Vec<D>{{0.75, 0.75}}};
            b.aspect[1] = std::sqrt(3.0);
        }
    } else {
        if (kind == LatticeKind::simple_cubic) {
            b.sites = {Vec<D>{{0.5, 0.5, 0.5}}};
        } else {
            b.sites = {Vec<D>{{0.25, 0.25, 0.25}}, Vec<D>{{0.75, 0.75, 0.25}},
                       Vec<D>{{0.75, 0.25, 0.75}}, Vec<D>{{0.25, 0.75, 0.75}}};
        }
    }
    return b;
}

} // namespace

template <int D>
std::vector<Vec<D>> lattice_sites(LatticeKind kind, const Vec<D>& lo, const Vec<D>& hi,
                                  const std::array<bool, D>& closed, std::size_t n) {
    enter_stage("placing particles on a lattice");
    const Basis<D> b = basis<D>(kind);
    Vec<D> L = hi - lo;
    for (int a = 0; a < D; ++a)
        if (!(L[a] > 0.0)) throw InputError("lattice: empty region");
    // cell edge a such that the region holds about n sites, then grow the cell
    // counts until it holds at least n
    double volume = 1.0, aspect_volume = 1.0;
    for (int a = 0; a < D; ++a) {
        volume *= L[a];
        aspect_volume *= b.aspect[a];
    }
    const double cells_wanted = static_cast<double>(n) / static_cast<double>(b.sites.size());
    double edge = std::pow(volume / (cells_wanted * aspect_volume), 1.0 / D);
    std::array<long, D> count{};
    for (int iter = 0; iter < 10000; ++iter) {
        long total = 1;
        for (int a = 0; a < D; ++a) {
            count[a] = std::max<long>(1, std::lround(L[a] / (edge * b.aspect[a])));
            total *= count[a];
        }
        if (static_cast<std::size_t>(total) * b.sites.size() >= n) break;
        edge *= 0.99;
    }
    // closed axes: map [umin, umax] in cell units onto [lo, hi]
    Vec<D> umin = Vec<D>::filled(1.0), umax = Vec<D>::filled(0.0);
    for (const auto& s : b.sites)
        for (int a = 0; a < D; ++a) {
            umin[a] = std::min(umin[a], s[a]);
            umax[a] = std::max(umax[a], s[a]);
        }
    for (int a = 0; a < D; ++a) umax[a] += static_cast<double>(count[a] - 1);
    // All sites in row-major order, then n of them spread evenly: the vacancies of an
    // incomplete lattice are scattered instead of leaving empty planes at one end.
    std::vector<Vec<D>> all;
    std::array<long, D> k{};
    while (true) {
        for (const auto& s : b.sites) {
            Vec<D> r;
            for (int a = 0; a < D; ++a) {
                const double u = static_cast<double>(k[a]) + s[a];
                if (!closed[a])
                    r[a] = lo[a] + u * L[a] / count[a];
                else if (umax[a] > umin[a])
                    r[a] = lo[a] + (u - umin[a]) / (umax[a] - umin[a]) * L[a];
                else
                    r[a] = lo[a] + 0.5 * L[a];
            }
            all.push_back(r);
        }
        int a = 0;
        while (a < D && ++k[a] == count[a]) k[a++] = 0;
        if (a == D) break;
    }
    std::vector<Vec<D>> out;
    out.reserve(n);
    if (all.size() >= n)
        for (std::size_t m = 0; m < n; ++m) out.push_back(all[m * all.size() / n]);
    if (out.size() < n) throw InputError("lattice: region too small for the requested count");
    return out;
}

template std::vector<Vec<2>> lattice_sites<2>(LatticeKind, const Vec<2>&, const Vec<2>&,
                                              const std::array<bool, 2>&, std::size_t);
template std::vector<Vec<3>> lattice_sites<3>(LatticeKind, const Vec<3>&, const Vec<3>&,
                                              const std::array<bool, 3>&, std::size_t);

} // namespace pedesis
