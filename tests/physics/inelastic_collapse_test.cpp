// Inelastic collapse and the TC model. With restitution 0.5 a dense 2D gas collapses
// (infinitely many collisions in finite time); the TC model (collisions within tc of a
// particle's previous one are elastic) must prevent it.
//
// Without the TC model the 2D gases below must collapse, and the engine must say so: it
// stops with a RunError that says "inelastic collapse" (EventEngine::run counts events
// at one instant and throws once there are more than 1000 + 200 N of them) - never an
// overlap, a hang, a silent stop at the collision limit or another exception. Collapse
// itself is physics, not rounding: at packing fraction 0.6 with restitution 0.5 it came
// for every seed tried (periodic, N = 1000: seeds 1-40, the latest after 805k pair
// collisions counting the 201k at the final instant, seed 1 after 285k; walled: seeds
// 1-12, all after at most 235k, seed 2 after 228k). Which collision starts it depends
// on rounding, so the limit of 3M collisions leaves a factor of ~4 over the latest seed
// and ~10 over the seeds used here. A run that reached the limit would take ~2 s; a
// collapse takes ~0.1 s.
//
// In 3D (N = 500, packing fraction 0.4) the same gas does not collapse: it cools by 10
// orders of magnitude in ~150 collisions per particle (seeds 1-8 tried), so the 3D case
// without TC only asserts that the engine either runs to the limits or reports
// collapse, and fails on an overlap or any other error.
#include "pedesis/core/error.hpp"
#include "pedesis/event/event_engine.hpp"
#include "support/gas_builder.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <string>

using namespace pedesis;
using namespace pedesis::test;

namespace {

EventParams inelastic(double tc) {
    EventParams p;
    p.restitution = 0.5;
    p.wall_restitution = 0.5;
    p.tc = tc;
    p.check_overlaps = true;
    return p;
}

// The run stops after 600k collisions or once the gas has cooled by 10 orders of
// magnitude: beyond that, Haff cooling makes the time between collisions grow without
// bound while the (rounding-level) centre-of-mass drift keeps the neighbour lists busy.
StopLimits cooling_limits(double e0) {
    StopLimits lim;
    lim.pair_collisions = 600'000;
    lim.min_kinetic_energy = 1e-10 * e0;
    return lim;
}

template <int D> void tc_prevents_collapse(bool periodic, std::uint64_t seed) {
    auto gas = make_gas(equal_gas<D>(D == 2 ? 1000 : 500, D == 2 ? 0.6 : 0.4, periodic, seed));
    // mean free time at the start ~0.08 (2D) / 0.05 (3D): tc is ~1% of it
    EventEngine<D> e(gas.particles, gas.box, inelastic(1e-3));
    const double e0 = e.kinetic_energy();
    StopReason why = StopReason::no_events;
    EXPECT_NO_THROW(why = e.run(cooling_limits(e0)));
    EXPECT_TRUE(why == StopReason::collisions || why == StopReason::energy);
    EXPECT_GT(e.counters().pair_collisions, 50 * gas.particles.size());
    EXPECT_NO_THROW(e.check_no_overlap());
    const auto s = e.snapshot();
    // strongly cooled, and the energy is accounted for
    EXPECT_LT(kinetic_energy(s), 0.01 * e0);
    EXPECT_NEAR(kinetic_energy(s), e.kinetic_energy(), 1e-9 * e0);
    EXPECT_NEAR(e.kinetic_energy() + e.counters().energy_lost, e0, 1e-9 * e0);
    if (periodic) {
        EXPECT_LT(norm(total_momentum(s)), 1e-9 * momentum_scale(gas.particles));
    }
}

// Runs the gas without the TC model; the RunError's message, or "" when the run ended
// without one (any other exception fails the test).
template <int D> std::string run_without_tc(bool periodic, std::uint64_t seed, StopLimits lim) {
    auto gas = make_gas(equal_gas<D>(D == 2 ? 1000 : 500, D == 2 ? 0.6 : 0.4, periodic, seed));
    EventEngine<D> e(gas.particles, gas.box, inelastic(0.0));
    const double e0 = e.kinetic_energy();
    lim.min_kinetic_energy = 1e-10 * e0;
    std::string message;
    try {
        e.run(lim);
        std::printf("no collapse within the limits (%llu collisions)\n",
                    static_cast<unsigned long long>(e.counters().pair_collisions));
    } catch (const RunError& err) {
        message = err.what();
        std::printf("collapse reported after %llu collisions: %s\n",
                    static_cast<unsigned long long>(e.counters().pair_collisions), message.c_str());
        // collapse is not an overlap, and the engine's state stays consistent: no pair
        // overlaps, and the energy lost is accounted for
        EXPECT_EQ(message.find("overlap"), std::string::npos) << message;
        EXPECT_LT(e.counters().pair_collisions, lim.pair_collisions);
        EXPECT_NEAR(e.kinetic_energy() + e.counters().energy_lost, e0, 1e-9 * e0);
    } catch (const std::exception& err) {
        ADD_FAILURE() << "unexpected exception type: " << err.what();
        return message;
    }
    EXPECT_NO_THROW(e.check_no_overlap());
    return message;
}

// 2D: the collapse must come, and be reported as such.
void without_tc_collapses_2d(bool periodic, std::uint64_t seed) {
    StopLimits lim;
    lim.pair_collisions = 3'000'000;
    const std::string m = run_without_tc<2>(periodic, seed, lim);
    ASSERT_FALSE(m.empty()) << "the dense inelastic 2D gas (seed " << seed
                            << ") did not collapse within " << lim.pair_collisions
                            << " collisions, or the engine did not detect it";
    EXPECT_NE(m.find("inelastic collapse"), std::string::npos) << m;
    EXPECT_NE(m.find("event.tc"), std::string::npos) << "the message should name the remedy: " << m;
}

} // namespace

