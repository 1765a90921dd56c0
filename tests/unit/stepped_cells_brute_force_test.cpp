// The stepped engine's cells against an O(N^2) minimum-image scan. A step moves every
// particle, then its cell list must find every overlapping pair: built so that the
// overlaps after the free flight are isolated pairs that approach, each must collide
// once (the pair_collisions counter equals the brute-force number of overlapping pairs,
// and exactly their particles change velocity). The overlapping particles sit on the
// faces of the engine's cells (exactly and a ulp either side), at -L/2, one ulp inside
// +L/2 or touching a wall, their partners a ulp inside contact or further, across the
// face or the periodic boundary; among them a static sc, fcc, square or hexagonal
// lattice; boxes a whole number of lattice cells long and a ulp either side; periodic,
// walled and mixed axes; two species of radius ratio 1, 2 and 5. The same
// configurations, at rest, must be refused by the constructor of both hard-particle
// engines (their check_no_overlap scans) exactly when brute force finds an overlap, and
// the message must name an overlapping pair. Every failure names its case.
#include "pedesis/event/event_engine.hpp"
#include "pedesis/stepped/stepped_engine.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <random>
#include <string>
#include <vector>

#include "support/face_pairs.hpp"
#include "support/lattices.hpp"
#include "support/pair_sets.hpp"

using namespace pedesis;
using test::PairSet;

