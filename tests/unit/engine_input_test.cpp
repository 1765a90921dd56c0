// Bad input to the event engine's constructor throws InputError (never RunError, never
// a crash): overlaps (naming both tags), particles outside walls, bad radii, masses and
// restitutions, N = 0, non-finite positions or velocities, boxes smaller than a particle.
#include "pedesis/core/error.hpp"
#include "pedesis/event/event_engine.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <string>

using namespace pedesis;

namespace {

constexpr double nan_v = std::numeric_limits<double>::quiet_NaN();
constexpr double inf_v = std::numeric_limits<double>::infinity();

// Five unit-diameter disks well apart in a 10 x 10 box; tags in reverse storage order so
// that a message quoting storage indices instead of tags is caught.
ParticleStore<2> five() {
    ParticleStore<2> p;
    p.species_table = {Species{"A", 0.5, 1.0}};
    p.resize(5);
    for (std::size_t i = 0; i < 5; ++i) {
        p.position[i] = Vec<2>{{-3.0 + 1.5 * static_cast<double>(i), 0.3 * static_cast<double>(i)}};
        p.velocity[i] = Vec<2>{{0.1 * static_cast<double>(i), -0.2}};
        p.tag[i] = static_cast<std::uint32_t>(4 - i);
        p.species[i] = 0;
    }
    return p;
}

Box<2> box10(bool periodic) {
    return Box<2>(Vec<2>{{10.0, 10.0}}, {periodic, periodic});
}

std::string input_error_message(const ParticleStore<2>& p, const Box<2>& box,
                                const EventParams& params) {
    try {
        EventEngine<2> e(p, box, params);
    } catch (const InputError& err) {
        return err.what();
    } catch (const std::exception& err) {
        return std::string("WRONG EXCEPTION TYPE: ") + err.what();
    }
    return "NO EXCEPTION";
}

void expect_input_error(const ParticleStore<2>& p, const Box<2>& box, const EventParams& params,
                        const std::string& what) {
    const std::string m = input_error_message(p, box, params);
    EXPECT_NE(m, "NO EXCEPTION") << what;
    EXPECT_EQ(m.rfind("WRONG EXCEPTION TYPE", 0), std::string::npos) << what << ": " << m;
}

} // namespace

TEST(EngineInput, ValidInputIsAccepted) {
    for (bool periodic : {true, false}) {
        EXPECT_NO_THROW((EventEngine<2>(five(), box10(periodic), EventParams{})));
    }
    // restitutions at the ends of [0, 1] are fine
    EventParams params;
    params.restitution = 0.0;
    params.wall_restitution = 1.0;
    EXPECT_NO_THROW((EventEngine<2>(five(), box10(false), params)));
    // a particle touching a wall exactly is fine
    auto p = five();
    p.position[0] = Vec<2>{{-4.5, 0.0}};
    EXPECT_NO_THROW((EventEngine<2>(p, box10(false), EventParams{})));
    // two particles exactly in contact are fine
    p = five();
    p.position[1] = p.position[0] + Vec<2>{{1.0, 0.0}};
    EXPECT_NO_THROW((EventEngine<2>(p, box10(true), EventParams{})));
}

TEST(EngineInput, OverlapNamesBothTags) {
    for (bool periodic : {true, false}) {
        auto p = five();
        // storage 1 and 3 (tags 3 and 1) overlap by 0.2
        p.position[3] = p.position[1] + Vec<2>{{0.0, 0.8}};
        const std::string m = input_error_message(p, box10(periodic), EventParams{});
        EXPECT_NE(m.find("particle 3"), std::string::npos) << m;
        EXPECT_NE(m.find("particle 1"), std::string::npos) << m;
        EXPECT_EQ(m.rfind("WRONG EXCEPTION TYPE", 0), std::string::npos) << m;
        EXPECT_NE(m, "NO EXCEPTION");
    }
    // overlap across the periodic boundary
    auto p = five();
    p.position[0] = Vec<2>{{-4.8, 2.0}};
    p.position[4] = Vec<2>{{4.7, 2.1}};
    const std::string m = input_error_message(p, box10(true), EventParams{});
    EXPECT_NE(m.find("particle 4"), std::string::npos) << m;
    EXPECT_NE(m.find("particle 0"), std::string::npos) << m;
}

