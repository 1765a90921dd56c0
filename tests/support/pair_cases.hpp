#pragma once
// The pair-force test cases shared by the brute-force test and the kernel-set test:
// Lennard-Jones, WCA and harmonic, each with one radius and with two, on random systems.
#include "support/soft_builder.hpp"

#include "pedesis/soft/pair_potentials.hpp"

#include <cmath>
#include <string>

namespace pedesis::test {

// n particles in a periodic box at number density rho, at least 0.75 apart; with
// `two_radii` every third particle has radius 0.35 instead of 0.5.
template <int D>
SoftState<D> pair_case_system(std::size_t n, double rho, bool two_radii, std::uint64_t seed) {
    const double L = std::pow(static_cast<double>(n) / rho, 1.0 / D);
    auto s = random_soft_system<D>(n, L, 0.5, seed, 0.75);
    if (two_radii) {
        s.p.species_table.push_back(Species{"B", 0.35, 1.0});
        for (std::size_t i = 0; i < s.size(); i += 3) s.p.species[i] = 1;
    }
    return s;
}

// The brute-force force on particle i (every other particle by minimum image) and its
// scale, the sum of its pairs' |F|; adds the pairs in range to `interacting`.
template <int D, class Pair>
Vec<D> brute_force_on(const SoftState<D>& s, const Pair& pair, std::size_t i, double& scale,
                      std::size_t& interacting) {
    Vec<D> f{};
    scale = 0.0;
    for (std::size_t j = 0; j < s.size(); ++j) {
        if (j == i) continue;
        const Vec<D> d = s.box.minimum_image(s.p.position[i] - s.p.position[j]);
        double f_over_r, energy;
        if (!pair.eval(norm2(d), s.p.radius(i) + s.p.radius(j), f_over_r, energy)) continue;
        f += f_over_r * d;
        scale += std::abs(f_over_r) * norm(d);
        ++interacting;
    }
    return f;
}

// check(system, pair, skin, name) for each case.
template <int D, class Check> void for_each_pair_case(Check&& check) {
    const std::size_t n = D == 2 ? 900 : 1000;
    for (bool two : {false, true}) {
        const std::string radii = two ? " two radii" : " one radius";
        // Lennard-Jones at 2.5 sigma, dense: more than 8 particles per r_list^D, so the
        // list uses cells of r_list / 2 and a stencil two deep
        check(pair_case_system<D>(n, D == 2 ? 0.7 : 0.8, two, 3), LjPair{1.0, -1.0, 2.5}, 0.3,
              "lj" + radii);
        // WCA and harmonic: short range, cells of r_list
        check(pair_case_system<D>(n, D == 2 ? 0.7 : 0.8, two, 4), WcaPair{1.0, -1.0}, 0.3,
              "wca" + radii);
        check(pair_case_system<D>(n, 0.4, two, 5), HarmonicPair{10.0, 2.0}, 1.0,
              "harmonic" + radii);
    }
}

} // namespace pedesis::test
