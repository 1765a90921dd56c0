// Lees-Edwards shear in the event engine, against results worked out by hand and exact
// balances: a free particle crossing the sliding face lands where the offset puts it; two
// particles meet across the face exactly when their images line up; no pair ever
// overlaps in dense, strongly sheared gases (a brute-force scan of every pair and image);
// the energy the flow feeds in, -rate V ∫ P_xy dt, is exactly the change of the peculiar
// kinetic energy plus what collisions and the thermostat took; a checkpoint continues
// bit for bit.
#include "support/sheared_gas.hpp"

#include "pedesis/core/error.hpp"
#include "pedesis/event/event_engine.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <random>
#include <sstream>
#include <string>
#include <vector>

using namespace pedesis;

namespace {

TEST(EventShear, AFreeParticleCrossingTheSlidingFaceLandsWhereTheOffsetPutsIt) {
    // x = 0, y = 4.5 in a 10 x 10 box at rate 0.2; peculiar velocity (0.3, 1): the
    // laboratory velocity is (0.3 + 0.2 * 4.5, 1) = (1.2, 1). At t = 2 the flight is at
    // (2.4, 6.5), past the top face: y wraps to -3.5 and x moves back by the offset
    // 0.2 * 10 * 2 = 4, to -1.6; the laboratory v_x loses 0.2 * 10 = 2, so the peculiar
    // v_x is -0.8 - 0.2 * (-3.5) = -0.1 (as it was just before the face: 1.2 - 0.2 * 6.5).
    ParticleStore<2> p;
    p.species_table = {Species{"A", 0.5, 1.0}};
    p.position = {Vec<2>{{0.0, 4.5}}};
    p.velocity = {Vec<2>{{0.3, 1.0}}};
    p.tag = {0};
    p.species = {0};
    EventEngine<2> e(p, test::sheared_box<2>(10.0, 0.2), EventParams{});
    StopLimits limits;
    limits.time = 2.0;
    ASSERT_EQ(e.run(limits), StopReason::time);
    const ParticleStore<2> s = e.snapshot();
    EXPECT_NEAR(s.position[0][0], -1.6, 1e-12);
    EXPECT_NEAR(s.position[0][1], -3.5, 1e-12);
    EXPECT_NEAR(s.velocity[0][0], -0.1, 1e-12);
    EXPECT_NEAR(s.velocity[0][1], 1.0, 1e-12);
    EXPECT_NEAR(e.box().shear_offset(), 4.0, 1e-12);
    EXPECT_NEAR(e.kinetic_energy(), 0.5 * (0.01 + 1.0), 1e-12);
}

TEST(EventShear, TwoParticlesMeetAcrossTheFaceWhenTheirImagesLineUp) {
    // A at (0, 4.55) and B at (-3, -4.55), both at rest in the flow. B's image above, at
    // height 5.45, drifts along x relative to A at rate * 0.9 = 0.09 from -3; contact (a
    // distance 1 at a height difference 0.9) comes when it is sqrt(0.19) short of A: at
    // t = (3 - sqrt(0.19)) / 0.09 = 28.49..., after the offset has wrapped several times.
    EventEngine<2> e(test::particle_pair<2>(Vec<2>{{0.0, 4.55}}, Vec<2>{{-3.0, -4.55}}),
                     test::sheared_box<2>(10.0, 0.1), EventParams{});
    StopLimits limits;
    limits.pair_collisions = 1;
    limits.time = 100.0;
    ASSERT_EQ(e.run(limits), StopReason::collisions);
    EXPECT_NEAR(e.time(), (3.0 - std::sqrt(0.19)) / 0.09, 1e-9);
    // the same in 3D, across the face below (B above A's image): the roles swapped
    EventEngine<3> f(test::particle_pair<3>(Vec<3>{{-3.0, -4.55, 0.2}}, Vec<3>{{0.0, 4.55, 0.2}}),
                     test::sheared_box<3>(10.0, 0.1), EventParams{});
    ASSERT_EQ(f.run(limits), StopReason::collisions);
    EXPECT_NEAR(f.time(), (3.0 - std::sqrt(0.19)) / 0.09, 1e-9);
}

TEST(EventShear, APairThatOnlyTheSlideBringsTogetherIsListedAheadOfThePass) {
    // Skin 0.1: lists reach 1.1, and the offset may slide by a whole reach, 1.1, between
    // shear passes (10 x 10 box, rate 0.1: one pass per 1.1 time units). A at (0, 4.75)
    // and B at (-1.9, -4.75) are at rest in the laboratory: only the slide moves B's image
    // above, at height 5.25, towards A along x at rate * L_y = 1. Contact (distance 1 at a
    // height difference 0.5) comes at t = 1.9 - sqrt(0.75) = 1.034, before the first pass:
    // B's image, 1.9 away along x at the start, is listed only if the scans across the
    // face reach the slide's allowance beyond the lists' reach.
    ParticleStore<2> p = test::particle_pair<2>(Vec<2>{{0.0, 4.75}}, Vec<2>{{-1.9, -4.75}});
    p.velocity = {Vec<2>{{-0.475, 0.0}}, Vec<2>{{0.475, 0.0}}}; // peculiar: lab velocity 0
    EventParams params;
    params.skin = 0.1;
    EventEngine<2> e(p, test::sheared_box<2>(10.0, 0.1), params);
    StopLimits limits;
    limits.pair_collisions = 1;
    limits.time = 1.5;
    ASSERT_EQ(e.run(limits), StopReason::collisions);
    EXPECT_NEAR(e.time(), 1.9 - std::sqrt(0.75), 1e-9);
}

// The flow's power: d K/dt = -rate V P_xy, with V P_xy = Σ m c_x c_y + the collisions'
// virial, so K(t) - K(0) = -rate G_xy - energy lost - energy the thermostat removed, to
// rounding, whatever happened on the way.
template <int D>
void expect_energy_balance(double rate, double restitution, double thermostat, int n,
                           double spacing, double t_end, bool check_pairs) {
    EventParams params;
    params.restitution = restitution;
    params.check_overlaps = true;
    if (thermostat > 0.0) {
        params.thermostat_temperature = thermostat;
        params.thermostat_interval = 0.37;
    }
    const Box<D> box = test::sheared_box<D>(spacing * n, rate);
    EventEngine<D> e(test::sheared_lattice_gas<D>(n, spacing, 7), box, params);
    const double k0 = e.kinetic_energy();
    StopLimits limits;
    for (int step = 1; step <= 40; ++step) {
        limits.time = t_end * step / 40.0;
        ASSERT_EQ(e.run(limits), StopReason::time);
        if (check_pairs) {
            ASSERT_GE(test::closest_approach(e.snapshot(), e.box()), 1.0 - 1e-9)
                << "t = " << e.time();
        }
    }
    const double g_xy = e.flux_moments().kinetic_integral[3] + e.counters().virial[3];
    const double balance = k0 - rate * g_xy - e.counters().energy_lost -
                           e.thermostat().energy_removed - e.kinetic_energy();
    EXPECT_NEAR(balance, 0.0, 1e-9 * k0) << "K0 " << k0 << ", rate G_xy " << rate * g_xy;
    EXPECT_GT(e.counters().pair_collisions, 20u * e.size());
    EXPECT_GT(-rate * g_xy, 0.01 * k0); // the flow did feed in energy
    if (thermostat > 0.0) {
        EXPECT_GT(e.thermostat().rescales, 10u);
    }
}

TEST(EventShear, TheFlowFeedsInExactlyThePowerOfTheShearStress2D) {
    // 144 disks on a square lattice (cell faces hold particles), strongly sheared
    expect_energy_balance<2>(1.0, 1.0, 0.0, 12, 1.25, 12.0, true);
}

TEST(EventShear, TheFlowFeedsInExactlyThePowerOfTheShearStress3D) {
    expect_energy_balance<3>(0.5, 1.0, 0.0, 6, 1.4, 8.0, true);
}

TEST(EventShear, ThermostatAndInelasticCollisionsBalanceTheViscousHeating) {
    expect_energy_balance<3>(0.3, 1.0, 1.0, 6, 1.3, 20.0, false);
    expect_energy_balance<2>(0.5, 0.8, 0.0, 12, 1.25, 20.0, false);
}

// The lists' skin changes which pairs are listed and when lists are rebuilt, never the
// dynamics: two runs with different skins follow the same trajectory until rounding
// errors grow. A pair across the sliding faces missed by a list (a scan too short along
// x, a slide allowance too small) collides in one run and not in the other.
template <int D> void expect_same_trajectory_for_two_skins(int n, double spacing, double rate) {
    EventParams thin, thick;
    const double room = 0.5 * spacing * n - 1.0; // between the contact and half the box
    thin.skin = 0.08 * room;
    thick.skin = 0.38 * room; // near choose_skin's cap, 0.4 of the room
    const Box<D> box = test::sheared_box<D>(spacing * n, rate);
    EventEngine<D> a(test::sheared_lattice_gas<D>(n, spacing, 9), box, thin);
    EventEngine<D> b(test::sheared_lattice_gas<D>(n, spacing, 9), box, thick);
    ASSERT_LT(a.skin(), 0.5 * b.skin());
    StopLimits limits;
    limits.time = 0.8;
    a.run(limits);
    b.run(limits);
    EXPECT_EQ(a.counters().pair_collisions, b.counters().pair_collisions);
    EXPECT_GT(a.counters().pair_collisions, 2u * a.size());
    const ParticleStore<D> sa = a.snapshot(), sb = b.snapshot();
    for (std::size_t i = 0; i < sa.size(); ++i) {
        // storage orders may differ: compare by tag
        std::size_t k = 0;
        while (sb.tag[k] != sa.tag[i]) ++k;
        // (rounding grows by chaos to about 1e-6 here; a missed collision is order 0.1)
        ASSERT_LT(norm(box.minimum_image(sa.position[i] - sb.position[k])), 1e-3) << sa.tag[i];
        ASSERT_LT(norm(sa.velocity[i] - sb.velocity[k]), 1e-3) << sa.tag[i];
    }
}

TEST(EventShear, TheSkinDoesNotChangeTheTrajectory) {
    expect_same_trajectory_for_two_skins<2>(16, 1.2, 2.0);
    expect_same_trajectory_for_two_skins<3>(7, 1.25, 2.0);
}

TEST(EventShear, TheThermostatHoldsThePeculiarTemperature) {
    EventParams params;
    params.thermostat_temperature = 2.0;
    params.thermostat_interval = 0.25;
    EventEngine<3> e(test::sheared_lattice_gas<3>(6, 1.4, 3), test::sheared_box<3>(8.4, 0.5),
                     params);
    StopLimits limits;
    limits.time = 10.0;
    ASSERT_EQ(e.run(limits), StopReason::time);
    // at a rescaling (t = 10 is one: 40 intervals) the temperature is the thermostat's:
    // 2 K / (3 N - 3) of the peculiar velocities less their mean
    const ParticleStore<3> s = e.snapshot();
    Vec<3> mean{};
    for (const auto& v : s.velocity) mean += v * (1.0 / s.size());
    double k = 0.0;
    for (const auto& v : s.velocity) k += 0.5 * norm2(v - mean);
    EXPECT_NEAR(2.0 * k / (3.0 * s.size() - 3.0), 2.0, 1e-9);
    EXPECT_EQ(e.thermostat().rescales, 40u);
}

TEST(EventShear, ACheckpointContinuesBitForBit) {
    EventParams params;
    params.thermostat_temperature = 1.0;
    params.thermostat_interval = 0.3;
    EventEngine<3> a(test::sheared_lattice_gas<3>(6, 1.3, 5), test::sheared_box<3>(7.8, 0.4),
                     params);
    StopLimits limits;
    limits.time = 3.1;
    a.run(limits);
    std::ostringstream out;
    a.save(out);
    std::istringstream in(out.str());
    EventEngine<3> b = EventEngine<3>::load(in, params);
    EXPECT_EQ(b.box().shear_rate(), 0.4);
    limits.time = 9.0;
    a.run(limits);
    b.run(limits);
    EXPECT_EQ(a.counters().pair_collisions, b.counters().pair_collisions);
    const ParticleStore<3> sa = a.snapshot(), sb = b.snapshot();
    for (std::size_t i = 0; i < sa.size(); ++i)
        for (int c = 0; c < 3; ++c) {
            ASSERT_EQ(sa.position[i][c], sb.position[i][c]) << i;
            ASSERT_EQ(sa.velocity[i][c], sb.velocity[i][c]) << i;
        }
    EXPECT_EQ(a.thermostat().energy_removed, b.thermostat().energy_removed);
}

TEST(EventShear, RefusesGrowthAndWallsAcrossTheFlow) {
    EventParams growing;
    growing.growth_rate = 0.1;
    EXPECT_THROW(EventEngine<2>(test::sheared_lattice_gas<2>(8, 1.5, 1),
                                test::sheared_box<2>(12.0, 0.1), growing),
                 InputError);
    Box<2> walled(Vec<2>{{12.0, 12.0}}, {true, false});
    EXPECT_THROW(walled.set_shear_rate(0.1), InputError);
    EventParams cold;
    cold.thermostat_temperature = 1.0;
    cold.thermostat_interval = 0.0;
    EXPECT_THROW(EventEngine<2>(test::sheared_lattice_gas<2>(8, 1.5, 1),
                                test::sheared_box<2>(12.0, 0.1), cold),
                 InputError);
}

} // namespace
