// The stepped engine against exact answers: few-body situations in which every collision
// lasts (as an overlap) to the end of its step, so the engine must reproduce the exact
// event-driven dynamics to rounding, whatever the order and number of events in one
// step: a head-on collision, unequal masses and radii at an angle, a chain of collisions
// within one step, a particle that hits a neighbour before the wall it was heading for,
// a corner, a periodic face. The event engine (itself checked against closed forms in
// exact_collisions_test) is the reference where there is no closed form.
#include "pedesis/event/event_engine.hpp"
#include "pedesis/stepped/stepped_engine.hpp"
#include "pedesis/stepped/time_step.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <string>
#include <vector>

using namespace pedesis;

namespace {

template <int D> struct Body {
    Vec<D> r, v;
    int species;
};

template <int D>
ParticleStore<D> store(const std::vector<Species>& table, const std::vector<Body<D>>& bodies) {
    ParticleStore<D> p;
    p.species_table = table;
    p.resize(bodies.size());
    for (std::size_t i = 0; i < bodies.size(); ++i) {
        p.position[i] = bodies[i].r;
        p.velocity[i] = bodies[i].v;
        p.tag[i] = static_cast<std::uint32_t>(i);
        p.species[i] = static_cast<std::uint16_t>(bodies[i].species);
    }
    return p;
}

// Runs both engines to steps x dt and compares every particle's position and velocity.
template <int D>
SteppedEngine<D> expect_same_as_event(const ParticleStore<D>& p, const Box<D>& box, double dt,
                                      int steps, double tol = 1e-12) {
    EventEngine<D> ev(p, box, EventParams{});
    StopLimits lim;
    lim.time = dt * steps;
    ev.run(lim);
    const ParticleStore<D> want = ev.snapshot();
    SteppedParams params;
    params.dt = dt;
    params.max_move = 1.0;
    SteppedEngine<D> st(p, box, params);
    for (int k = 0; k < steps; ++k) st.step();
    const ParticleStore<D>& got = st.particles();
    // (each engine keeps its own storage order: matched by tag)
    const std::vector<std::uint32_t> gi = got.index_of_tags(), wi = want.index_of_tags();
    for (std::size_t t = 0; t < p.size(); ++t) {
        const Vec<D> dr = box.minimum_image(got.position[gi[t]] - want.position[wi[t]]);
        EXPECT_LT(norm(dr), tol) << "position of particle " << t;
        EXPECT_LT(norm(got.velocity[gi[t]] - want.velocity[wi[t]]), tol)
            << "velocity of particle " << t;
    }
    EXPECT_EQ(st.counters().pair_collisions, ev.counters().pair_collisions);
    EXPECT_EQ(st.counters().wall_collisions, ev.counters().wall_collisions);
    for (int a = 0; a < D; ++a)
        for (int s = 0; s < 2; ++s)
            EXPECT_NEAR(st.counters().wall_impulse[a][s], ev.counters().wall_impulse[a][s], tol);
    EXPECT_EQ(st.stats().late_collisions, 0u);
    return st;
}

Box<2> square(double L, bool periodic) {
    return Box<2>(Vec<2>::filled(L), {periodic, periodic});
}

} // namespace

TEST(SteppedExact, HeadOnEqualMassesSwapWithinOneStep) {
    // contact at t = 0.1 inside a step of 0.25; afterwards each carries the other's velocity
    const std::vector<Species> t{{"A", 0.5, 1.0}};
    const auto p =
        store<2>(t, {{{{-0.6, 0.0}}, {{1.0, 0.0}}, 0}, {{{0.6, 0.0}}, {{-1.0, 0.0}}, 0}});
    SteppedParams params;
    params.dt = 0.25;
    SteppedEngine<2> e(p, square(10.0, false), params);
    e.step();
    EXPECT_NEAR(e.particles().velocity[0][0], -1.0, 1e-15);
    EXPECT_NEAR(e.particles().velocity[1][0], 1.0, 1e-15);
    // at contact (t = 0.1) at -0.5 and 0.5, then 0.15 back
    EXPECT_NEAR(e.particles().position[0][0], -0.65, 1e-15);
    EXPECT_NEAR(e.particles().position[1][0], 0.65, 1e-15);
    EXPECT_EQ(e.counters().pair_collisions, 1u);
    // virial: J n . r_ij = (2 mu g) sigma = 2 x 0.5 x 2 x 1
    EXPECT_NEAR(e.counters().virial[0], 2.0, 1e-14);
}

