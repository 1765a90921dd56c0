#pragma once
// Builds SoftState systems for the soft/active-matter tests.
#include "pedesis/core/rng.hpp"
#include "pedesis/soft/soft_state.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <numeric>
#include <random>

namespace pedesis::test {

// N particles of radius `radius` placed uniformly at random in a periodic box of side L
// with centres at least `min_distance` apart (soft particles may overlap; the ABP
// tutorial's builder uses 1.0), directors uniformly random.
template <int D>
SoftState<D> random_soft_system(std::size_t n, double L, double radius = 1.0,
                                std::uint64_t seed = 1, double min_distance = 0.0) {
    SoftState<D> s;
    std::array<bool, D> periodic;
    periodic.fill(true);
    s.box = Box<D>(Vec<D>::filled(L), periodic);
    s.resize(n);
    s.p.species_table = {Species{"A", radius, 1.0}};
    for (std::size_t i = 0; i < n; ++i) {
        CounterRng rng(seed, RngStream::placement, static_cast<std::uint32_t>(i));
        s.p.tag[i] = static_cast<std::uint32_t>(i);
        s.p.species[i] = 0;
        bool free = false;
        while (!free) { // brute force: these systems are small
            for (int a = 0; a < D; ++a) s.p.position[i][a] = rng.uniform(-0.5 * L, 0.5 * L);
            free = true;
            for (std::size_t j = 0; j < i && free && min_distance > 0.0; ++j)
                free = norm2(s.box.minimum_image(s.p.position[i] - s.p.position[j])) >=
                       min_distance * min_distance;
        }
        Vec<D> d;
        for (int a = 0; a < D; ++a) d[a] = rng.normal();
        s.director[i] = d * (1.0 / norm(d));
    }
    return s;
}

// cells^3 fcc unit cells at number density rho in a periodic cube (in.lj's start):
// 4 cells^3 particles of one species "A" (radius 0.5, mass 1), at rest, directors along x.
inline SoftState<3> fcc_soft_state(int cells, double rho) {
    const double a = std::cbrt(4.0 / rho), L = cells * a;
    SoftState<3> s;
    s.box = Box<3>(Vec<3>::filled(L), std::array<bool, 3>{true, true, true});
    s.resize(static_cast<std::size_t>(4 * cells * cells * cells));
    s.p.species_table = {Species{"A", 0.5, 1.0}};
    const double basis[4][3] = {{0, 0, 0}, {0.5, 0.5, 0}, {0.5, 0, 0.5}, {0, 0.5, 0.5}};
    std::size_t i = 0;
    for (int x = 0; x < cells; ++x)
        for (int y = 0; y < cells; ++y)
            for (int z = 0; z < cells; ++z)
                for (const auto& b : basis) {
                    s.p.position[i] = Vec<3>{{(x + b[0]) * a, (y + b[1]) * a, (z + b[2]) * a}} -
                                      Vec<3>::filled(0.5 * L);
                    s.p.tag[i] = static_cast<std::uint32_t>(i);
                    s.p.species[i] = 0;
                    s.director[i] = Vec<3>{{1.0, 0.0, 0.0}};
                    ++i;
                }
    return s;
}

// The same system with its storage reordered at random (tags travel with particles),
// as an engine that sorts for locality would leave it.
template <int D> SoftState<D> permuted_storage(const SoftState<D>& s, std::mt19937_64& gen) {
    std::vector<std::uint32_t> perm(s.size());
    std::iota(perm.begin(), perm.end(), std::uint32_t{0});
    std::shuffle(perm.begin(), perm.end(), gen);
    SoftState<D> t = s;
    t.apply_order(perm);
    return t;
}

} // namespace pedesis::test
