#pragma once
// Systems for the hard-particle engines' Lees-Edwards tests (event and stepped): a sheared
// square or cube, a lattice gas whose points sit on the box's faces, a pair, and the
// closest approach of any two particles over the images across the sliding faces.
#include "pedesis/core/box.hpp"
#include "pedesis/core/particles.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <limits>
#include <random>

namespace pedesis::test {

// A square (cube) of side `length`, periodic except z when `wall_z`, sheared at `rate`.
template <int D> Box<D> sheared_box(double length, double rate, bool wall_z = false) {
    Vec<D> L{};
    std::array<bool, D> periodic{};
    for (int a = 0; a < D; ++a) {
        L[a] = length;
        periodic[a] = !(wall_z && a == 2);
    }
    Box<D> box(L, periodic);
    box.set_shear_rate(rate);
    return box;
}

// n^D disks (spheres) of radius 0.5 on a lattice of the given spacing (on the box's faces,
// or half a spacing off them along z between walls), Gaussian velocities at T = 1 with no
// total momentum.
template <int D>
ParticleStore<D> sheared_lattice_gas(int n, double spacing, unsigned seed, bool wall_z = false) {
    ParticleStore<D> p;
    p.species_table = {Species{"A", 0.5, 1.0}};
    std::mt19937_64 rng(seed);
    std::normal_distribution<double> gauss;
    const int total = D == 2 ? n * n : n * n * n;
    Vec<D> sum{};
    for (int k = 0; k < total; ++k) {
        Vec<D> r{}, v{};
        int rest = k;
        for (int a = 0; a < D; ++a) {
            const double lift = wall_z && a == 2 ? 0.5 : 0.0;
            r[a] = spacing * (rest % n + lift) - 0.5 * spacing * n;
            rest /= n;
            v[a] = gauss(rng);
        }
        p.position.push_back(r);
        p.velocity.push_back(v);
        sum += v;
        p.tag.push_back(static_cast<std::uint32_t>(k));
        p.species.push_back(0);
    }
    for (auto& v : p.velocity) v -= sum * (1.0 / total);
    return p;
}

// Two particles of radius 0.5 at a and b, at rest in the flow (no peculiar velocity).
template <int D> ParticleStore<D> particle_pair(const Vec<D>& a, const Vec<D>& b) {
    ParticleStore<D> p;
    p.species_table = {Species{"A", 0.5, 1.0}};
    p.position = {a, b};
    p.velocity = {Vec<D>{}, Vec<D>{}};
    p.tag = {0, 1};
    p.species = {0, 0};
    return p;
}

// The closest approach of any two particles (positions of one instant) over the images
// across the sliding y faces and the periodic x (and z) faces: brute force.
template <int D> double closest_approach(const ParticleStore<D>& s, const Box<D>& box) {
    double closest = std::numeric_limits<double>::infinity();
    for (std::size_t i = 0; i < s.size(); ++i)
        for (std::size_t j = i + 1; j < s.size(); ++j)
            for (int ky = -1; ky <= 1; ++ky)
                for (int kx = -2; kx <= 2; ++kx) {
                    Vec<D> d = s.position[i] - s.position[j];
                    d[1] += ky * box.length(1);
                    d[0] += ky * box.shear_offset() + kx * box.length(0);
                    if (D == 3 && box.periodic(D - 1))
                        d[D - 1] -= box.length(D - 1) * std::round(d[D - 1] / box.length(D - 1));
                    closest = std::min(closest, norm(d));
                }
    return closest;
}

} // namespace pedesis::test
