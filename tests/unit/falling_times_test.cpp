// Event times in uniform gravity (event/falling_times.hpp) against the closed forms, and
// one ball bouncing on an elastic floor in the event engine: its bounces come at the
// exact period 2 v0 / g, it never sinks below the floor, and its energy holds.
#include "pedesis/event/event_engine.hpp"
#include "pedesis/event/falling_times.hpp"

#include <gtest/gtest.h>

#include <cmath>

using namespace pedesis;

TEST(FallingTimes, GapTimesAreTheRootsOfTheParabola) {
    // dropped from rest at height 2 with g = -1: sqrt(2 h / g) = 2
    EXPECT_DOUBLE_EQ(falling_gap_time(2.0, 0.0, -1.0), 2.0);
    // thrown up at 3 from height 0 (in contact, leaving): back after 2 v / g = 6
    EXPECT_DOUBLE_EQ(falling_gap_time(0.0, 3.0, -1.0), 6.0);
    // thrown up at 1 from height 4: 4 + t - t^2/2 = 0 at t = 1 + 3 = 4
    EXPECT_NEAR(falling_gap_time(4.0, 1.0, -1.0), 4.0, 1e-15);
    // thrown down at 1 from height 4: t = -1 + 3 = 2
    EXPECT_NEAR(falling_gap_time(4.0, -1.0, -1.0), 2.0, 1e-15);
    // a ceiling above a particle pulled away from it: reached only if fast enough
    EXPECT_EQ(falling_gap_time(1.0, -1.0, 1.0), never);                         // v^2 < 2 g h
    EXPECT_NEAR(falling_gap_time(1.0, -2.0, 1.0), 2.0 - std::sqrt(2.0), 1e-15); // smaller root
    EXPECT_EQ(falling_gap_time(1.0, 0.5, 1.0), never);
    // no acceleration along the gap: the straight flight's time
    EXPECT_DOUBLE_EQ(falling_gap_time(3.0, -1.5, 0.0), 2.0);
    EXPECT_EQ(falling_gap_time(3.0, 1.5, 0.0), never);
    // at contact or past it by rounding: now if approaching or at rest on it
    EXPECT_EQ(falling_gap_time(0.0, -1.0, -1.0), 0.0);
    EXPECT_EQ(falling_gap_time(-1e-17, 0.0, -1.0), 0.0);
    EXPECT_DOUBLE_EQ(falling_gap_time(-1e-17, 1.0, -1.0), 2.0);
    // a gap closing at once keeps its relative precision ((-w - sqrt(disc)) / a would
    // cancel to 0 here)
    EXPECT_NEAR(falling_gap_time(1e-20, -1.0, -1.0), 1e-20, 1e-35);
}

TEST(FallingTimes, WallTimeChoosesTheWallMetFirst) {
    bool upper = true;
    // between walls at -5 and 5, radius 0.5, at 0 moving up at 1 under g = -1: peak 0.5,
    // so the floor (contact plane -4.5) at t = 1 + sqrt(1 + 9) = 1 + sqrt(10)
    EXPECT_NEAR(falling_wall_time(0.0, 1.0, -1.0, -5.0, 5.0, 0.5, upper), 1.0 + std::sqrt(10.0),
                1e-14);
    EXPECT_FALSE(upper);
    // fast enough to reach the ceiling's contact plane (4.5): 4.5 = 10 t - t^2 / 2
    EXPECT_NEAR(falling_wall_time(0.0, 10.0, -1.0, -5.0, 5.0, 0.5, upper),
                10.0 - std::sqrt(100.0 - 9.0), 1e-13);
    EXPECT_TRUE(upper);
}

TEST(FallingTimes, ShellBoundComesNoLaterThanTheExit) {
    const Vec<2> d{0.1, 0.0}, v{0.3, -0.2}, g{0.0, -1.0};
    const double radius = 1.0;
    const double t = falling_shell_exit_time<2>(d, v, g, radius);
    ASSERT_GT(t, 0.0);
    // the particle is still inside at the bound's time, and the bound is not far off
    for (double s = 0.0; s <= t; s += t / 100.0) {
        const Vec<2> x = d + v * s + g * (0.5 * s * s);
        EXPECT_LE(norm(x), radius * (1.0 + 1e-12));
    }
    const Vec<2> at = d + v * t + g * (0.5 * t * t);
    EXPECT_GT(norm(at), 0.5 * radius);
}

TEST(FallingBall, BouncesAtTheExactPeriodAndNeverSinks) {
    ParticleStore<2> p;
    p.species_table.push_back(Species{"A", 0.5, 2.0});
    p.resize(1);
    p.tag[0] = 0;
    p.species[0] = 0;
    const Box<2> box(Vec<2>{4.0, 20.0}, {true, false});
    // starting on the floor's contact plane, thrown up at 3 (peak 4.5 above it)
    p.position[0] = Vec<2>{0.0, box.lo(1) + 0.5};
    p.velocity[0] = Vec<2>{0.0, 3.0};
    EventParams params;
    params.gravity = {0.0, -1.0, 0.0};
    EventEngine<2> e(p, box, params);
    const double e0 = e.kinetic_energy() + e.potential_energy();
    // the weight times the centre's height above the floor: m g r on the contact plane
    EXPECT_DOUBLE_EQ(e0, 0.5 * 2.0 * 9.0 + 2.0 * 0.5);
    double lowest = 1e300;
    for (int k = 1; k <= 1000; ++k) {
        StopLimits lim;
        lim.time = 0.37 * k;
        e.run(lim);
        lowest = std::min(lowest, e.position_now(0)[1] - (box.lo(1) + 0.5));
        const double energy = e.kinetic_energy() + e.potential_energy();
        ASSERT_NEAR(energy, e0, 1e-12 * e0) << "t = " << e.time();
    }
    EXPECT_GE(lowest, -1e-12);
    // 370 time units at a period of 2 v0 / g = 6: 61 bounces
    EXPECT_EQ(e.counters().wall_collisions, 61u);
    // the height at t = 370 = 61 * 6 + 4: 3 * 4 - 4^2 / 2 = 4
    EXPECT_NEAR(e.position_now(0)[1] - (box.lo(1) + 0.5), 4.0, 1e-9);
    EXPECT_NEAR(e.velocity(0)[1], -1.0, 1e-9);
}

TEST(FallingBall, GravityAlongAPeriodicAxisIsRefused) {
    ParticleStore<2> p;
    p.species_table.push_back(Species{"A", 0.5, 1.0});
    p.resize(1);
    p.position[0] = Vec<2>{0.0, 0.0};
    p.velocity[0] = Vec<2>{1.0, 0.0};
    EventParams params;
    params.gravity = {-1.0, 0.0, 0.0};
    try {
        EventEngine<2> e(p, Box<2>(Vec<2>{4.0, 4.0}, {true, false}), params);
        FAIL() << "gravity along the periodic x axis was accepted";
    } catch (const InputError& err) {
        EXPECT_NE(std::string(err.what()).find("periodic"), std::string::npos) << err.what();
    }
}
