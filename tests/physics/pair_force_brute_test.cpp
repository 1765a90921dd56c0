// The pair-force path (one-pass neighbour list, r_list/2 cells for dense long-cutoff
// systems, the branch-free F/r loop for one radius, the per-pair branch for several)
// against a brute-force O(N^2) sum over every pair by minimum image, in 2D and 3D, with
// one radius and with two. The two sums add the same pair forces in different orders,
// so they agree to rounding: 1e-12 of the sum of the pair forces' magnitudes on each
// particle (a missing or doubled pair would show at order 1).
#include "support/pair_cases.hpp"

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
        double scale;
        const Vec<D> f = test::brute_force_on(s, pair, i, scale, interacting);
        bad += !(norm(s.force[i] - f) <= 1e-12 * scale);
    }
    EXPECT_GT(interacting, s.size()) << "too few pairs in range to test anything";
    EXPECT_EQ(bad, 0u) << "particles whose force differs from the brute-force sum";
}

} // namespace

TEST(PairForceBruteForce, TwoDimensions) {
    test::for_each_pair_case<2>([](auto s, const auto& pair, double skin, const std::string& what) {
        check_against_brute_force(std::move(s), pair, skin, what);
    });
}

TEST(PairForceBruteForce, ThreeDimensions) {
    test::for_each_pair_case<3>([](auto s, const auto& pair, double skin, const std::string& what) {
        check_against_brute_force(std::move(s), pair, skin, what);
    });
}
