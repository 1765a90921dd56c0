// The event engine's moving wall ([event.moving_wall]; event/moving_wall.hpp) against
// exact results and brute force:
// - one ball bouncing elastically on a vibrated floor under gravity follows the flight
//   that brute force gives (each contact found on a fine grid and refined by bisection,
//   the rebound u - (v - u) in the wall's frame), bounce by bounce;
// - in an elastic gas under gravity on a vibrated floor the energy gained is exactly the
//   wall's work, to rounding, and no centre is ever below the floor's contact plane;
// - a piston driven at constant speed into an ideal gas does the work of a slow
//   compression, and a restart continues bit for bit.
#include "pedesis/core/error.hpp"
#include "pedesis/event/event_engine.hpp"
#include "support/falling_gas.hpp"
#include "support/gas_builder.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <numbers>
#include <sstream>

using namespace pedesis;
using namespace pedesis::test;

namespace {

EventParams vibrated_floor(double amplitude, double frequency, double g) {
    EventParams p;
    p.gravity = {0.0, g, 0.0};
    p.moving_wall_axis = 1;
    p.moving_wall.amplitude = amplitude;
    p.moving_wall.angular_frequency = 2.0 * std::numbers::pi * frequency;
    return p;
}

// Brute force for one ball of radius r over a floor at lo + W(t): the height y and
// vertical velocity v at time `end`, from y0, v0 at 0 (no side walls reached).
struct Ball {
    double y, v;
};
Ball brute_force_ball(double y0, double v0, double g, double lo, double r, const WallMotion& m,
                      double end, int& bounces) {
    double t = 0.0, y = y0, v = v0;
    const double h = 1e-4;
    bounces = 0;
    const auto gap = [&](double s) {
        return y + v * s + 0.5 * g * s * s - (lo + r + m.displacement(t + s));
    };
    while (t < end) {
        const double step = std::min(h, end - t);
        if (gap(step) >= 0.0) {
            y += v * step + 0.5 * g * step * step;
            v += g * step;
            t += step;
            continue;
        }
        double a = 0.0, b = step;
        for (int k = 0; k < 200 && b - a > 1e-16; ++k) {
            const double mid = 0.5 * (a + b);
            (gap(mid) < 0.0 ? b : a) = mid;
        }
        y += v * a + 0.5 * g * a * a;
        v += g * a;
        t += a;
        const double u = m.velocity(t);
        v = u - (v - u);
        ++bounces;
    }
    return {y, v};
}

TEST(MovingWallEngine, ABallOnAVibratedFloorBouncesAsBruteForceSays) {
    // a 10 x 20 box, periodic along x; the floor vibrates with amplitude 0.2 at frequency
    // 1 (Gamma = A omega^2 / g = 1.6): the ball drops from 3 above the floor
    const EventParams params = vibrated_floor(0.2, 1.0, -5.0);
    ParticleStore<2> p;
    p.species_table = {Species{"A", 0.5, 1.0}};
    p.position = {Vec<2>{{0.0, -10.0 + 3.5}}};
    p.velocity = {Vec<2>{{0.0, 0.0}}};
    p.tag = {0};
    p.species = {0};
    const Box<2> box(Vec<2>{{10.0, 20.0}}, {true, false});
    for (double end : {2.0, 5.0, 9.0}) {
        EventEngine<2> e(p, box, params);
        StopLimits lim;
        lim.time = end;
        e.run(lim);
        int bounces = 0;
        const Ball b =
            brute_force_ball(-6.5, 0.0, -5.0, -10.0, 0.5, params.moving_wall, end, bounces);
        EXPECT_EQ(e.counters().wall_collisions, static_cast<std::uint64_t>(bounces)) << end;
        EXPECT_NEAR(e.snapshot().position[0][1], b.y, 1e-6) << end;
        EXPECT_NEAR(e.snapshot().velocity[0][1], b.v, 1e-6) << end;
        if (end == 9.0) {
            EXPECT_GE(bounces, 3);
        }
    }
}

TEST(MovingWallEngine, AnElasticGasGainsExactlyTheWallsWorkAndStaysAboveTheFloor) {
    // 80 disks under gravity -1 on a floor vibrated hard (Gamma = 3.9)
    auto gas = falling_gas<2>(80, Vec<2>{{16.0, 40.0}}, 0.4, 5);
    const EventParams params = vibrated_floor(0.4, 0.5, -1.0);
    EventEngine<2> e(gas.particles, gas.box, params);
    const double e0 = e.kinetic_energy() + e.potential_energy();
    double lowest = 1e300;
    StopLimits lim;
    for (int k = 1; k <= 40; ++k) {
        lim.time = 1.0 * k;
        e.run(lim);
        const double floor = e.moving_wall_position();
        for (const auto& r : e.snapshot().position) lowest = std::min(lowest, r[1] - (floor + 0.5));
    }
    const double gained = e.kinetic_energy() + e.potential_energy() - e0;
    std::printf("wall work %.10g, energy gained %.10g, lowest centre above the floor's plane "
                "%.3g\n",
                e.wall_work(), gained, lowest);
    EXPECT_GT(e.wall_work(), 10.0); // it did work
    EXPECT_NEAR(gained, e.wall_work(), 1e-9 * (e0 + std::abs(e.wall_work())));
    EXPECT_NEAR(e.counters().energy_lost, 0.0, 1e-9 * (e0 + std::abs(e.wall_work())));
    EXPECT_GT(e.counters().pair_collisions, 1000u);
    EXPECT_GE(lowest, -1e-9);
}

TEST(MovingWallEngine, APistonCompressingAGasSlowlyDoesTheAdiabaticWork) {
    // a dilute 2D gas (N = 200, eta 0.005: Z - 1 = 0.01) compressed by the lower y wall at
    // speed 0.02, far below the thermal speed 1: a quasi-static adiabatic compression of
    // an ideal gas, T V^(2/d) = const, so in 2D the work is K0 (V0 / V1 - 1); 5 % allows
    // for Z and the heating of a finite speed (of order u / v_thermal)
    auto gas = make_gas(equal_gas<2>(200, 0.005, false, 9));
    EventParams params;
    params.moving_wall_axis = 1;
    params.moving_wall.speed = 0.02;
    EventEngine<2> e(gas.particles, gas.box, params);
    const double k0 = e.kinetic_energy();
    const double l = gas.box.length(1);
    StopLimits lim;
    lim.time = 0.25 * l / 0.02; // a quarter of the height
    e.run(lim);
    const double v_ratio = l / (l - 0.25 * l);
    const double expected = k0 * (v_ratio - 1.0);
    std::printf("piston work %.6g, adiabatic ideal gas %.6g (ratio %.4f)\n", e.wall_work(),
                expected, e.wall_work() / expected);
    EXPECT_NEAR(e.wall_work(), expected, 0.05 * expected);
    EXPECT_NEAR(e.kinetic_energy() - k0, e.wall_work(), 1e-9 * k0);
}

TEST(MovingWallEngine, ARestartContinuesBitForBit) {
    auto gas = falling_gas<2>(60, Vec<2>{{12.0, 30.0}}, 0.4, 3);
    EventParams params = vibrated_floor(0.3, 0.7, -1.0);
    params.restitution = 0.9;
    params.wall_restitution = 0.95;
    params.tc = 1e-4;
    EventEngine<2> one(gas.particles, gas.box, params);
    StopLimits lim;
    lim.time = 20.0;
    one.run(lim);
    EventEngine<2> first(gas.particles, gas.box, params);
    lim.time = 10.0;
    first.run(lim);
    std::stringstream buffer;
    first.save(buffer);
    EventEngine<2> second = EventEngine<2>::load(buffer, params);
    lim.time = 20.0;
    second.run(lim);
    EXPECT_EQ(one.counters().wall_collisions, second.counters().wall_collisions);
    EXPECT_EQ(one.wall_work(), second.wall_work());
    std::stringstream ca, cb;
    one.save(ca);
    second.save(cb);
    EXPECT_TRUE(ca.str() == cb.str()) << "the checkpoints differ";
}

TEST(MovingWallEngine, RefusesWhatItCannotMove) {
    auto gas = make_gas(equal_gas<2>(4, 0.02, false, 1));
    EventParams params;
    params.moving_wall_axis = 0;
    params.moving_wall.speed = 0.1;
    // along a periodic axis: refused
    const Box<2> periodic(Vec<2>{{gas.box.length(0), gas.box.length(1)}}, {true, false});
    EXPECT_THROW(EventEngine<2>(gas.particles, periodic, params), InputError);
    // a piston driven into the opposite wall stops the run with a message
    EventEngine<2> e(gas.particles, gas.box, params);
    StopLimits lim;
    lim.time = 1e4;
    EXPECT_THROW(e.run(lim), RunError);
}

} // namespace
