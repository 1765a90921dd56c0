// Inelastic collapse and the TC model. With restitution 0.5 a dense 2D gas collapses
// (infinitely many collisions in finite time); the TC model (collisions within tc of a
// particle's previous one are elastic) must prevent it. Without it the engine must
// either keep running or stop with a RunError that says "inelastic collapse" - never
// overlap, hang or fail in any other way. (Which of the two happens depends on
// rounding, so that is all the test asserts for tc = 0; with this engine the 2D systems
// below do collapse without the TC model, so the TC tests are not vacuous.)
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

template <int D> void without_tc_runs_or_reports_collapse(bool periodic, std::uint64_t seed) {
    auto gas = make_gas(equal_gas<D>(D == 2 ? 1000 : 500, D == 2 ? 0.6 : 0.4, periodic, seed));
    EventEngine<D> e(gas.particles, gas.box, inelastic(0.0));
    try {
        e.run(cooling_limits(e.kinetic_energy()));
        std::printf("no collapse within the limits (%llu collisions)\n",
                    static_cast<unsigned long long>(e.counters().pair_collisions));
        EXPECT_NO_THROW(e.check_no_overlap());
    } catch (const RunError& err) {
        const std::string m = err.what();
        std::printf("collapse reported after %llu collisions: %s\n",
                    static_cast<unsigned long long>(e.counters().pair_collisions), m.c_str());
        EXPECT_NE(m.find("inelastic collapse"), std::string::npos) << m;
        EXPECT_EQ(m.find("overlap"), std::string::npos) << m;
    } catch (const std::exception& err) {
        ADD_FAILURE() << "unexpected exception type: " << err.what();
    }
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
TEST(InelasticCollapse, WithoutTcRunsOrReportsCollapse2D) {
    without_tc_runs_or_reports_collapse<2>(true, 1);
}
TEST(InelasticCollapse, WithoutTcRunsOrReportsCollapseWalled2D) {
    without_tc_runs_or_reports_collapse<2>(false, 2);
}
TEST(InelasticCollapse, WithoutTcRunsOrReportsCollapse3D) {
    without_tc_runs_or_reports_collapse<3>(true, 3);
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
