// Dynamics of active Brownian particles against exact results (PHYSICS.md):
// free-particle MSD and orientation autocorrelation, flocking by polar alignment, and
// trajectories independent of the number of OpenMP threads.
#include "support/free_abp.hpp"
#include "support/soft_builder.hpp"
#include "support/thread_independence.hpp"

#include "pedesis/soft/brownian.hpp"
#include "pedesis/soft/evolver.hpp"
#include "pedesis/soft/pair_force.hpp"
#include "pedesis/soft/pair_potentials.hpp"
#include "pedesis/soft/polar_align.hpp"
#include "pedesis/soft/self_propulsion.hpp"

#include <gtest/gtest.h>

using namespace pedesis;

namespace {

TEST(FreeAbp, MsdAndOrientation2D) {
    test::check_free_abp<2>();
}
TEST(FreeAbp, MsdAndOrientation3D) {
    test::check_free_abp<3>();
}

// Polar order P = |sum n_i| / N.
template <int D> double polar_order(const SoftState<D>& s) {
    Vec<D> m{};
    for (const auto& d : s.director) m += d;
    return norm(m) / static_cast<double>(s.size());
}

// The tutorial's model without noise: alignment must order the system (P > 0.99), from
// a random start where P ~ 1/sqrt(N) (checked too, so the test cannot pass trivially).
TEST(PolarAlign, NoiselessAlignmentOrdersTheSystem) {
    auto s = test::random_soft_system<2>(400, std::sqrt(400 / 0.4), 1.0, 21, 1.0);
    ASSERT_LT(polar_order(s), 0.2);
    Evolver<2> e(s, 0.5);
    e.add_force(std::make_unique<PairForce<2, HarmonicPair>>("harmonic", HarmonicPair{10.0, 2.0}));
    e.add_force(std::make_unique<SelfPropulsion<2>>(1.0));
    e.add_torque(std::make_unique<PolarAlign<2>>(1.0, 2.0));
    e.add_integrator(std::make_unique<BrownianIntegrator<2>>(0.0, 1.0, 1));
    e.add_integrator(std::make_unique<BrownianRotationIntegrator<2>>(0.0, 1.0, 1));
    double order = 0.0;
    for (int block = 0; block < 40 && order <= 0.99; ++block) {
        e.run(500, 0.01);
        order = polar_order(s);
    }
    EXPECT_GT(order, 0.99) << "after " << s.time << " time units";
    std::printf("polar order %.4f at t = %.0f\n", order, s.time);
}

// Same seed, 1 and 2 threads: bit-identical positions and directors after 1000 steps
// (2D; 500 in 3D) of the tutorial's full model (noise on).
template <int D> SoftState<D> tutorial_run() {
    auto s = test::random_soft_system<D>(D == 2 ? 1000 : 600, D == 2 ? 50.0 : 12.0, 1.0, 7, 1.0);
    Evolver<D> e(s, 0.5);
    e.add_force(std::make_unique<PairForce<D, HarmonicPair>>("harmonic", HarmonicPair{10.0, 2.0}));
    e.add_force(std::make_unique<SelfPropulsion<D>>(1.0));
    e.add_torque(std::make_unique<PolarAlign<D>>(1.0, 2.0));
    e.add_integrator(std::make_unique<BrownianIntegrator<D>>(0.1, 1.0, 3));
    e.add_integrator(std::make_unique<BrownianRotationIntegrator<D>>(0.1, 1.0, 3));
    e.run(D == 2 ? 1000 : 500, 0.01);
    return s;
}

TEST(Reproducibility, OneAndTwoThreadsBitIdentical2D) {
    test::expect_thread_independent<2>(tutorial_run<2>);
}
TEST(Reproducibility, OneAndTwoThreadsBitIdentical3D) {
    test::expect_thread_independent<3>(tutorial_run<3>);
}

} // namespace
