// Checkpoint and restart, bit for bit: running to 2T in one go must give exactly the
// same state (memcmp-equal doubles) as running to T, saving to a stream, loading and
// running to 2T; in 2D and 3D, periodic and walled, elastic and inelastic with the TC
// model (tc ~ 20-40% of the mean free time at the restart, so that many collisions right after the
// restart depend on the saved per-particle collision clocks; checked by mutation: an
// engine that does not save them fails these tests). ~20 collisions per particle in each half, so
// any state the checkpoint leaves out (event calendar, neighbour lists, per-particle times,
// counters, TC clocks) would change the trajectory and be caught: hard-particle dynamics is
// chaotic, and one different bit grows to O(1) within a few collision times.
#include "pedesis/core/error.hpp"
#include "pedesis/event/event_engine.hpp"
#include "support/event_lists.hpp"
#include "support/gas_builder.hpp"

#include <gtest/gtest.h>

#include <cstring>
#include <limits>
#include <sstream>
#include <string>

using namespace pedesis;
using namespace pedesis::test;

namespace {

template <int D> void expect_same_counters(const EventCounters<D>& a, const EventCounters<D>& b) {
    EXPECT_EQ(a.pair_collisions, b.pair_collisions);
    EXPECT_EQ(a.wall_collisions, b.wall_collisions);
    EXPECT_EQ(a.list_rebuilds, b.list_rebuilds);
    EXPECT_EQ(a.stale_events, b.stale_events);
    EXPECT_TRUE(same_bits(a.virial, b.virial));
    for (int k = 0; k < D; ++k)
        for (int side = 0; side < 2; ++side)
            EXPECT_TRUE(same_bits(a.wall_impulse[k][side], b.wall_impulse[k][side]));
    EXPECT_TRUE(same_bits(a.energy_lost, b.energy_lost));
}

template <int D> void expect_same_state(const EventEngine<D>& a, const EventEngine<D>& b) {
    EXPECT_TRUE(same_bits(a.time(), b.time()));
    EXPECT_TRUE(same_bits(a.kinetic_energy(), b.kinetic_energy()));
    EXPECT_TRUE(same_bits(a.packing_fraction(), b.packing_fraction()));
    EXPECT_EQ(a.growth().steps, b.growth().steps);
    expect_same_counters(a.counters(), b.counters());
    const auto sa = a.snapshot(), sb = b.snapshot();
    ASSERT_EQ(sa.size(), sb.size());
    std::size_t bad_r = 0, bad_v = 0;
    for (std::size_t i = 0; i < sa.size(); ++i) {
        EXPECT_EQ(sa.tag[i], sb.tag[i]);
        EXPECT_EQ(sa.species[i], sb.species[i]);
        bad_r += !same_bits(sa.position[i], sb.position[i]);
        bad_v += !same_bits(sa.velocity[i], sb.velocity[i]);
    }
    EXPECT_EQ(bad_r, 0u) << "positions differing in at least one bit";
    EXPECT_EQ(bad_v, 0u) << "velocities differing in at least one bit";
}

// size_ratio < 1: a mixture whose radii differ enough for two cell grids (size classes);
// growth_rate > 0: Lubachevsky-Stillinger growth all along both halves (the diameter
// grows by 0.05 per unit time, so the packing fraction rises by about a third), which
// needs the radii's reference time, rates, thermostat and pressure window saved
template <int D>
void restart_case(bool periodic, double restitution, double tc, double size_ratio = 1.0,
                  double growth_rate = 0.0) {
    SCOPED_TRACE(std::string(periodic ? "periodic" : "walled") + " restitution " +
                 std::to_string(restitution) + " tc " + std::to_string(tc) + " size ratio " +
                 std::to_string(size_ratio) + " growth " + std::to_string(growth_rate));
    auto spec = equal_gas<D>(D == 2 ? 800 : 500, D == 2 ? 0.45 : 0.35, periodic, 77);
    if (size_ratio < 1.0) {
        spec.species = {SpeciesSpec{D == 2 ? 100u : 60u, 0.5, 1.0, -1.0},
                        SpeciesSpec{D == 2 ? 700u : 440u, 0.5 * size_ratio, 1.0, -1.0}};
        spec.placement = Placement::random;
        spec.eta = 0.3;
    }
    auto gas = make_gas(spec);
    EventParams params;
    params.restitution = restitution;
    params.wall_restitution = restitution;
    params.tc = tc;
    params.growth_rate = growth_rate;
    // T: about 20 collisions per particle (collision frequency ~6 (2D) / ~14 (3D) at T = 1;
    // fewer when the gas cools)
    const double T = D == 2 ? 3.5 : 1.5;

    EventEngine<D> one(gas.particles, gas.box, params);
    StopLimits lim;
    lim.time = 2.0 * T;
    one.run(lim);

    EventEngine<D> first(gas.particles, gas.box, params);
    lim.time = T;
    first.run(lim);
    std::stringstream buffer;
    first.save(buffer);
    EventEngine<D> second = EventEngine<D>::load(buffer, params);
    expect_same_state(first, second); // the restored state is the saved one
    lim.time = 2.0 * T;
    second.run(lim);

    EXPECT_GT(one.counters().pair_collisions, (restitution < 1.0 ? 5 : 10) * gas.particles.size());
    expect_same_state(one, second);
    // the complete states agree too: their checkpoints are byte for byte the same
    std::stringstream a, b;
    one.save(a);
    second.save(b);
    EXPECT_TRUE(a.str() == b.str()) << "checkpoints of the two runs differ";
    // and the first engine, continued without a restart, agrees as well
    first.run(lim);
    expect_same_state(one, first);
}

// The engine's checkpoint, as the bytes a file would hold.
template <int D> std::string checkpoint_bytes(const EventEngine<D>& e) {
    std::stringstream buffer;
    e.save(buffer);
    return buffer.str();
}

} // namespace

