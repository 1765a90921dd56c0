// Large-N relaxation of the speed distribution (label "validation"): N = 20000 started
// at equal speeds; after 20 collisions per particle the speeds must pass a
// Kolmogorov-Smirnov test against Rayleigh (2D) / Maxwell (3D) at alpha = 0.01
// (critical distance 1.63 / sqrt(N) = 0.0115), four times sharper than the CI version.
// Independence and the exact temperature as in tests/physics/speed_distribution_test.cpp.
#include "pedesis/event/event_engine.hpp"
#include "pedesis/observe/theory.hpp"
#include "support/gas_builder.hpp"

#include <gtest/gtest.h>

#include <cstdio>

using namespace pedesis;
using namespace pedesis::test;

namespace {

template <int D> void large_case(double eta) {
    const std::size_t n = 20000;
    auto spec = equal_gas<D>(n, eta, true, 5);
    spec.velocity = VelocityKind::equal_speed;
    auto gas = make_gas(spec);
    const double T = kinetic_temperature(gas.particles);
    EventEngine<D> e(gas.particles, gas.box, EventParams{});
    StopLimits lim;
    lim.pair_collisions = 20 * n / 2;
    e.run(lim);
    auto v = speeds(e.snapshot());
    const double d =
        theory::ks_distance(v, [&](double x) { return theory::speed_cdf(D, x, T, 1.0); });
    const double critical = theory::ks_critical(n, 0.01);
    std::printf("D %d N %zu: KS distance %.5f (critical %.5f)\n", D, n, d, critical);
    EXPECT_LT(d, critical);
}

} // namespace

TEST(SpeedDistributionLarge, Rayleigh2D) {
    large_case<2>(0.3);
}
TEST(SpeedDistributionLarge, Maxwell3D) {
    large_case<3>(0.2);
}
