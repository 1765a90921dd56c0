// Relaxation of the speed distribution: a gas started with all speeds equal (random
// directions, zero momentum) must reach the Rayleigh (2D) / Maxwell (3D) distribution
// of PHYSICS.md within a few collisions per particle. Kolmogorov-Smirnov test at
// significance alpha = 0.001 on one snapshot of N = 2000 speeds (critical distance
// 1.95 / sqrt(N) = 0.044). The speeds of distinct particles are independent up to the
// fixed-energy constraint, which only narrows the KS statistic (conservative); the
// temperature is the exact one of the gas, 2K / (D N), fixed by energy conservation.
// The same test must reject the initial equal-speed state (KS distance ~0.6 and ~0.6),
// which shows it can fail.
#include "pedesis/event/event_engine.hpp"
#include "pedesis/observe/theory.hpp"
#include "support/gas_builder.hpp"

#include <gtest/gtest.h>

#include <cstdio>

using namespace pedesis;
using namespace pedesis::test;

namespace {

constexpr double alpha = 1e-3;

template <int D> double ks_to_equilibrium(const ParticleStore<D>& s, double T) {
    auto v = speeds(s);
    return theory::ks_distance(v, [&](double x) { return theory::speed_cdf(D, x, T, 1.0); });
}

template <int D> void relaxation_case(double eta, double collisions_per_particle) {
    const std::size_t n = 2000;
    auto spec = equal_gas<D>(n, eta, true, 21);
    spec.velocity = VelocityKind::equal_speed;
    spec.placement = Placement::random;
    auto gas = make_gas(spec);
    const double T = kinetic_temperature(gas.particles);
    ASSERT_NEAR(T, 1.0, 1e-12);
    // the initial state: all speeds sqrt(D T / m)
    for (double v : speeds(gas.particles)) ASSERT_NEAR(v, std::sqrt(D * T), 1e-12);
    const double critical = theory::ks_critical(n, alpha);
    const double d_initial = ks_to_equilibrium(gas.particles, T);
    EXPECT_GT(d_initial, critical) << "the equal-speed state must fail the KS test";

    EventEngine<D> e(gas.particles, gas.box, EventParams{});
    StopLimits lim;
    lim.pair_collisions = static_cast<std::uint64_t>(collisions_per_particle * n / 2.0);
    e.run(lim);
    const auto s = e.snapshot();
    EXPECT_NEAR(kinetic_temperature(s), T, 1e-12);
    const double d_final = ks_to_equilibrium(s, T);
    std::printf(
        "D %d: KS distance initial %.4f, after %.0f collisions/particle %.4f (critical %.4f)\n", D,
        d_initial, collisions_per_particle, d_final, critical);
    EXPECT_LT(d_final, critical) << "speeds have not relaxed to the equilibrium distribution";
    // the test is sharp enough to see a wrong temperature: 30% off is rejected
    auto v = speeds(s);
    EXPECT_GT(
        theory::ks_distance(v, [&](double x) { return theory::speed_cdf(D, x, 1.3 * T, 1.0); }),
        critical);
}

} // namespace

TEST(SpeedDistribution, RelaxesToRayleigh2D) {
    relaxation_case<2>(0.3, 10.0);
}
TEST(SpeedDistribution, RelaxesToMaxwell3D) {
    relaxation_case<3>(0.2, 10.0);
}
