// The meeting of a falling particle and a vibrated or driven wall (event/moving_wall.hpp)
// against brute force: the gap sampled on a fine grid over the horizon, its first sign
// change refined by bisection. A contact the climb reports must be one (the gap there is
// within the tolerance and closing), none may lie before it, and a contact the grid sees
// must be found at the same time; checks are followed, as the engine follows them, until
// a contact or the horizon. Cases: random flights, particles touching a wall they just
// left, resting on a rising wall, grazing one.
#include "pedesis/event/moving_wall.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <random>

using namespace pedesis;

namespace {

struct Flight {
    double s, w, a, t0;
    WallMotion motion;
    double gap(double tau) const {
        return s + w * tau + 0.5 * a * tau * tau -
               (motion.displacement(t0 + tau) - motion.displacement(t0));
    }
    double rate(double tau) const { return w + a * tau - motion.velocity(t0 + tau); }
};

constexpr double tolerance = 1e-12;

// The first time the gap goes below zero on a grid of `points` over [0, horizon]
// (refined by bisection), or never.
double brute_force_contact(const Flight& f, double horizon, int points) {
    double prev = 0.0;
    // a start at contact counts only where it closes
    if (f.gap(0.0) <= tolerance && f.rate(0.0) < 0.0) return 0.0;
    for (int k = 1; k <= points; ++k) {
        const double tau = horizon * k / points;
        if (f.gap(tau) < 0.0) {
            double lo = prev, hi = tau;
            for (int it = 0; it < 200 && hi - lo > 1e-15 * (1.0 + hi); ++it) {
                const double mid = 0.5 * (lo + hi);
                (f.gap(mid) < 0.0 ? hi : lo) = mid;
            }
            return lo;
        }
        prev = tau;
    }
    return never;
}

// What the engine does: meet, and at a check predict again from there.
WallMeeting follow(const Flight& f, double horizon, int& checks) {
    double tau = 0.0;
    checks = 0;
    for (int round = 0; round < 10000; ++round) {
        const Flight from{f.gap(tau), f.w + f.a * tau, f.a, f.t0 + tau, f.motion};
        const WallMeeting m =
            moving_gap_time(from.s, from.w, from.a, f.motion, from.t0, horizon - tau, tolerance);
        if (m.contact || !(m.time < never)) return {m.contact ? tau + m.time : never, m.contact};
        ++checks;
        EXPECT_GT(m.time, 0.0);
        tau += m.time;
    }
    ADD_FAILURE() << "checks without end";
    return {};
}

void expect_agrees(const Flight& f, double horizon, const char* what) {
    int checks = 0;
    const WallMeeting m = follow(f, horizon, checks);
    const double truth = brute_force_contact(f, horizon, 200000);
    if (m.contact) {
        EXPECT_LE(f.gap(m.time), tolerance * 10) << what;
        EXPECT_LT(f.rate(m.time), 0.0) << what;
        // no earlier contact: the grid's first crossing is not before it (a grazing dip
        // between grid points can make the climb's earlier than the grid's)
        if (truth < never) {
            EXPECT_LE(m.time, truth + 1e-9 * (1.0 + truth)) << what;
            if (truth - m.time > 1e-6) {
                // then the grid stepped over a dip the climb caught
                double lowest = f.gap(m.time);
                EXPECT_LE(lowest, tolerance * 10) << what;
            }
        }
    } else {
        EXPECT_EQ(truth, never) << what << ": missed a contact at " << truth << " (s " << f.s
                                << ", w " << f.w << ", a " << f.a << ", t0 " << f.t0 << ", A "
                                << f.motion.amplitude << ", omega " << f.motion.angular_frequency
                                << ")";
    }
}

TEST(MovingWall, RandomFlightsOverAVibratedWallMeetItWhenBruteForceDoes) {
    std::mt19937_64 rng(11);
    std::uniform_real_distribution<double> u(0.0, 1.0);
    int contacts = 0;
    for (int k = 0; k < 300; ++k) {
        WallMotion motion;
        motion.amplitude = 0.01 + 0.5 * u(rng);
        motion.angular_frequency = 1.0 + 30.0 * u(rng);
        const Flight f{2.0 * u(rng), 6.0 * u(rng) - 3.0, k % 3 == 0 ? 0.0 : -10.0 * u(rng),
                       10.0 * u(rng), motion};
        expect_agrees(f, 3.0, "random");
        int checks = 0;
        if (follow(f, 3.0, checks).contact) ++contacts;
    }
    EXPECT_GT(contacts, 150); // most of them fall onto it
}

TEST(MovingWall, AParticleThatJustLeftTheWallIsNotMetAgainAtOnce) {
    // at contact, leaving at 0.3 relative to the wall, then falling back under gravity
    for (double t0 : {0.0, 0.1, 0.37, 1.9}) {
        WallMotion motion{0.1, 20.0, 0.0};
        const Flight f{0.0, motion.velocity(t0) + 0.3, -9.81, t0, motion};
        int checks = 0;
        const WallMeeting m = follow(f, 5.0, checks);
        ASSERT_TRUE(m.contact) << t0;
        EXPECT_GT(m.time, 1e-3) << t0;
        expect_agrees(f, 5.0, "just left");
    }
}

TEST(MovingWall, AParticleRestingOnARisingWallIsMetAtOnce) {
    // at t0 = 0 the wall is at rest and accelerating up at A omega^2 = 40 > 9.81
    WallMotion motion{0.1, 20.0, 0.0};
    const WallMeeting m = moving_gap_time(0.0, 0.0, -9.81, motion, 0.0, 1.0, tolerance);
    // (rate exactly 0 at a gap of 0: the wall's rise closes it at once: the first climb
    // creeps, and contact comes within a few tolerances)
    ASSERT_TRUE(m.contact);
    EXPECT_LT(m.time, 1e-5);
    // the rebound leaves at least `least` relative to the wall
    EXPECT_DOUBLE_EQ(wall_rebound(1.0, 1.0, 0.9, 1e-6), 1.0 + 1e-6);
    EXPECT_DOUBLE_EQ(wall_rebound(-2.0, 1.0, 0.5, 1e-6), 2.5);
}

TEST(MovingWall, GrazesAreEitherMetOrPassedNeverMissed) {
    // a particle skimming the top of the wall's stroke: gap minimum about +-1e-9
    WallMotion motion{0.5, 2.0 * std::numbers::pi, 0.0};
    for (double lift : {1e-9, -1e-9, 1e-6, -1e-6}) {
        // a particle at rest at height 2A + lift above the face, no gravity; the wall
        // reaches 2A at t = 0.5
        const Flight f{2.0 * motion.amplitude + lift, 0.0, 0.0, 0.0, motion};
        expect_agrees(f, 1.0, "graze");
        int checks = 0;
        EXPECT_EQ(follow(f, 1.0, checks).contact, lift < 0.0) << lift;
    }
}

TEST(MovingWall, ADrivenWallIsExact) {
    // a piston at speed 0.5 towards a particle 1 away, at rest, no gravity: meets at 2
    WallMotion piston{0.0, 0.0, 0.5};
    const WallMeeting m = moving_gap_time(1.0, 0.0, 0.0, piston, 3.0, 10.0, tolerance);
    ASSERT_TRUE(m.contact);
    EXPECT_DOUBLE_EQ(m.time, 2.0);
    EXPECT_FALSE(moving_gap_time(1.0, 0.0, 0.0, piston, 3.0, 1.5, tolerance).contact);
}

} // namespace
