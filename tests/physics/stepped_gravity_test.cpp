// The stepped engine in gravity ([stepped] gravity): parabolic steps, wall crossings
// found on the parabola and the bounce reflected there.
// - one ball on an elastic floor bounces at the exact period 2 v0 / g and keeps its
//   energy to rounding, whatever the step (the crossing is a root, not a straight-line
//   guess);
// - an elastic gas keeps kinetic plus potential energy to rounding (each rewind is exact:
//   pairs fall alike, so their relative motion within a step is straight);
// - the floor carries the weight: its impulse per time is N m g (momentum balance; the
//   ceiling gets nothing at this height).
#include "pedesis/stepped/stepped_engine.hpp"
#include "support/falling_gas.hpp"

#include <gtest/gtest.h>

#include <cmath>

using namespace pedesis;
using namespace pedesis::test;

TEST(SteppedGravity, ABallBouncesAtTheExactPeriod) {
    ParticleStore<2> p;
    p.species_table.push_back(Species{"A", 0.5, 2.0});
    p.resize(1);
    const Box<2> box(Vec<2>{4.0, 20.0}, {true, false});
    p.position[0] = Vec<2>{0.0, box.lo(1) + 0.5};
    p.velocity[0] = Vec<2>{0.0, 3.0};
    SteppedParams params;
    params.dt = 0.01;
    params.max_move = 1.0;
    params.gravity = {0.0, -1.0, 0.0};
    SteppedEngine<2> e(p, box, params);
    const double e0 = e.kinetic_energy() + e.potential_energy();
    double lowest = 1e300;
    for (int k = 0; k < 37000; ++k) { // t = 370: 61 periods of 6 and 4 more
        e.step();
        lowest = std::min(lowest, e.particles().position[0][1] - (box.lo(1) + 0.5));
    }
    EXPECT_NEAR(e.kinetic_energy() + e.potential_energy(), e0, 1e-11 * e0);
    EXPECT_GE(lowest, -1e-12);
    EXPECT_EQ(e.counters().wall_collisions, 61u);
    // at t = 370 = 61 * 6 + 4: height 3 * 4 - 4^2 / 2 = 4, velocity -1
    EXPECT_NEAR(e.particles().position[0][1] - (box.lo(1) + 0.5), 4.0, 1e-8);
    EXPECT_NEAR(e.particles().velocity[0][1], -1.0, 1e-8);
}

TEST(SteppedGravity, AnElasticGasKeepsItsEnergyAndTheFloorCarriesTheWeight) {
    Gas<2> gas = falling_gas<2>(200, Vec<2>{400.0, 30.0}, 0.25, 5);
    SteppedParams params;
    params.dt = 0.02;
    params.gravity = {0.0, -1.0, 0.0};
    SteppedEngine<2> e(gas.particles, gas.box, params);
    const double e0 = e.kinetic_energy() + e.potential_energy();
    for (int k = 0; k < 5000; ++k) e.step(); // settle (t = 100)
    const double t0 = e.time();
    const double impulse0 = std::abs(e.counters().wall_impulse[1][0]);
    double worst = 0.0;
    for (int k = 0; k < 20000; ++k) {
        e.step();
        if (k % 100 == 0)
            worst = std::max(worst, std::abs(e.kinetic_energy() + e.potential_energy() - e0) / e0);
    }
    EXPECT_GT(e.counters().pair_collisions, 5000u);
    std::printf("[stepped gravity] energy drift %.2e over %llu pair and %llu wall collisions\n",
                worst, static_cast<unsigned long long>(e.counters().pair_collisions),
                static_cast<unsigned long long>(e.counters().wall_collisions));
    EXPECT_LT(worst, 1e-11);
    const double force = (std::abs(e.counters().wall_impulse[1][0]) - impulse0) / (e.time() - t0);
    std::printf("[stepped gravity] floor force / weight = %.5f\n", force / 200.0);
    // the change of the total momentum over the window (~sqrt(N m T) ~ 20) against the
    // weight's impulse 200 * 400 = 8e4: 3e-4
    EXPECT_NEAR(force / 200.0, 1.0, 2e-3);
    EXPECT_EQ(e.counters().wall_impulse[1][1], 0.0);
    e.check_no_overlap(1e-6);
}