TEST(SteppedExact, UnequalMassesAndRadiiAtAnAngle) {
    const std::vector<Species> t{{"light", 0.3, 1.0}, {"heavy", 1.1, 7.5}};
    const auto p =
        store<2>(t, {{{{-2.0, 0.9}}, {{3.0, -0.4}}, 0}, {{{1.0, 0.0}}, {{-0.5, 0.3}}, 1}});
    for (double dt : {0.02, 0.04, 0.07}) expect_same_as_event<2>(p, square(12.0, false), dt, 8);
}

TEST(SteppedExact, ChainOfCollisionsWithinOneStep) {
    // A hits B (at t = 0.025), then B hits C (0.044), then C hits D (0.06), all within the
    // first step of 0.1
    const std::vector<Species> t{{"A", 0.5, 1.0}, {"B", 0.5, 2.0}};
    const auto p = store<2>(t, {{{{-2.2, 0.0}}, {{4.0, 0.0}}, 0},
                                {{{-1.1, 0.05}}, {{0.0, 0.0}}, 1},
                                {{{-0.05, 0.0}}, {{0.0, 0.0}}, 0},
                                {{{1.0, -0.1}}, {{0.0, 0.0}}, 1}});
    const auto e = expect_same_as_event<2>(p, square(20.0, false), 0.1, 3);
    EXPECT_GE(e.counters().pair_collisions, 3u);
    EXPECT_GE(e.stats().most_events_in_step, 2u);
}

TEST(SteppedExact, NeighbourBeforeTheWall) {
    // A heads for the right wall (it would reach it at t = 0.1) but B hits it first, at
    // t = 0.05, which changes when A reaches the wall (0.106), in the same step of 0.11:
    // the wall must not be applied before the collision
    const std::vector<Species> t{{"A", 0.5, 1.0}};
    const double L = 6.0;
    const auto p =
        store<2>(t, {{{{2.3, 0.0}}, {{2.0, 0.0}}, 0}, {{{2.45, 1.2}}, {{0.0, -4.0}}, 0}});
    expect_same_as_event<2>(p, square(L, false), 0.11, 4);
}

TEST(SteppedExact, CornerAndFullCircuitOfAWalledBox) {
    // v = (v0, v0) from the centre of a walled square comes back after 2 (L - 2r) / v0,
    // having hit each wall once; two walls are hit in one step at the corner
    const std::vector<Species> t{{"A", 0.5, 1.0}};
    const double L = 5.0, v0 = 1.3;
    const auto p = store<2>(t, {{{{0.0, 0.0}}, {{v0, v0}}, 0}});
    const double period = 2.0 * (L - 1.0) / v0;
    const int steps = 250;
    SteppedParams params;
    params.dt = period / steps;
    SteppedEngine<2> e(p, square(L, false), params);
    for (int k = 0; k < steps; ++k) e.step();
    EXPECT_NEAR(e.particles().position[0][0], 0.0, 1e-12);
    EXPECT_NEAR(e.particles().position[0][1], 0.0, 1e-12);
    EXPECT_NEAR(e.particles().velocity[0][0], v0, 1e-15);
    EXPECT_EQ(e.counters().wall_collisions, 4u);
    for (int a = 0; a < 2; ++a)
        for (int s = 0; s < 2; ++s) EXPECT_NEAR(e.counters().wall_impulse[a][s], 2.0 * v0, 1e-14);
    // the corner itself, in 3D, with the event engine as reference
    const std::vector<Species> t3{{"A", 0.5, 1.0}};
    ParticleStore<3> one;
    one.species_table = t3;
    one.resize(1);
    one.position[0] = Vec<3>{{1.3, 1.3, 1.3}};
    one.velocity[0] = Vec<3>{{1.0, 1.0, 1.0}};
    one.tag[0] = 0;
    one.species[0] = 0;
    expect_same_as_event<3>(one, Box<3>(Vec<3>::filled(4.0), {false, false, false}), 0.25, 7);
}

TEST(SteppedExact, CollisionAcrossAPeriodicFace) {
    const std::vector<Species> t{{"A", 0.5, 1.0}, {"B", 0.7, 3.0}};
    const auto p =
        store<2>(t, {{{{4.4, 0.2}}, {{1.5, 0.0}}, 0}, {{{-4.3, -0.1}}, {{-0.5, 0.1}}, 1}});
    expect_same_as_event<2>(p, square(10.0, true), 0.13, 10);
}