TEST(EngineInput, OutsideWalls) {
    auto p = five();
    p.position[2] = Vec<2>{{0.0, 4.6}}; // radius 0.5, wall at 5: pokes through
    expect_input_error(p, box10(false), EventParams{}, "through a wall");
    p.position[2] = Vec<2>{{7.0, 3.0}}; // centre outside the box
    expect_input_error(p, box10(false), EventParams{}, "outside the box");
    // the same position is legal when that axis is periodic (it is wrapped)
    EXPECT_NO_THROW((EventEngine<2>(p, box10(true), EventParams{})));
}

TEST(EngineInput, BadRadiusOrMass) {
    for (double r : {0.0, -0.5, nan_v, inf_v}) {
        auto p = five();
        p.species_table[0].radius = r;
        expect_input_error(p, box10(true), EventParams{}, "radius " + std::to_string(r));
    }
    for (double m : {0.0, -1.0, nan_v}) {
        auto p = five();
        p.species_table[0].mass = m;
        expect_input_error(p, box10(true), EventParams{}, "mass " + std::to_string(m));
    }
}

TEST(EngineInput, BadRestitution) {
    for (double xi : {-0.1, 1.1, nan_v}) {
        EventParams params;
        params.restitution = xi;
        expect_input_error(five(), box10(true), params, "restitution " + std::to_string(xi));
        EventParams wall;
        wall.wall_restitution = xi;
        expect_input_error(five(), box10(false), wall, "wall restitution " + std::to_string(xi));
    }
    for (double tc : {-1.0, nan_v, inf_v}) {
        EventParams params;
        params.tc = tc;
        expect_input_error(five(), box10(true), params, "tc " + std::to_string(tc));
    }
}

TEST(EngineInput, NoParticles) {
    ParticleStore<2> p;
    p.species_table = {Species{"A", 0.5, 1.0}};
    expect_input_error(p, box10(true), EventParams{}, "N = 0");
    ParticleStore<3> q;
    q.species_table = {Species{"A", 0.5, 1.0}};
    EXPECT_THROW(
        (EventEngine<3>(q, Box<3>(Vec<3>::filled(10.0), {true, true, true}), EventParams{})),
        InputError);
}

TEST(EngineInput, NonFiniteState) {
    for (bool periodic : {true, false}) {
        auto p = five();
        p.position[2][1] = nan_v;
        expect_input_error(p, box10(periodic), EventParams{}, "NaN position");
        p = five();
        p.position[2][0] = INFINITY;
        expect_input_error(p, box10(periodic), EventParams{}, "infinite position");
        p = five();
        p.velocity[4][0] = nan_v;
        expect_input_error(p, box10(periodic), EventParams{}, "NaN velocity");
    }
}

TEST(EngineInput, BoxSmallerThanAParticle) {
    ParticleStore<2> p;
    p.species_table = {Species{"big", 2.0, 1.0}};
    p.resize(1);
    p.position[0] = Vec<2>{{0.0, 0.0}};
    p.velocity[0] = Vec<2>{{1.0, 0.0}};
    p.tag[0] = 0;
    p.species[0] = 0;
    for (bool periodic : {true, false})
        expect_input_error(p, Box<2>(Vec<2>{{3.0, 10.0}}, {periodic, periodic}), EventParams{},
                           "diameter 4 in a box 3 wide");
    // periodic: the box must also be wider than twice the contact distance
    expect_input_error(p, Box<2>(Vec<2>{{6.0, 20.0}}, {true, true}), EventParams{},
                       "periodic 6 < 2 x 4");
}

TEST(EngineInput, FixedObstaclesAreAccepted) {
    auto p = five();
    p.species_table.push_back(Species{"post", 0.5, INFINITY});
    p.species[2] = 1;
    p.velocity[2] = Vec<2>{{3.0, 3.0}}; // ignored: obstacles never move
    EventEngine<2> e(p, box10(false), EventParams{});
    for (std::size_t i = 0; i < e.size(); ++i)
        if (e.lazy_particles().species[i] == 1) {
            EXPECT_EQ(norm2(e.lazy_particles().velocity[i]), 0.0);
        }
}