TEST(InelasticCollapse, TcModelPreventsCollapse2D) {
    tc_prevents_collapse<2>(true, 1);
}
TEST(InelasticCollapse, TcModelPreventsCollapseWalled2D) {
    tc_prevents_collapse<2>(false, 2);
}
TEST(InelasticCollapse, TcModelPreventsCollapse3D) {
    tc_prevents_collapse<3>(true, 3);
}
TEST(InelasticCollapse, WithoutTcCollapses2D) {
    without_tc_collapses_2d(true, 1);
}
TEST(InelasticCollapse, WithoutTcCollapsesWalled2D) {
    without_tc_collapses_2d(false, 2);
}
TEST(InelasticCollapse, WithoutTcRunsOrReportsCollapse3D) {
    StopLimits lim;
    lim.pair_collisions = 600'000;
    const std::string m = run_without_tc<3>(true, 3, lim);
    if (!m.empty()) {
        EXPECT_NE(m.find("inelastic collapse"), std::string::npos) << m;
    }
}

TEST(InelasticCollapse, StickyPairStaysTogetherWithoutEvents) {
    // restitution 0: a head-on pair ends with zero relative velocity in contact and must
    // then move on together without further collisions or a false collapse report
    ParticleStore<2> p;
    p.species_table = {Species{"A", 0.5, 1.0}};
    p.resize(2);
    p.position = {Vec<2>{{-1.0, 0.0}}, Vec<2>{{1.0, 0.0}}};
    p.velocity = {Vec<2>{{1.0, 0.2}}, Vec<2>{{-1.0, 0.2}}};
    p.tag = {0, 1};
    p.species = {0, 0};
    EventParams params;
    params.restitution = 0.0;
    params.check_overlaps = true;
    EventEngine<2> e(p, Box<2>(Vec<2>{{20.0, 20.0}}, {true, true}), params);
    StopLimits lim;
    lim.time = 200.0;
    EXPECT_NO_THROW(e.run(lim));
    EXPECT_EQ(e.counters().pair_collisions, 1u);
    const auto s = e.snapshot();
    EXPECT_NEAR(norm(s.velocity[0] - s.velocity[1]), 0.0, 1e-15);
    EXPECT_NEAR(norm(e.box().minimum_image(s.position[0] - s.position[1])), 1.0, 1e-12);
}

TEST(InelasticCollapse, TrackedKineticEnergyStaysAccurateWhenCooledDeeply) {
    // kinetic_energy() is what a user plots for T(t) (Haff's law spans many decades) and
    // what StopLimits::min_kinetic_energy compares with. After the gas has cooled by many
    // orders of magnitude it must still be the kinetic energy of the particles: never
    // negative, and the sum of m v^2 / 2 to rounding. Smallest case: two disks colliding
    // head-on again and again through the periodic boundary, restitution 0.3, so the
    // energy falls by 0.09 per collision (1e-21 after 20 collisions).
    ParticleStore<2> p;
    p.species_table = {Species{"A", 0.5, 1.0}};
    p.resize(2);
    p.position = {Vec<2>{{-1.0, 0.0}}, Vec<2>{{1.0, 0.0}}};
    p.velocity = {Vec<2>{{1.0, 0.0}}, Vec<2>{{-1.0, 0.0}}};
    p.tag = {0, 1};
    p.species = {0, 0};
    EventParams params;
    params.restitution = 0.3;
    EventEngine<2> e(p, Box<2>(Vec<2>{{10.0, 10.0}}, {true, true}), params);
    for (std::uint64_t c : {5u, 10u, 15u, 20u}) {
        StopLimits lim;
        lim.pair_collisions = c;
        EXPECT_NO_THROW(e.run(lim));
        ASSERT_EQ(e.counters().pair_collisions, c);
        const double true_ke = kinetic_energy(e.snapshot());
        EXPECT_NEAR(true_ke, std::pow(0.09, static_cast<double>(c)), 1e-9 * true_ke); // closed form
        EXPECT_GE(e.kinetic_energy(), 0.0) << "after " << c << " collisions";
        EXPECT_NEAR(e.kinetic_energy(), true_ke, 1e-6 * true_ke)
            << "after " << c << " collisions: tracked " << e.kinetic_energy()
            << " vs sum of m v^2 / 2 " << true_ke;
    }
}
