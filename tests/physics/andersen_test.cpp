// The event engine's Andersen thermostat ([event] thermostat = "andersen"): hard disks
// (N = 400, area fraction 0.2, periodic) started at T = 1 and held at T = 2 reach the set
// temperature and a Maxwellian speed distribution, P(v < u) = 1 - exp(-m u^2 / (2 T)) in
// 2D. Every redraw is a velocity from the canonical distribution, so <K> = N D T / 2
// exactly (the centre of mass takes its share: no momentum is kept).
// Statistics: 400 snapshots one time unit apart (a redraw rate of 1 per particle and ~3
// collisions per particle in between decorrelate them): the mean temperature's standard
// error is ~0.4% (tolerance 2%); the 160000 pooled speeds give a Kolmogorov-Smirnov
// distance whose 1% critical value for independent samples is 1.63 / sqrt(160000) =
// 0.004: we allow 0.01 for the residual correlations.
#include "pedesis/event/event_engine.hpp"
#include "support/gas_builder.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

using namespace pedesis;
using namespace pedesis::test;

TEST(Andersen, HoldsTheSetTemperatureWithMaxwellianSpeeds) {
    auto spec = equal_gas<2>(400, 0.2, true, 21);
    spec.placement = Placement::random;
    const auto gas = make_gas(spec);
    EventParams params;
    params.andersen_rate = 1.0;
    params.andersen_temperature = 2.0;
    params.seed = 8;
    EventEngine<2> e(gas.particles, gas.box, params);
    StopLimits lim;
    lim.time = 10.0; // ten redraws' times: the start's e^-10 is left
    e.run(lim);
    std::vector<double> speeds;
    double kinetic = 0.0;
    const int snapshots = 400;
    for (int k = 1; k <= snapshots; ++k) {
        lim.time = 10.0 + k;
        e.run(lim);
        kinetic += e.kinetic_energy();
        for (std::size_t i = 0; i < e.size(); ++i) speeds.push_back(norm(e.velocity(i)));
    }
    const double T = kinetic / snapshots / 400.0; // K = N T in 2D
    std::printf("[andersen] T = %.4f (set 2), %llu redraws, %llu collisions\n", T,
                static_cast<unsigned long long>(e.driving().andersen_events),
                static_cast<unsigned long long>(e.counters().pair_collisions));
    EXPECT_NEAR(T / 2.0, 1.0, 0.02);
    // ~N rate t redraws
    EXPECT_NEAR(static_cast<double>(e.driving().andersen_events) / (400.0 * e.time()), 1.0, 0.02);
    std::sort(speeds.begin(), speeds.end());
    double ks = 0.0;
    const double n = static_cast<double>(speeds.size());
    for (std::size_t k = 0; k < speeds.size(); ++k) {
        const double F = 1.0 - std::exp(-speeds[k] * speeds[k] / (2.0 * 2.0));
        ks = std::max({ks, std::abs(F - static_cast<double>(k) / n),
                       std::abs(F - static_cast<double>(k + 1) / n)});
    }
    std::printf("[andersen] Kolmogorov-Smirnov distance to Maxwell at T = 2: %.4f\n", ks);
    EXPECT_LT(ks, 0.01);
}

TEST(Andersen, WarmsAColdGasFromRest) {
    // every particle at rest: no collision would ever come, only the redraws move them
    auto spec = equal_gas<2>(100, 0.1, true, 2);
    spec.placement = Placement::random;
    auto gas = make_gas(spec);
    for (auto& v : gas.particles.velocity) v = Vec<2>{};
    EventParams params;
    params.andersen_rate = 2.0;
    params.andersen_temperature = 0.5;
    EventEngine<2> e(gas.particles, gas.box, params);
    EXPECT_EQ(e.kinetic_energy(), 0.0);
    StopLimits lim;
    lim.time = 20.0;
    e.run(lim);
    EXPECT_GT(e.counters().pair_collisions, 100u);
    EXPECT_NEAR(e.kinetic_energy() / 100.0, 0.5, 0.25); // one snapshot of K = N T: ~10% noise
    EXPECT_NEAR(e.driving().andersen_energy, e.kinetic_energy(), 1e-9);
}