TEST(Restart, BitForBitPeriodic2D) {
    restart_case<2>(true, 1.0, 0.0);
}
TEST(Restart, BitForBitWalled2D) {
    restart_case<2>(false, 1.0, 0.0);
}
TEST(Restart, BitForBitPeriodic3D) {
    restart_case<3>(true, 1.0, 0.0);
}
TEST(Restart, BitForBitWalled3D) {
    restart_case<3>(false, 1.0, 0.0);
}
TEST(Restart, BitForBitInelasticTcPeriodic2D) {
    restart_case<2>(true, 0.7, 0.05);
}
TEST(Restart, BitForBitInelasticTcWalled2D) {
    restart_case<2>(false, 0.7, 0.05);
}
TEST(Restart, BitForBitInelasticTcPeriodic3D) {
    restart_case<3>(true, 0.7, 0.03);
}
TEST(Restart, BitForBitInelasticTcWalled3D) {
    restart_case<3>(false, 0.7, 0.03);
}

TEST(Restart, BitForBitTwoSizeClasses2D) {
    restart_case<2>(true, 1.0, 0.0, 0.25);
}
TEST(Restart, BitForBitTwoSizeClasses3D) {
    restart_case<3>(false, 1.0, 0.0, 0.25);
}

TEST(Restart, BitForBitGrowingPeriodic3D) {
    restart_case<3>(true, 1.0, 0.0, 1.0, 0.05);
}
TEST(Restart, BitForBitGrowingWalledMixture2D) {
    restart_case<2>(false, 1.0, 0.0, 0.25, 0.05);
}

