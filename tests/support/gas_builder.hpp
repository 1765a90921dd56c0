#pragma once
// Shared helpers for the tests: builds a ParticleStore of disks (D = 2) or spheres
// (D = 3) on a lattice or at random in a periodic or walled box, with Maxwell-Boltzmann
// (or equal-speed) velocities and zero total momentum; plus small measurement helpers
// (temperature, momentum, block statistics, bitwise comparison).
#include "pedesis/core/box.hpp"
#include "pedesis/core/error.hpp"
#include "pedesis/core/particles.hpp"
#include "pedesis/core/rng.hpp"
#include "pedesis/core/species.hpp"
#include "pedesis/core/vec.hpp"
#include "pedesis/setup/random_placement.hpp"
#include "pedesis/setup/velocities.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <numbers>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

namespace pedesis::test {

enum class Placement { lattice, random };

struct SpeciesSpec {
    std::size_t count = 0;
    double radius = 0.5;
    double mass = 1.0;
    double temperature = -1.0; // < 0: use GasSpec::temperature
};

template <int D> struct GasSpec {
    std::vector<SpeciesSpec> species{SpeciesSpec{1000, 0.5, 1.0, -1.0}};
    double eta = 0.2;                    // packing fraction over the whole box volume
    Vec<D> aspect = Vec<D>::filled(1.0); // box edge ratios (scaled to give eta)
    bool periodic = true;                // all axes periodic, or all axes walled
    Placement placement = Placement::lattice;
    VelocityKind velocity = VelocityKind::maxwell_boltzmann; // or equal_speed
    double temperature = 1.0;
    bool zero_momentum = true;
    std::uint64_t seed = 1;
};

template <int D> struct Gas {
    ParticleStore<D> particles;
    Box<D> box;
};

inline double particle_volume(int dim, double radius) {
    return dim == 2 ? std::numbers::pi * radius * radius
                    : 4.0 / 3.0 * std::numbers::pi * radius * radius * radius;
}

// Convenience: N equal particles of diameter 1 and mass 1.
template <int D>
GasSpec<D> equal_gas(std::size_t n, double eta, bool periodic = true, std::uint64_t seed = 1) {
    GasSpec<D> g;
    g.species = {SpeciesSpec{n, 0.5, 1.0, -1.0}};
    g.eta = eta;
    g.periodic = periodic;
    g.seed = seed;
    return g;
}

// Lattice start: a whole hexagonal (2D) / fcc (3D) lattice with at least n sites fills
// the region, and the spare sites are left empty at random.
//
// (Not setup/lattice_sites: that returns the first n sites, row-major, of a near-cubic
// lattice with at least n sites, which leaves the last rows or planes empty. For 20000
// spheres it picks 18^3 fcc cells for 20000 of 23328 sites, so two of the 18 planes, 11%
// of the box, are empty; the density step launches a sound wave whose kinetic energy
// reached ~3% of the thermal energy and distorted the speed distribution for tens of
// collisions per particle. Random vacancies keep the density uniform on all scales
// above the lattice spacing.)
template <int D>
std::vector<Vec<D>> lattice_with_random_vacancies(const Vec<D>& lo, const Vec<D>& hi,
                                                  const std::array<bool, D>& closed, std::size_t n,
                                                  std::uint64_t seed) {
    std::vector<Vec<D>> basis;
    Vec<D> aspect = Vec<D>::filled(1.0);
    if constexpr (D == 2) {
        basis = {Vec<D>{{0.25, 0.25}}, Vec<D>{{0.75, 0.75}}};
        aspect[1] = std::sqrt(3.0);
    } else {
        basis = {Vec<D>{{0.25, 0.25, 0.25}}, Vec<D>{{0.75, 0.75, 0.25}}, Vec<D>{{0.75, 0.25, 0.75}},
                 Vec<D>{{0.25, 0.75, 0.75}}};
    }
    const Vec<D> L = hi - lo;
    double volume = 1.0, aspect_volume = 1.0;
    for (int a = 0; a < D; ++a) {
        volume *= L[a];
        aspect_volume *= aspect[a];
    }
    const double edge = std::pow(volume * static_cast<double>(basis.size()) /
                                     (static_cast<double>(n) * aspect_volume),
                                 1.0 / D);
    std::array<std::size_t, D> cells;
    for (int a = 0; a < D; ++a)
        cells[a] = std::max<std::size_t>(
            1, static_cast<std::size_t>(std::floor(L[a] / (edge * aspect[a]))));
    auto total = [&] {
        std::size_t t = basis.size();
        for (int a = 0; a < D; ++a) t *= cells[a];
        return t;
    };
    // add cells along the axis whose cells are the most stretched until n sites fit
    while (total() < n) {
        int widest = 0;
        for (int a = 1; a < D; ++a)
            if (L[a] / (static_cast<double>(cells[a]) * aspect[a]) >
                L[widest] / (static_cast<double>(cells[widest]) * aspect[widest]))
                widest = a;
        ++cells[widest];
    }
    std::vector<Vec<D>> all;
    all.reserve(total());
    std::array<std::size_t, D> k{};
    while (true) {
        for (const auto& b : basis) {
            Vec<D> r;
            for (int a = 0; a < D; ++a) {
                const double u = static_cast<double>(k[a]) + b[a];
                if (!closed[a]) {
                    r[a] = lo[a] + u * L[a] / static_cast<double>(cells[a]);
                } else {
                    // outermost sites on lo and hi (basis offsets run from 0.25 to 0.75)
                    const double umin = 0.25, umax = static_cast<double>(cells[a]) - 0.25;
                    r[a] = lo[a] + (u - umin) / (umax - umin) * L[a];
                }
            }
            all.push_back(r);
        }
        int a = 0;
        while (a < D && ++k[a] == cells[a]) k[a++] = 0;
        if (a == D) break;
    }
    // keep n of the sites, chosen uniformly at random (partial Fisher-Yates), in lattice order
    std::vector<std::size_t> idx(all.size());
    for (std::size_t m = 0; m < idx.size(); ++m) idx[m] = m;
    CounterRng rng(seed, RngStream::placement, 0xfffffffeu);
    for (std::size_t m = 0; m < n; ++m) {
        const std::size_t left = idx.size() - m;
        const auto j =
            m + static_cast<std::size_t>(rng.uniform() * static_cast<double>(left)) % left;
        std::swap(idx[m], idx[j]);
    }
    idx.resize(n);
    std::sort(idx.begin(), idx.end());
    std::vector<Vec<D>> out(n);
    for (std::size_t m = 0; m < n; ++m) out[m] = all[idx[m]];
    return out;
}

template <int D> Gas<D> make_gas(const GasSpec<D>& spec) {
    std::size_t n = 0;
    double occupied = 0.0, max_radius = 0.0;
    for (const auto& s : spec.species) {
        n += s.count;
        occupied += static_cast<double>(s.count) * particle_volume(D, s.radius);
        max_radius = std::max(max_radius, s.radius);
    }
    if (n == 0) throw InputError("gas builder: no particles");
    double aspect_volume = 1.0;
    for (int a = 0; a < D; ++a) aspect_volume *= spec.aspect[a];
    const double scale = std::pow(occupied / spec.eta / aspect_volume, 1.0 / D);
    Vec<D> L;
    std::array<bool, D> periodic;
    for (int a = 0; a < D; ++a) {
        L[a] = scale * spec.aspect[a];
        periodic[a] = spec.periodic;
    }
    Gas<D> gas{ParticleStore<D>{}, Box<D>(L, periodic)};
    auto& p = gas.particles;
    for (std::size_t k = 0; k < spec.species.size(); ++k) {
        // (append rather than "S" + to_string: GCC 12 warns falsely on the latter at -O3)
        std::string name = std::to_string(k);
        name.insert(name.begin(), 'S');
        p.species_table.push_back(Species{name, spec.species[k].radius, spec.species[k].mass});
    }
    p.resize(n);
    {
        std::size_t i = 0;
        for (std::size_t k = 0; k < spec.species.size(); ++k)
            for (std::size_t c = 0; c < spec.species[k].count; ++c, ++i) {
                p.tag[i] = static_cast<std::uint32_t>(i);
                p.species[i] = static_cast<std::uint16_t>(k);
            }
    }

    if (spec.placement == Placement::lattice) {
        // the region the centres may occupy: inset by the largest radius from walls
        Vec<D> lo, hi;
        std::array<bool, D> closed;
        for (int a = 0; a < D; ++a) {
            closed[a] = !spec.periodic;
            const double inset = spec.periodic ? 0.0 : max_radius;
            lo[a] = gas.box.lo(a) + inset;
            hi[a] = gas.box.hi(a) - inset;
        }
        std::vector<Vec<D>> sites = lattice_with_random_vacancies<D>(lo, hi, closed, n, spec.seed);
        // mixtures: shuffle the sites so that species are spread over the box
        if (spec.species.size() > 1) {
            CounterRng rng(spec.seed, RngStream::placement, 0xffffffffu);
            for (std::size_t k = sites.size(); k > 1; --k) {
                const auto j = static_cast<std::size_t>(rng.uniform() * static_cast<double>(k)) % k;
                std::swap(sites[k - 1], sites[j]);
            }
        }
        for (std::size_t i = 0; i < n; ++i) p.position[i] = sites[i];
    } else {
        std::vector<Vec<D>> pos;
        std::vector<double> radii;
        std::uint32_t first = 0;
        // place the biggest particles first
        std::vector<std::size_t> order(spec.species.size());
        for (std::size_t k = 0; k < order.size(); ++k) order[k] = k;
        std::stable_sort(order.begin(), order.end(), [&](std::size_t x, std::size_t y) {
            return spec.species[x].radius > spec.species[y].radius;
        });
        std::vector<std::size_t> start(spec.species.size(), 0);
        for (std::size_t k = 1; k < spec.species.size(); ++k)
            start[k] = start[k - 1] + spec.species[k - 1].count;
        std::vector<Vec<D>> placed(n);
        for (std::size_t k : order) {
            const auto& s = spec.species[k];
            PlacementRequest<D> req;
            req.count = s.count;
            req.radius = s.radius;
            for (int a = 0; a < D; ++a) {
                const double inset = spec.periodic ? 0.0 : s.radius;
                req.lo[a] = gas.box.lo(a) + inset;
                req.hi[a] = gas.box.hi(a) - inset;
            }
            req.first_tag = first;
            req.what = std::to_string(k);
            req.what.insert(0, std::string_view("gas builder species "));
            const std::size_t before = pos.size();
            place_randomly<D>(pos, radii, gas.box, req, spec.seed);
            for (std::size_t c = 0; c < s.count; ++c) placed[start[k] + c] = pos[before + c];
            first += static_cast<std::uint32_t>(s.count);
        }
        for (std::size_t i = 0; i < n; ++i) {
            p.position[i] = placed[i];
            gas.box.wrap(p.position[i]);
        }
    }

    // velocities: each species at its own temperature, then zero total momentum
    VelocitySpec vs;
    vs.kind = spec.velocity;
    std::vector<std::vector<std::size_t>> members(spec.species.size());
    for (std::size_t i = 0; i < n; ++i) members[p.species[i]].push_back(i);
    std::vector<std::size_t> all(n);
    for (std::size_t i = 0; i < n; ++i) all[i] = i;
    for (std::size_t k = 0; k < spec.species.size(); ++k) {
        const auto& s = spec.species[k];
        const double T = s.temperature >= 0.0 ? s.temperature : spec.temperature;
        vs.temperature = T;
        vs.speed = std::sqrt(D * T / s.mass);
        const auto& idx = members[k];
        for (std::size_t m = 0; m < idx.size(); ++m) {
            const std::size_t i = idx[m];
            if (spec.velocity == VelocityKind::equal_speed && spec.zero_momentum && m % 2 == 1) {
                // equal speeds and zero momentum at once: pairs with opposite velocities
                p.velocity[i] = -p.velocity[idx[m - 1]];
            } else {
                p.velocity[i] = draw_velocity<D>(vs, s.mass, spec.seed, p.tag[i]);
            }
        }
        if (spec.velocity == VelocityKind::maxwell_boltzmann) {
            if (spec.zero_momentum) remove_drift(p, idx);
            rescale_temperature(p, idx, T);
        }
    }
    if (spec.velocity == VelocityKind::maxwell_boltzmann && spec.zero_momentum &&
        spec.species.size() > 1) {
        // total momentum of all species together; keeps each species' temperature close
        remove_drift(p, all);
    }
    return gas;
}

// ---- measurement helpers -------------------------------------------------------

template <int D> double kinetic_energy(const ParticleStore<D>& p) {
    double e = 0.0;
    for (std::size_t i = 0; i < p.size(); ++i)
        if (std::isfinite(p.mass(i))) e += 0.5 * p.mass(i) * norm2(p.velocity[i]);
    return e;
}

// Kinetic temperature sum m v^2 / (D N) of the mobile particles of one species (or all
// when species < 0).
template <int D> double kinetic_temperature(const ParticleStore<D>& p, int species = -1) {
    double s = 0.0;
    std::size_t count = 0;
    for (std::size_t i = 0; i < p.size(); ++i) {
        if (species >= 0 && p.species[i] != species) continue;
        if (!std::isfinite(p.mass(i))) continue;
        s += p.mass(i) * norm2(p.velocity[i]);
        ++count;
    }
    return s / (D * static_cast<double>(count));
}

template <int D> Vec<D> total_momentum(const ParticleStore<D>& p) {
    Vec<D> m{};
    for (std::size_t i = 0; i < p.size(); ++i)
        if (std::isfinite(p.mass(i))) m += p.mass(i) * p.velocity[i];
    return m;
}

// sum of m |v|, the natural scale against which to judge a momentum error
template <int D> double momentum_scale(const ParticleStore<D>& p) {
    double s = 0.0;
    for (std::size_t i = 0; i < p.size(); ++i)
        if (std::isfinite(p.mass(i))) s += p.mass(i) * norm(p.velocity[i]);
    return s;
}

template <int D> std::vector<double> speeds(const ParticleStore<D>& p) {
    std::vector<double> s(p.size());
    for (std::size_t i = 0; i < p.size(); ++i) s[i] = norm(p.velocity[i]);
    return s;
}

inline bool same_bits(double a, double b) {
    return std::memcmp(&a, &b, sizeof(double)) == 0;
}

template <int D> bool same_bits(const Vec<D>& a, const Vec<D>& b) {
    return std::memcmp(a.c.data(), b.c.data(), sizeof(double) * D) == 0;
}

template <std::size_t N>
bool same_bits(const std::array<double, N>& a, const std::array<double, N>& b) {
    return std::memcmp(a.data(), b.data(), sizeof(double) * N) == 0;
}

// Mean and standard error of the mean of (assumed independent) block values.
struct BlockStats {
    double mean = 0.0;
    double std_error = 0.0;
    std::size_t blocks = 0;
};

inline BlockStats block_stats(const std::vector<double>& x) {
    BlockStats b;
    b.blocks = x.size();
    if (x.empty()) return b;
    for (double v : x) b.mean += v;
    b.mean /= static_cast<double>(x.size());
    if (x.size() < 2) return b;
    double var = 0.0;
    for (double v : x) var += (v - b.mean) * (v - b.mean);
    var /= static_cast<double>(x.size() - 1);
    b.std_error = std::sqrt(var / static_cast<double>(x.size()));
    return b;
}

} // namespace pedesis::test
