#include "pedesis/setup/init_random.hpp"

#include "pedesis/core/error.hpp"
#include "pedesis/core/rng.hpp"
#include "pedesis/setup/random_placement.hpp"

#include <fmt/core.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <numbers>
#include <vector>

namespace pedesis {

namespace {

std::string opt(const InitRandomOptions& o, const char* name) {
    return o.option_prefix + name;
}

void require_positive(const InitRandomOptions& o, double x, const char* name, const char* what) {
    if (!(std::isfinite(x) && x > 0.0))
        throw InputError(
            fmt::format("{}: {} must be a positive {}, got {}", o.context, opt(o, name), what, x));
}

// The densest arrangement of points at least rcut apart (hexagonal in 2D, fcc in 3D)
// holds this many per rcut^D; above it no placement can succeed, so say so at once
// instead of letting random placement grind to its give-up.
constexpr double close_packing_density(int dim) {
    return dim == 2 ? 2.0 / std::numbers::sqrt3 : std::numbers::sqrt2;
}

// Random sequential placement stalls well below close packing, near this density
// (jamming coverage 0.547 of disks, 0.384 of spheres, of diameter rcut).
constexpr double jamming_density(int dim) {
    return dim == 2 ? 0.547 * 4.0 / std::numbers::pi : 0.384 * 6.0 / std::numbers::pi;
}

} // namespace

template <int D> std::string box_lengths_text(const Box<D>& box) {
    std::string s = fmt::format("{}", box.length(0));
    for (int a = 1; a < D; ++a) s += fmt::format(" x {}", box.length(a));
    return s;
}

namespace {

template <int D>
std::vector<Vec<D>> random_positions(const Box<D>& box, std::size_t n, const InitRandomOptions& o) {
    std::vector<Vec<D>> pos;
    pos.reserve(n);
    if (o.rcut == 0.0) {
        // Nothing to avoid, and a zero distance would ask the cell list for zero-width
        // cells; these are the draws place_randomly would accept first.
        for (std::size_t k = 0; k < n; ++k) {
            CounterRng rng(o.seed, RngStream::placement, static_cast<std::uint32_t>(k));
            Vec<D> r;
            for (int a = 0; a < D; ++a) r[a] = rng.uniform(box.lo(a), box.hi(a));
            pos.push_back(r);
        }
    } else {
        // Centres are points here: the soft particles' radius may overlap, only rcut counts.
        std::vector<double> radii;
        PlacementRequest<D> req;
        req.count = n;
        req.radius = 0.0;
        for (int a = 0; a < D; ++a) {
            req.lo[a] = box.lo(a);
            req.hi[a] = box.hi(a);
        }
        req.min_distance = o.rcut;
        req.what = o.context;
        try {
            place_randomly(pos, radii, box, req, o.seed);
        } catch (const InputError&) {
            throw InputError(fmt::format(
                "{0}: {1} {2} is too dense to place centres {3} {4} apart at random: "
                "gave up after {5} of {6} particles (random placement stalls near phi * rcut^{7} = "
                "{8:.2f}); lower {1} or {3}",
                o.context, opt(o, "phi"), o.phi, opt(o, "rcut"), o.rcut, pos.size(), n, D,
                jamming_density(D)));
        }
    }
    // The uniform draws include the upper edge; the box is half-open, and moving a
    // centre across a periodic edge changes no minimum-image distance.
    for (Vec<D>& r : pos) box.wrap(r);
    return pos;
}

// Uniform on the circle or the sphere. The placement stream with its second counter
// word at 1 never meets the counters place_randomly uses (word 1 = 0), so positions
// and directors are independent without a stream of their own.
template <int D> Vec<D> random_director(std::uint64_t seed, std::uint32_t tag) {
    CounterRng rng(seed, RngStream::placement, tag, 1);
    const double angle = 2.0 * std::numbers::pi * rng.uniform();
    Vec<D> n;
    if constexpr (D == 2) {
        n[0] = std::cos(angle);
        n[1] = std::sin(angle);
    } else {
        const double z = rng.uniform(-1.0, 1.0);
        const double s = std::sqrt(std::max(0.0, 1.0 - z * z));
        n[0] = s * std::cos(angle);
        n[1] = s * std::sin(angle);
        n[2] = z;
    }
    return n;
}

} // namespace

template <int D> SoftState<D> init_random(const InitRandomOptions& o) {
    require_positive(o, o.phi, "phi", "number density (particles per unit area or volume)");
    require_positive(o, o.L, "L", "box length");
    if (o.Ly) require_positive(o, *o.Ly, "Ly", "box length");
    if (o.Lz) require_positive(o, *o.Lz, "Lz", "box length");
    if (D == 2 && o.Lz)
        throw InputError(fmt::format("{}: {} needs a 3D box", o.context, opt(o, "Lz")));
    if (!(std::isfinite(o.rcut) && o.rcut >= 0.0))
        throw InputError(
            fmt::format("{}: {} must be a distance >= 0 (0: centres may coincide), got {}",
                        o.context, opt(o, "rcut"), o.rcut));
    require_positive(o, o.radius, "radius", "particle radius");

    Vec<D> L;
    L[0] = o.L;
    L[1] = o.Ly.value_or(o.L);
    if constexpr (D == 3) L[2] = o.Lz.value_or(o.L);
    std::array<bool, D> periodic;
    periodic.fill(true);
    const Box<D> box(L, periodic);

    const double wanted = std::round(o.phi * box.volume());
    if (!(wanted <= static_cast<double>(std::numeric_limits<std::uint32_t>::max())))
        throw InputError(
            fmt::format("{}: {} {} in a box {} gives {} particles, more than particle ids "
                        "can number ({})",
                        o.context, opt(o, "phi"), o.phi, box_lengths_text(box), wanted,
                        std::numeric_limits<std::uint32_t>::max()));
    const auto n = static_cast<std::size_t>(wanted);
    if (n == 0)
        throw InputError(fmt::format("{}: {} {} in a box {} gives no particle "
                                     "(N = round(phi * volume) = 0)",
                                     o.context, opt(o, "phi"), o.phi, box_lengths_text(box)));
    if (o.phi * std::pow(o.rcut, D) > close_packing_density(D))
        throw InputError(fmt::format(
            "{0}: {1} {2} is impossible with {3} {4}: no arrangement puts centres "
            "that densely at least rcut apart (close packing allows phi * rcut^{5} <= {6:.4f}); "
            "lower {1} or {3}",
            o.context, opt(o, "phi"), o.phi, opt(o, "rcut"), o.rcut, D, close_packing_density(D)));
    // The cell list behind the placement sizes its grid from L / rcut in an int.
    double longest = 0.0;
    for (int a = 0; a < D; ++a) longest = std::max(longest, box.length(a));
    if (o.rcut > 0.0 && longest > 1e9 * o.rcut)
        throw InputError(
            fmt::format("{0}: {1} {2} is below 1e-9 of the box length; use {1} 0 for no "
                        "minimum distance",
                        o.context, opt(o, "rcut"), o.rcut));

    const std::vector<Vec<D>> pos = random_positions(box, n, o);

    SoftState<D> s;
    s.box = box;
    s.p.species_table = {Species{"A", o.radius, 1.0}};
    s.resize(n);
    for (std::size_t i = 0; i < n; ++i) {
        const auto tag = static_cast<std::uint32_t>(i);
        s.p.tag[i] = tag;
        s.p.species[i] = 0;
        s.p.position[i] = pos[i];
        s.director[i] = random_director<D>(o.seed, tag);
    }

    return s;
}

template SoftState<2> init_random<2>(const InitRandomOptions&);
template SoftState<3> init_random<3>(const InitRandomOptions&);
template std::string box_lengths_text<2>(const Box<2>&);
template std::string box_lengths_text<3>(const Box<3>&);

} // namespace pedesis