TEST(Restart, ManyRestartsInARow) {
    // ten save/load cycles (3D, walls, TC model with tc ~ a mean free time, so that the
    // per-particle collision clocks matter for most collisions) against one run
    auto gas = make_gas(equal_gas<3>(400, 0.35, false, 12));
    EventParams params;
    params.restitution = 0.8;
    params.wall_restitution = 0.9;
    params.tc = 0.05;
    EventEngine<3> one(gas.particles, gas.box, params);
    StopLimits lim;
    lim.time = 6.0;
    one.run(lim);
    EventEngine<3> e(gas.particles, gas.box, params);
    for (int k = 1; k <= 10; ++k) {
        lim.time = 0.6 * k;
        e.run(lim);
        std::stringstream buffer;
        e.save(buffer);
        e = EventEngine<3>::load(buffer, params);
    }
    EXPECT_GT(one.counters().pair_collisions, 10 * gas.particles.size());
    expect_same_state(one, e);
}

TEST(Restart, RejectsCorruptOrMismatchedCheckpoints) {
    auto gas = make_gas(equal_gas<2>(100, 0.3, true, 1));
    EventEngine<2> e(gas.particles, gas.box, EventParams{});
    const std::string bytes = checkpoint_bytes(e);
    {
        std::stringstream in(bytes.substr(0, bytes.size() / 2));
        EXPECT_THROW(EventEngine<2>::load(in, EventParams{}), InputError);
    }
    {
        std::stringstream in(bytes);
        EXPECT_THROW(EventEngine<3>::load(in, EventParams{}), InputError);
    }
    {
        std::string bad = bytes;
        bad[0] ^= 0x5a;
        std::stringstream in(bad);
        EXPECT_THROW(EventEngine<2>::load(in, EventParams{}), InputError);
    }
    {
        std::stringstream in("");
        EXPECT_THROW(EventEngine<2>::load(in, EventParams{}), InputError);
    }
}

TEST(Restart, RejectsEventPartnersThatNameNoParticleShellOrWall) {
    // A walled 2D box has wall codes -3 ... -6; one below them would reach process_wall
    // with a wall index out of range, and one at N or above a particle that is not there.
    auto gas = make_gas(equal_gas<2>(100, 0.3, false, 1));
    EventEngine<2> e(gas.particles, gas.box, EventParams{});
    const std::string bytes = checkpoint_bytes(e);
    const std::size_t at = test::read_event_lists(e).first_event_partner_offset;
    const auto load_with_partner = [&](std::int32_t partner) {
        std::string edited = bytes;
        std::memcpy(edited.data() + at, &partner, sizeof partner);
        std::stringstream in(edited);
        return EventEngine<2>::load(in, EventParams{});
    };
    for (std::int32_t ok : {-6, -1, 99}) EXPECT_NO_THROW(load_with_partner(ok)) << ok;
    for (std::int32_t bad : {-7, -100, std::numeric_limits<std::int32_t>::min(), 100})
        EXPECT_THROW(load_with_partner(bad), InputError) << bad;
}

TEST(Restart, LoadValidatesParameters) {
    // The parameters given to load() are user input just like the constructor's: a
    // restitution outside [0, 1] or a negative tc must be refused with InputError, not
    // silently run (restitution 1.5 would pump energy into the gas).
    auto gas = make_gas(equal_gas<2>(100, 0.3, true, 1));
    EventEngine<2> e(gas.particles, gas.box, EventParams{});
    const std::string bytes = checkpoint_bytes(e);
    auto load_with = [&](const EventParams& params) {
        std::stringstream in(bytes);
        return EventEngine<2>::load(in, params);
    };
    EventParams ok;
    EXPECT_NO_THROW(load_with(ok));
    for (double bad : {-0.1, 1.5, std::numeric_limits<double>::quiet_NaN()}) {
        EventParams p;
        p.restitution = bad;
        EXPECT_THROW(load_with(p), InputError) << "restitution " << bad;
        EventParams w;
        w.wall_restitution = bad;
        EXPECT_THROW(load_with(w), InputError) << "wall restitution " << bad;
    }
    EventParams t;
    t.tc = -1.0;
    EXPECT_THROW(load_with(t), InputError) << "tc -1";
}
