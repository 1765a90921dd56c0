// Checkpoint and restart with gravity, the Andersen thermostat and the white-noise
// driving, bit for bit (as restart_test.cpp for the plain engine): running to 2T in one
// go gives the same state as running to T, saving, loading and running on. The random
// numbers of the stochastic events are keyed by their count (not drawn from a stream
// that would have to be saved), and the next event's time is saved: an engine that
// redrew it at the restart would diverge at once.
#include "pedesis/core/error.hpp"
#include "pedesis/event/event_engine.hpp"
#include "support/falling_gas.hpp"
#include "support/gas_builder.hpp"

#include <gtest/gtest.h>

#include <sstream>

using namespace pedesis;
using namespace pedesis::test;

namespace {

template <int D> void expect_same(const EventEngine<D>& a, const EventEngine<D>& b) {
    EXPECT_TRUE(same_bits(a.time(), b.time()));
    EXPECT_EQ(a.counters().pair_collisions, b.counters().pair_collisions);
    EXPECT_EQ(a.counters().wall_collisions, b.counters().wall_collisions);
    EXPECT_EQ(a.driving().andersen_events, b.driving().andersen_events);
    EXPECT_EQ(a.driving().kicks, b.driving().kicks);
    EXPECT_TRUE(same_bits(a.driving().injected_energy, b.driving().injected_energy));
    EXPECT_TRUE(same_bits(a.kinetic_energy(), b.kinetic_energy()));
    EXPECT_TRUE(same_bits(a.potential_energy(), b.potential_energy()));
    const auto sa = a.snapshot(), sb = b.snapshot();
    ASSERT_EQ(sa.size(), sb.size());
    std::size_t bad = 0;
    for (std::size_t i = 0; i < sa.size(); ++i)
        bad += !same_bits(sa.position[i], sb.position[i]) ||
               !same_bits(sa.velocity[i], sb.velocity[i]);
    EXPECT_EQ(bad, 0u) << "particles differing in at least one bit";
    std::stringstream ca, cb;
    a.save(ca);
    b.save(cb);
    EXPECT_TRUE(ca.str() == cb.str()) << "the checkpoints differ";
}

template <int D>
void restart_case(const Gas<D>& gas, const EventParams& params, double half,
                  std::uint64_t min_collisions) {
    EventEngine<D> one(gas.particles, gas.box, params);
    StopLimits lim;
    lim.time = 2.0 * half;
    one.run(lim);
    EXPECT_GT(one.counters().pair_collisions, min_collisions);

    EventEngine<D> first(gas.particles, gas.box, params);
    lim.time = half;
    first.run(lim);
    std::stringstream buffer;
    first.save(buffer);
    EventEngine<D> second = EventEngine<D>::load(buffer, params);
    lim.time = 2.0 * half;
    second.run(lim);
    expect_same(one, second);
}

} // namespace

TEST(DrivenRestart, GravityBitForBit2D) {
    EventParams params;
    params.gravity = {0.0, -1.0, 0.0};
    params.restitution = 0.8; // a settling bed: many collisions near the floor
    params.tc = 0.01;
    restart_case<2>(falling_gas<2>(300, Vec<2>{30.0, 40.0}, 0.5, 7), params, 10.0, 3000);
}

TEST(DrivenRestart, GravityBitForBit3D) {
    EventParams params;
    params.gravity = {0.0, 0.0, -0.5};
    restart_case<3>(falling_gas<3>(300, Vec<3>{10.0, 10.0, 20.0}, 0.5, 9), params, 8.0, 2000);
}

TEST(DrivenRestart, AndersenBitForBit) {
    auto spec = equal_gas<2>(400, 0.3, true, 3);
    EventParams params;
    params.andersen_rate = 0.5;
    params.andersen_temperature = 1.5;
    restart_case<2>(make_gas(spec), params, 3.0, 2000);
}

TEST(DrivenRestart, WhiteNoiseDrivingBitForBit) {
    auto spec = equal_gas<3>(300, 0.2, true, 4);
    EventParams params;
    params.restitution = 0.9;
    params.driving_rate = 2.0;
    params.driving_strength = 0.1;
    restart_case<3>(make_gas(spec), params, 3.0, 2000);
}

TEST(DrivenRestart, ACheckpointWithOtherGravityIsRefused) {
    auto gas = falling_gas<2>(50, Vec<2>{20.0, 20.0}, 0.5, 1);
    EventParams params;
    params.gravity = {0.0, -1.0, 0.0};
    EventEngine<2> e(gas.particles, gas.box, params);
    std::stringstream buffer;
    e.save(buffer);
    params.gravity = {0.0, -2.0, 0.0};
    EXPECT_THROW(EventEngine<2>::load(buffer, params), InputError);
}
