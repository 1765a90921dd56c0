// Relaxation of the speed distribution in the stepped engine: a gas started with all
// speeds equal (random directions) must reach the Rayleigh (2D) / Maxwell (3D)
// distribution of PHYSICS.md, f(v) = (m v / T) exp(-m v^2 / 2T) in 2D, within a few
// collisions per particle. Kolmogorov-Smirnov test (observe/theory.hpp) at significance
// alpha = 0.001 on one snapshot of N = 2000 speeds, critical distance 1.95 / sqrt(N) =
// 0.044, with T = 2K / (D N), exact because the engine conserves the kinetic energy.
// Speeds of distinct particles are independent up to the fixed-energy constraint, which
// only narrows the KS statistic, so the test is conservative. It must reject the
// initial equal-speed state and a temperature 30% off, which shows it can fail.
#include "pedesis/observe/theory.hpp"
#include "pedesis/stepped/stepped_engine.hpp"
#include "pedesis/stepped/time_step.hpp"
#include "support/gas_builder.hpp"

#include <gtest/gtest.h>

#include <cstdio>

using namespace pedesis;
using namespace pedesis::test;

namespace {

template <int D> double ks_against_theory(const ParticleStore<D>& p, double T) {
    auto v = speeds(p);
    return theory::ks_distance(v, [&](double x) { return theory::speed_cdf(D, x, T, 1.0); });
}

template <int D> void relaxes(double eta, bool periodic, double collisions_per_particle) {
    const std::size_t n = 2000;
    auto spec = equal_gas<D>(n, eta, periodic, 23);
    spec.velocity = VelocityKind::equal_speed;
    spec.placement = Placement::random;
    auto gas = make_gas(spec);
    const double T = kinetic_temperature(gas.particles);
    const double critical = theory::ks_critical(n, 1e-3);
    const double d_initial = ks_against_theory(gas.particles, T);
    EXPECT_GT(d_initial, critical) << "the equal-speed state must fail the KS test";

    SteppedParams params;
    params.dt = suggested_time_step(gas.particles, params.max_move, 20.0 * n);
    SteppedEngine<D> e(gas.particles, gas.box, params);
    const auto target = static_cast<std::uint64_t>(collisions_per_particle * n);
    while (e.counters().pair_collisions < target) e.step();
    EXPECT_NEAR(kinetic_temperature(e.particles()), T, 1e-12);
    const double d_final = ks_against_theory(e.particles(), T);
    std::printf("D %d: KS distance initial %.4f, after %.1f collisions per particle (%llu steps "
                "of %g) %.4f (critical %.4f)\n",
                D, d_initial, static_cast<double>(e.counters().pair_collisions) / n,
                static_cast<unsigned long long>(e.steps()), params.dt, d_final, critical);
    EXPECT_LT(d_final, critical) << "speeds have not relaxed to the equilibrium distribution";
    auto v = speeds(e.particles());
    EXPECT_GT(
        theory::ks_distance(v, [&](double x) { return theory::speed_cdf(D, x, 1.3 * T, 1.0); }),
        critical);
}

} // namespace

TEST(SteppedSpeedDistribution, RelaxesToRayleighInAWalledBox2D) {
    relaxes<2>(0.25, false, 5.0);
}

TEST(SteppedSpeedDistribution, RelaxesToMaxwell3D) {
    relaxes<3>(0.2, true, 5.0);
}
