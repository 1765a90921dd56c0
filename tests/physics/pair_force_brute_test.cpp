// The pair-force path (one-pass neighbour list, r_list/2 cells for dense long-cutoff
// systems, the branch-free F/r loop for one radius, the per-pair branch for several)
// against a brute-force O(N^2) sum over every pair by minimum image, in 2D and 3D, with
// one radius and with two. The two sums add the same pair forces in different orders,
// so they agree to rounding: 1e-12 of the sum of the pair forces' magnitudes on each
// particle (a missing or doubled pair would show at order 1).
#include "support/soft_builder.hpp"

#include "pedesis/soft/evolver.hpp"
#include "pedesis/soft/pair_force.hpp"
#include "pedesis/soft/pair_potentials.hpp"

#include <gtest/gtest.h>

#include <memory>
#include <string>

using namespace pedesis;

namespace {

template <int D, class Pair>
void check_against_brute_force(SoftState<D> s, const Pair& pair, double skin,
                               const std::string& what) {
    SCOPED_TRACE(what);
    Evolver<D> e(s, skin);
    e.add_force(std::make_unique<PairForce<D, Pair>>("pair", pair));
    std::fill(s.force.begin(), s.force.end(), Vec<D>{});
    e.forces()[0]->add_forces(s, e.neighbor_list());

    std::size_t interacting = 0, bad = 0;
    for (std::size_t i = 0; i < s.size(); ++i) {
        Vec<D> f{};
        double scale = 0.0;
        for (std::size_t j = 0; j < s.size(); ++j) {
            if (j == i) continue;
            const Vec<D> d = s.box.minimum_image(s.p.position[i] - s.p.position[j]);
            double f_over_r, energy;
            if (!pair.eval(norm2(d), s.p.radius(i) + s.p.radius(j), f_over_r, energy)) continue;
            f += f_over_r * d;
            scale += std::abs(f_over_r) * norm(d);
            ++interacting;
        }
        bad += !(norm(s.force[i] - f) <= 1e-12 * scale);
    }
    EXPECT_GT(interacting, s.size()) << "too few pairs in range to test anything";
    EXPECT_EQ(bad, 0u) << "particles whose force differs from the brute-force sum";
}

// n particles in a periodic box at number density rho, at least `gap` apart; with
// `two_radii` every third particle has radius 0.35 instead of 0.5.
template <int D>
SoftState<D> system(std::size_t n, double rho, bool two_radii, std::uint64_t seed) {
    const double L = std::pow(static_cast<double>(n) / rho, 1.0 / D);
    auto s = test::random_soft_system<D>(n, L, 0.5, seed, 0.75);
    if (two_radii) {
        s.p.species_table.push_back(Species{"B", 0.35, 1.0});
        for (std::size_t i = 0; i < s.size(); i += 3) s.p.species[i] = 1;
    }
    return s;
}

template <int D> void all_cases() {
    const std::size_t n = D == 2 ? 900 : 1000;
    for (bool two : {false, true}) {
        const std::string radii = two ? " two radii" : " one radius";
        // Lennard-Jones at 2.5 sigma, dense: more than 8 particles per r_list^D, so the
        // list uses cells of r_list / 2 and a stencil two deep
        check_against_brute_force(system<D>(n, D == 2 ? 0.7 : 0.8, two, 3), LjPair{1.0, -1.0, 2.5},
                                  0.3, "lj" + radii);
        // WCA and harmonic: short range, cells of r_list
        check_against_brute_force(system<D>(n, D == 2 ? 0.7 : 0.8, two, 4), WcaPair{1.0, -1.0}, 0.3,
                                  "wca" + radii);
        check_against_brute_force(system<D>(n, 0.4, two, 5), HarmonicPair{10.0, 2.0}, 1.0,
                                  "harmonic" + radii);
    }
}

} // namespace

TEST(PairForceBruteForce, TwoDimensions) {
    all_cases<2>();
}

TEST(PairForceBruteForce, ThreeDimensions) {
    all_cases<3>();
}