TEST(SteppedExact, SphereClusterIn3D) {
    const std::vector<Species> t{{"A", 0.5, 1.0}, {"B", 0.8, 2.5}};
    const auto p = store<3>(t, {{{{-1.5, 0.1, 0.0}}, {{2.0, 0.0, 0.1}}, 0},
                                {{{0.0, 0.0, 0.0}}, {{0.0, 0.0, 0.0}}, 1},
                                {{{1.2, 0.9, -0.3}}, {{-0.4, -0.6, 0.0}}, 0}});
    expect_same_as_event<3>(p, Box<3>(Vec<3>::filled(8.0), {false, true, false}), 0.2, 10);
}

TEST(SteppedExact, TooFastAParticleStopsTheStepAndNamesIt) {
    const std::vector<Species> t{{"A", 0.5, 1.0}};
    // particle 1 moves 0.3 per step of 0.1: 0.6 radii, over max_move = 0.5
    const auto p = store<2>(t, {{{{0.0, 0.0}}, {{0.1, 0.0}}, 0}, {{{2.0, 0.0}}, {{0.0, 3.0}}, 0}});
    SteppedParams params;
    params.dt = 0.1;
    SteppedEngine<2> e(p, square(10.0, false), params);
    try {
        e.step();
        FAIL() << "no error";
    } catch (const RunError& err) {
        const std::string m = err.what();
        EXPECT_NE(m.find("at step 0 particle 1"), std::string::npos) << m;
        EXPECT_NE(m.find("0.6 radii"), std::string::npos) << m;
        EXPECT_NE(m.find("reduce [stepped] dt to"), std::string::npos) << m;
    }
    EXPECT_EQ(e.particles().position[1][1], 0.0) << "nothing moves before the check";
    const FastestParticle f = fastest_particle(p, 0.1);
    EXPECT_EQ(f.index, 1u);
    EXPECT_NEAR(f.radii_per_step, 0.6, 1e-12);
    // K = 4.505, T = 2.2525; for 2 samples the tail speed sqrt(2 (ln 2 + 6) T) = 5.491
    // exceeds both speeds: 0.5 x 0.5 / 5.491 = 0.0455, rounded down to 0.045
    EXPECT_DOUBLE_EQ(suggested_time_step(p, 0.5, 2.0), 0.045);
    // one fast particle among 1000 at rest: T = 0.05, the tail speed for 1001 samples is
    // sqrt(2 (ln 1001 + 6) 0.05) = 1.14, so the fast one sets 0.5 x 0.5 / 10
    ParticleStore<2> many;
    many.species_table = t;
    many.resize(1001);
    for (std::uint32_t i = 0; i < 1001; ++i) {
        many.position[i] = Vec<2>{{static_cast<double>(i), 0.0}};
        many.velocity[i] = Vec<2>{};
        many.tag[i] = i;
        many.species[i] = 0;
    }
    many.velocity[7] = Vec<2>{{6.0, 8.0}};
    EXPECT_DOUBLE_EQ(suggested_time_step(many, 0.5, 1001.0), 0.025);
}

TEST(SteppedExact, BadStatesAreInputErrors) {
    const std::vector<Species> t{{"A", 0.5, 1.0}};
    SteppedParams params;
    params.dt = 0.1;
    EXPECT_THROW(SteppedEngine<2>(store<2>(t, {{{{0.0, 0.0}}, {{0.0, 0.0}}, 0},
                                               {{{0.9, 0.0}}, {{0.0, 0.0}}, 0}}),
                                  square(10.0, false), params),
                 InputError);
    EXPECT_THROW(SteppedEngine<2>(store<2>(t, {{{{4.8, 0.0}}, {{0.0, 0.0}}, 0}}),
                                  square(10.0, false), params),
                 InputError);
    EXPECT_THROW(
        SteppedEngine<2>(
            store<2>(t, {{{{0.0, 0.0}}, {{std::numeric_limits<double>::quiet_NaN(), 0.0}}, 0}}),
            square(10.0, false), params),
        InputError);
    params.dt = 0.0;
    EXPECT_THROW(SteppedEngine<2>(store<2>(t, {{{{0.0, 0.0}}, {{0.0, 0.0}}, 0}}),
                                  square(10.0, false), params),
                 InputError);
}
