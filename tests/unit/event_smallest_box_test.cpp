// The smallest periodic boxes of the event engine. It once accepted a box as soon as
// half its shortest length exceeded the largest contact distance; just above that, the
// lists' skin (capped by the room between the two) was so thin that even one free
// particle made list events at intervals of about L / 2 - 2 r: one ulp above, a run
// stopped at t = 3e-14 with "time stopped advancing ... inelastic collapse"; 1e-7 above,
// a run to t = 10 did not end in 10 s (found by the event grids' brute-force test). Now
// half the length must exceed the contact by a tenth of it, and a run in the smallest
// box it accepts goes at the pace of its physics.
#include "pedesis/core/error.hpp"
#include "pedesis/event/event_engine.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

using namespace pedesis;

namespace {

// One particle of radius 0.25 at rest position (0, 0), moving at (1, 0), in a periodic
// square of side L.
ParticleStore<2> one_particle() {
    ParticleStore<2> p;
    p.species_table = {Species{"A", 0.25, 1.0}};
    p.position = {Vec<2>{{0.0, 0.0}}};
    p.velocity = {Vec<2>{{1.0, 0.0}}};
    p.tag = {0};
    p.species = {0};
    return p;
}

TEST(EventSmallestBox, ABoxWithoutRoomForASkinIsRefusedWithTheLengthItNeeds) {
    // 4 radii + 1 ulp, and just under 4.4 radii (contact 0.5: 2.2 contacts = 1.1)
    for (const double L : {std::nextafter(1.0, 2.0), 1.0999}) {
        const Box<2> box(Vec<2>{{L, L}}, {true, true});
        try {
            EventEngine<2> engine(one_particle(), box, EventParams{});
            ADD_FAILURE() << "L = " << L << " was accepted";
        } catch (const InputError& e) {
            EXPECT_NE(std::string(e.what()).find("at least 2.2 times the largest contact"),
                      std::string::npos)
                << e.what();
        }
    }
}

TEST(EventSmallestBox, OneFreeParticleRunsInTheSmallestBoxAccepted) {
    const Box<2> box(Vec<2>{{1.1, 1.1}}, {true, true});
    for (const double skin : {0.01, 0.1, 0.5}) {
        EventParams params;
        params.skin = skin;
        EventEngine<2> engine(one_particle(), box, params);
        StopLimits limits;
        limits.time = 10.0;
        EXPECT_NO_THROW(engine.run(limits)) << "skin " << skin;
        EXPECT_NEAR(engine.time(), 10.0, 1e-9) << "skin " << skin;
        // the skin asked for, capped at 0.45 of the room (0.0225), rebuilt after the
        // particle has moved half of it: one rebuild per 0.5 skin of a run of length 10
        const double used = std::min(skin, 0.45 * (0.55 - 0.5));
        EXPECT_LE(engine.counters().list_rebuilds, 10.0 / (0.5 * used) + 2) << "skin " << skin;
        EXPECT_GE(engine.counters().list_rebuilds, 10.0 / (0.5 * used) - 2) << "skin " << skin;
    }
}

} // namespace