namespace {

// Nearest neighbours 1 apart, so that lattice spheres of radius_a (0.45) never touch:
// the fcc cube is sqrt 2 on edge.
inline double lattice_edge(test::LatticeKind kind) {
    return kind == test::LatticeKind::fcc ? std::sqrt(2.0) : 1.0;
}

template <int D> struct Case {
    test::LatticeKind kind;
    int cells;
    int nudge;
    int pattern; // 0 periodic, 1 walls, 2 mixed
    double ratio;
    std::size_t pairs;
    std::uint64_t seed;

    std::string name() const {
        return test::lattice_name(kind, D) + " " + std::to_string(cells) + "^" + std::to_string(D) +
               " cells of edge " + test::exact(lattice_edge(kind)) + ", L " +
               test::nudge_name(nudge) + ", axes " +
               (pattern == 0   ? "periodic"
                : pattern == 1 ? "walled"
                               : "mixed") +
               ", ratio " + std::to_string(ratio) + ", " + std::to_string(pairs) + " pairs, seed " +
               std::to_string(seed);
    }
};

constexpr double radius_a = 0.45; // lattice sites 1 apart nearly touch
constexpr double dt = 1.0;

// Speeds a multiple of 2^-12: with dt = 1 the moves (and most positions) are exact.
double speed_for(double radius) {
    return std::ldexp(std::floor(std::ldexp(0.4 * radius, 12)), -12);
}

template <int D> struct Built {
    Box<D> box;
    ParticleStore<D> p;
};

// Distance at which a pair's straight paths overlap at the end of the step, by the
// closing speed: from a ulp inside contact to nine tenths of the closing.
inline double overlap_distance(double contact, double closing, std::mt19937_64& gen) {
    switch (gen() % 4) {
    case 0:
        return std::nextafter(contact, 0.0);
    case 1:
        return contact;
    case 2:
        return contact - 0.9 * closing;
    default:
        return contact - std::uniform_real_distribution<double>(0.0, 0.9)(gen) * closing;
    }
}

template <int D> Built<D> build(const Case<D>& c) {
    std::mt19937_64 gen(c.seed);
    const Vec<D> edge = test::unit_cell<D>(c.kind, lattice_edge(c.kind));
    const auto [lattice, offset, cells] = test::lattice_box<D>(edge, c.cells, c.nudge, c.pattern);
    Built<D> b{lattice, {}};
    const Box<D>& box = b.box;
    const double radius[2] = {radius_a, radius_a / c.ratio};
    b.p.species_table = {Species{"A", radius[0], 1.0}, Species{"B", radius[1], 1.0}};
    auto background = test::lattice_sites(box, c.kind, cells, edge, offset);

    // the engine's cells: at least a contact distance, and about one particle, wide
    const auto guess = static_cast<double>(background.size() + 2 * c.pairs);
    const CellList<D> grid(box, std::max(2.0 * radius_a, std::pow(box.volume() / guess, 1.0 / D)));
    std::array<int, D> slabs;
    for (int a = 0; a < D; ++a) slabs[a] = grid.cells_along(a);

    // the pairs: positions at the end of the step, velocities towards each other
    std::vector<Vec<D>> after, vel;
    std::vector<std::uint16_t> species;
    auto isolated = [&](const Vec<D>& r, double margin) {
        for (const auto& q : after)
            if (norm2(box.minimum_image(r - q)) < margin * margin) return false;
        return true;
    };
    const double keep_off = 2.0 * radius_a + 2.0 * radius_a; // a contact, and the paths' spread
    for (std::size_t tries = 0; tries < 40 * c.pairs && after.size() < 2 * c.pairs; ++tries) {
        const std::uint16_t sx = gen() % 2, sy = gen() % 2;
        double ux = speed_for(radius[sx]);
        const double uy = speed_for(radius[sy]);
        const double contact = radius[sx] + radius[sy];
        std::vector<Vec<D>> two;
        test::add_face_pairs(
            box, slabs, 1,
            [&](std::mt19937_64& g) { return overlap_distance(contact, ux + uy, g); }, gen, two);
        if (two.size() != 2) continue;
        // an anchor on a wall moves in to touch it, its partner with it
        for (int a = 0; a < D; ++a) {
            if (box.periodic(a)) continue;
            const double lo = box.lo(a) + radius[sx], hi = box.hi(a) - radius[sx];
            const double shift = two[0][a] < lo   ? lo - two[0][a]
                                 : two[0][a] > hi ? hi - two[0][a]
                                                  : 0.0;
            two[0][a] += shift;
            two[1][a] += shift;
        }
        Vec<D> e = box.minimum_image(two[1] - two[0]);
        if (!(norm(e) > 0.0)) continue;
        e *= 1.0 / norm(e);
        // X moves towards Y and Y towards X. After the bounce (equal masses: the normal
        // velocities swap) each goes back along the line by less than ux + uy: a pair
        // whose bounce would reach a wall (an anchor touching a wall, hit towards it)
        // makes a chain of collisions, not the one this case counts
        const double closing = ux + uy;
        Vec<D> before_x = two[0] - e * ux, before_y = two[1] + e * uy;
        if (!box.contains(two[0], radius[sx]) || !box.contains(two[1], radius[sy]) ||
            !box.contains(two[0] - e * closing, radius[sx]) ||
            !box.contains(two[1] + e * closing, radius[sy]))
            continue;
        if (!isolated(two[0], keep_off) || !isolated(two[1], keep_off)) continue;
        box.wrap(before_x);
        box.wrap(before_y);
        // in a box under about two contacts and two closings long, the start's minimum
        // image can be another image than the one the pair overlaps through (the pair
        // would overlap already, or approach from the other side), and after the bounce
        // the pair can meet again through the next image: only pairs that stay beyond
        // contact through every other image, by the whole closing, make a case with one
        // known collision
        const Vec<D> gap = e * (norm(box.minimum_image(two[1] - two[0])) + closing);
        if (!(norm(box.minimum_image(before_y - before_x) - gap) < 1e-9)) continue;
        bool alone = true;
        for (int k = 0; k < (D == 2 ? 9 : 27); ++k) {
            Vec<D> image = gap;
            bool shifted = false;
            for (int a = 0, m = k; a < D; ++a, m /= 3) {
                if (!box.periodic(a) || m % 3 == 1) continue;
                image[a] += (m % 3 - 1) * box.length(a);
                shifted = true;
            }
            alone = alone && (!shifted || norm(image) - closing > contact);
        }
        if (!alone) continue;
        after.insert(after.end(), two.begin(), two.end());
        vel.push_back(e * ux);
        vel.push_back(e * (-uy));
        species.push_back(sx);
        species.push_back(sy);
        b.p.position.push_back(before_x);
        b.p.position.push_back(before_y);
    }
    // the static lattice around them, away from every pair
    for (const auto& r : background) {
        const std::uint16_t s = gen() % 2;
        if (!box.contains(r, radius[s]) || !isolated(r, keep_off)) continue;
        b.p.position.push_back(r);
        vel.push_back(Vec<D>{});
        species.push_back(s);
    }
    b.p.velocity = vel;
    b.p.species = species;
    for (std::size_t i = 0; i < b.p.position.size(); ++i)
        b.p.tag.push_back(static_cast<std::uint32_t>(i));
    return b;
}

// Positions after the free flight, as the engine computes them.
template <int D> std::vector<Vec<D>> moved(const Built<D>& b) {
    std::vector<Vec<D>> r = b.p.position;
    for (std::size_t i = 0; i < r.size(); ++i) {
        r[i] += b.p.velocity[i] * dt;
        b.box.wrap(r[i]);
    }
    return r;
}

template <int D>
PairSet overlaps(const Built<D>& b, const std::vector<Vec<D>>& pos, double shrink) {
    const auto& t = b.p.species_table;
    return test::brute_pairs(b.box, pos, [&](std::uint32_t i, std::uint32_t j) {
        const double c = (t[b.p.species[i]].radius + t[b.p.species[j]].radius) * shrink;
        return c * c;
    });
}

// One step: the collisions are exactly the brute-force overlaps after the flight.
template <int D> std::size_t check_step(const Case<D>& c) {
    const Built<D> b = build(c);
    const std::string label = c.name();
    const std::vector<Vec<D>> after = moved(b);
    EXPECT_TRUE(overlaps(b, b.p.position, 1.0).empty())
        << label << ": the case overlaps at the start";
    const PairSet expect = overlaps(b, after, 1.0);
    std::vector<std::uint32_t> in_pairs;
    for (const auto& [i, j] : expect) in_pairs.insert(in_pairs.end(), {i, j});
    std::sort(in_pairs.begin(), in_pairs.end());
    EXPECT_EQ(std::adjacent_find(in_pairs.begin(), in_pairs.end()), in_pairs.end())
        << label << ": the case has a particle in two overlaps";

    SteppedParams params;
    params.dt = dt;
    SteppedEngine<D> engine(b.p, b.box, params);
    engine.step();
    std::vector<std::uint32_t> changed;
    for (std::uint32_t i = 0; i < b.p.size(); ++i)
        if (!(engine.particles().velocity[i] == b.p.velocity[i])) changed.push_back(i);
    EXPECT_EQ(engine.counters().pair_collisions, expect.size())
        << label << ": " << test::describe_pairs(expect, "overlap after the flight", b.box, after);
    EXPECT_EQ(changed, in_pairs) << label << ": "
                                 << test::describe_pairs(expect, "overlap after the flight", b.box,
                                                         after);
    EXPECT_EQ(engine.counters().wall_collisions, 0u) << label;
    return expect.size();
}

// The constructors' overlap scans, on the configuration after the flight at rest:
// refused exactly when brute force finds an overlap beyond the engines' tolerance
// (1e-10 of the contact), naming an overlapping pair.
template <int D, class Engine, class Params>
void check_constructor(const Built<D>& b, const std::vector<Vec<D>>& pos, const Params& params,
                       const std::string& label) {
    ParticleStore<D> p = b.p;
    p.position = pos;
    std::fill(p.velocity.begin(), p.velocity.end(), Vec<D>{});
    const PairSet bad = overlaps(b, pos, 1.0 - 1e-10);
    try {
        Engine engine(p, b.box, params);
        EXPECT_TRUE(bad.empty()) << label << ": not refused; "
                                 << test::describe_pairs(bad, "overlap", b.box, pos);
    } catch (const InputError& e) {
        const std::string msg = e.what();
        const bool named = std::any_of(bad.begin(), bad.end(), [&](const test::Pair& q) {
            return msg.find("particle " + std::to_string(q.first) + " and particle " +
                            std::to_string(q.second) + " overlap") != std::string::npos;
        });
        EXPECT_TRUE(named) << label << ": " << msg
                           << "; brute force: " << test::describe_pairs(bad, "overlap", b.box, pos);
    }
}

template <int D> bool event_accepts(const Box<D>& box) {
    for (int a = 0; a < D; ++a)
        if (box.periodic(a) && !(0.5 * box.length(a) > 2.0 * radius_a)) return false;
    return true;
}

struct Tally {
    int cases = 0;
    std::size_t collisions = 0;
};

template <int D> Tally check_all(const std::vector<int>& sizes, int seeds) {
    Tally tally;
    std::uint64_t seed = 77;
    for (auto kind : test::lattice_kinds<D>())
        for (int n : sizes) {
            // the largest crystals (fcc 10^3: 4000 sites) add time, not kinds of geometry
            if (test::basis<D>(kind).size() * std::pow(n, D) > 1500.0) continue;
            for (int nudge : {-1, 0, 1})
                for (int pattern : {0, 1, 2})
                    for (double ratio : {1.0, 2.0, 5.0})
                        for (int k = 0; k < seeds; ++k) {
                            const Case<D> c{kind,    n,     nudge,
                                            pattern, ratio, 3 + static_cast<std::size_t>(n),
                                            seed++};
                            // the stepped engine needs periodic lengths above 2 contacts
                            bool ok = true;
                            for (int a = 0; a < D; ++a)
                                ok = ok && (pattern == 1 || (pattern == 2 && a % 2) ||
                                            n * test::unit_cell<D>(kind, lattice_edge(kind))[a] >
                                                4.0 * radius_a + 1e-9);
                            if (!ok) continue;
                            tally.collisions += check_step(c);
                            const Built<D> b = build(c);
                            const auto after = moved(b);
                            SteppedParams sp;
                            sp.dt = dt;
                            check_constructor<D, SteppedEngine<D>>(
                                b, after, sp, c.name() + ", stepped constructor");
                            if (event_accepts(b.box))
                                check_constructor<D, EventEngine<D>>(
                                    b, after, EventParams{}, c.name() + ", event constructor");
                            ++tally.cases;
                        }
        }
    return tally;
}

TEST(SteppedCellsBruteForce, PairsOnCellFacesAmongSquareAndHexagonalLattices) {
    const Tally t = check_all<2>({2, 3, 4, 5, 7, 10, 14, 20}, 3);
    EXPECT_GT(t.cases, 700);
    EXPECT_GT(t.collisions, 3000u);
    RecordProperty("cases", t.cases);
    std::printf("%d cases, %zu collisions\n", t.cases, t.collisions);
}

TEST(SteppedCellsBruteForce, PairsOnCellFacesAmongScAndFccLattices) {
    const Tally t = check_all<3>({2, 3, 4, 5, 7, 10}, 2);
    EXPECT_GT(t.cases, 400);
    EXPECT_GT(t.collisions, 2000u);
    RecordProperty("cases", t.cases);
    std::printf("%d cases, %zu collisions\n", t.cases, t.collisions);
}

} // namespace
