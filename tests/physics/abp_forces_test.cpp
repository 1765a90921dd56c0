// Forces and torques of the soft engine against their definitions: each pair force is
// minus the numerical gradient of its energy, forces obey Newton's third law, and the
// polar alignment torque has the tutorial's sign and magnitude tau = J sin(theta_j - theta_i).
#include "support/soft_builder.hpp"

#include "pedesis/soft/evolver.hpp"
#include "pedesis/soft/pair_force.hpp"
#include "pedesis/soft/pair_potentials.hpp"
#include "pedesis/soft/polar_align.hpp"

#include <gtest/gtest.h>

using namespace pedesis;

namespace {

template <class Pair> double pair_energy(const Pair& p, double r, double rsum) {
    double f, u;
    return p.eval(r * r, rsum, f, u) ? u : 0.0;
}

// Central differences with h = 1e-6 have error ~h^2 U''' ~ 1e-11 and rounding ~1e-16/h:
// 1e-7 relative is a safe bound for both.
template <class Pair>
void expect_force_is_minus_gradient(const Pair& p, double rsum, double r_max) {
    for (double r = 0.3 * r_max; r < 0.999 * r_max; r += 0.01 * r_max) {
        double f_over_r = 0.0, u = 0.0;
        ASSERT_TRUE(p.eval(r * r, rsum, f_over_r, u)) << r;
        const double h = 1e-6;
        const double numeric =
            -(pair_energy(p, r + h, rsum) - pair_energy(p, r - h, rsum)) / (2 * h);
        EXPECT_NEAR(f_over_r * r, numeric, 1e-7 * std::max(1.0, std::abs(numeric))) << "r = " << r;
    }
    double f, u;
    EXPECT_FALSE(p.eval(1.0001 * r_max * r_max * 1.0001, rsum, f, u))
        << "no force beyond the range";
}

TEST(PairPotentials, HarmonicForceIsMinusGradient) {
    expect_force_is_minus_gradient(HarmonicPair{10.0, 2.0}, 2.0, 2.0);
    expect_force_is_minus_gradient(HarmonicPair{3.0, -1.0}, 1.4, 1.4); // range = r_i + r_j
    // the tutorial's law: F = k (a - r) at r
    double f, u;
    HarmonicPair{10.0, 2.0}.eval(1.5 * 1.5, 2.0, f, u);
    EXPECT_DOUBLE_EQ(f * 1.5, 10.0 * 0.5);
    EXPECT_DOUBLE_EQ(u, 0.5 * 10.0 * 0.25);
}

TEST(PairPotentials, WcaForceIsMinusGradientAndVanishesAtCutoff) {
    const WcaPair w{1.5, 1.0};
    const double rc = std::pow(2.0, 1.0 / 6.0);
    expect_force_is_minus_gradient(w, 1.0, rc);
    double f, u;
    ASSERT_TRUE(w.eval(0.999999 * rc * rc * 0.999999, 1.0, f, u));
    EXPECT_NEAR(u, 0.0, 1e-9);
    EXPECT_NEAR(f, 0.0, 1e-4);
}

// Lennard-Jones (LAMMPS' lj/cut, not shifted): U(sigma) = 0, the minimum -eps at
// 2^(1/6) sigma where the force vanishes, nothing beyond cutoff * sigma.
TEST(PairPotentials, LennardJonesMinimumAndCutoff) {
    const LjPair lj{1.5, 1.0, 2.5};
    expect_force_is_minus_gradient(lj, 1.0, 2.5);
    double f, u;
    ASSERT_TRUE(lj.eval(1.0, 7.0, f, u)); // sigma given: the radii do not matter
    EXPECT_NEAR(u, 0.0, 1e-15);
    EXPECT_DOUBLE_EQ(f, 24.0 * 1.5);
    const double rmin = std::pow(2.0, 1.0 / 6.0);
    ASSERT_TRUE(lj.eval(rmin * rmin, 1.0, f, u));
    EXPECT_NEAR(u, -1.5, 1e-14);
    EXPECT_NEAR(f, 0.0, 1e-14);
    ASSERT_TRUE(lj.eval(2.4999 * 2.4999, 1.0, f, u));
    EXPECT_NEAR(u, 4.0 * 1.5 * (std::pow(2.4999, -12) - std::pow(2.4999, -6)), 1e-15);
    // default sigma: the contact distance; default cutoff 2.5 sigma
    const LjPair contact{1.0, -1.0};
    EXPECT_DOUBLE_EQ(contact.max_range(2.0), 5.0);
    ASSERT_TRUE(contact.eval(4.0, 2.0, f, u));
    EXPECT_NEAR(u, 0.0, 1e-15);
}

template <int D> void check_newton_third_law() {
    auto s = test::random_soft_system<D>(D == 2 ? 400 : 600, 12.0, 1.0, 3);
    Evolver<D> e(s, 0.3);
    e.add_force(std::make_unique<PairForce<D, HarmonicPair>>("harmonic", HarmonicPair{10.0, 2.0}));
    std::fill(s.force.begin(), s.force.end(), Vec<D>{});
    e.forces()[0]->add_forces(s, e.neighbor_list());
    Vec<D> total{};
    double scale = 0.0;
    for (const auto& f : s.force) {
        total += f;
        scale += norm(f);
    }
    ASSERT_GT(scale, 100.0) << "the test needs overlapping particles";
    // pairwise forces cancel to rounding: ~1e-16 x sum |F|
    for (int a = 0; a < D; ++a) EXPECT_NEAR(total[a], 0.0, 1e-12 * scale);
}

TEST(PairForces, NewtonsThirdLaw2D) {
    check_newton_third_law<2>();
}
TEST(PairForces, NewtonsThirdLaw3D) {
    check_newton_third_law<3>();
}

TEST(PolarAlign, TorqueSignAndMagnitudeForTwoDisks) {
    auto s = test::random_soft_system<2>(2, 20.0);
    s.p.position[0] = Vec<2>{{0.0, 0.0}};
    s.p.position[1] = Vec<2>{{1.5, 0.0}};
    const double ti = 0.3, tj = 1.1;
    s.director[0] = Vec<2>{{std::cos(ti), std::sin(ti)}};
    s.director[1] = Vec<2>{{std::cos(tj), std::sin(tj)}};
    Evolver<2> e(s, 0.5);
    e.add_torque(std::make_unique<PolarAlign<2>>(2.0, 2.0));
    const PolarAlign<2> pa(2.0, 2.0);
    std::fill(s.torque.begin(), s.torque.end(), TorqueVec<2>{});
    pa.add_torques(s, e.neighbor_list());
    EXPECT_NEAR(s.torque[0][0], 2.0 * std::sin(tj - ti), 1e-14); // turns 0 towards 1
    EXPECT_NEAR(s.torque[1][0], 2.0 * std::sin(ti - tj), 1e-14);
    // out of range: no torque
    s.p.position[1] = Vec<2>{{2.5, 0.0}};
    Evolver<2> e2(s, 0.5);
    e2.add_torque(std::make_unique<PolarAlign<2>>(2.0, 2.0));
    std::fill(s.torque.begin(), s.torque.end(), TorqueVec<2>{});
    pa.add_torques(s, e2.neighbor_list());
    EXPECT_EQ(s.torque[0][0], 0.0);
}

} // namespace
