// The event engine's per-size-class grids and reach scans against an O(N^2)
// minimum-image scan. Its neighbour lists (read from its checkpoint, the one public view
// of them) must hold, for every particle, exactly the particles whose list centres lie
// closer than contact + skin (the engine's own test, so the comparison is exact), each
// once: right after construction (the grids' whole build), and again after thousands of
// events (each particle's list rebuilt alone, from the grid cells within reach of its
// size class). And the first pair collision of the run must be the brute-force earliest
// over all pairs. Geometries: sc, fcc, square and hexagonal lattices from the smallest
// box the engine accepts to 20 list ranges per axis, touching or not, with cells exactly
// as wide as the lattice spacing (sites on every face) and a ulp either side, box lengths
// one ulp either side, periodic, walled and mixed axes, two species of radius ratio 1, 2
// (one size class) and 5 (two classes), skins from a tenth of a radius to more than the
// contact distance. Every failure names its case.
#include "pedesis/event/event_engine.hpp"
#include "pedesis/event/prediction.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cstdio>
#include <random>
#include <string>
#include <vector>

#include "support/event_lists.hpp"
#include "support/lattices.hpp"
#include "support/pair_sets.hpp"
#include "support/random_positions.hpp"

using namespace pedesis;
using test::PairSet;

namespace {

template <int D> struct Case {
    test::LatticeKind kind;
    int cells;     // conventional cells per axis
    double edge;   // of a conventional cell
    int nudge;     // box length: a ulp short (-1), exact (0) or long (+1)
    int pattern;   // 0 periodic, 1 walls, 2 mixed
    double radius; // of species A; B is radius / ratio
    double ratio;  //
    double skin;   //
    std::uint64_t seed;

    std::string name() const {
        return test::lattice_name(kind, D) + " " + std::to_string(cells) + "^" + std::to_string(D) +
               " cells of edge " + test::exact(edge) + ", L " + test::nudge_name(nudge) +
               ", axes " +
               (pattern == 0   ? "periodic"
                : pattern == 1 ? "walled"
                               : "mixed") +
               ", radius " + test::exact(radius) + ", ratio " + std::to_string(ratio) + ", skin " +
               test::exact(skin) + ", seed " + std::to_string(seed);
    }
};

template <int D> struct Setup {
    Box<D> box;
    ParticleStore<D> p;
};

// The lattice (shifted half a cell on walled axes, sites too near a wall dropped), each
// site species A or B at random, Gaussian velocities.
template <int D> Setup<D> make_setup(const Case<D>& c) {
    const Vec<D> edge = test::unit_cell<D>(c.kind, c.edge);
    const auto [box, offset, cells] = test::lattice_box<D>(edge, c.cells, c.nudge, c.pattern);
    Setup<D> s{box, {}};
    s.p.species_table = {Species{"A", c.radius, 1.0}, Species{"B", c.radius / c.ratio, 0.5}};
    std::mt19937_64 gen(c.seed);
    std::normal_distribution<double> normal;
    for (const auto& r : test::lattice_sites(s.box, c.kind, cells, edge, offset)) {
        const std::uint16_t sp = gen() % 2;
        if (!s.box.contains(r, s.p.species_table[sp].radius)) continue;
        s.p.position.push_back(r);
        Vec<D> v;
        for (int a = 0; a < D; ++a) v[a] = normal(gen);
        s.p.velocity.push_back(v);
        s.p.tag.push_back(static_cast<std::uint32_t>(s.p.tag.size()));
        s.p.species.push_back(sp);
    }
    return s;
}

// Every list equals the brute-force set of its centre (exactly the engine's test:
// |min image of c_i - c_j|^2 < (r_i + r_j + skin)^2), each entry once.
template <int D> void expect_lists_exact(const test::EventLists<D>& l, const std::string& label) {
    const auto& t = l.species_table;
    const PairSet expect =
        test::both_orders(test::brute_pairs(l.box, l.centre, [&](std::uint32_t i, std::uint32_t j) {
            const double cut = t[l.species[i]].radius + t[l.species[j]].radius + l.skin;
            return cut * cut;
        }));
    PairSet listed;
    for (std::uint32_t i = 0; i < l.neighbours.size(); ++i)
        for (std::uint32_t j : l.neighbours[i]) listed.push_back({i, j});
    std::sort(listed.begin(), listed.end());
    EXPECT_EQ(std::adjacent_find(listed.begin(), listed.end()), listed.end())
        << label << ": a neighbour listed twice";
    EXPECT_TRUE(std::none_of(listed.begin(), listed.end(),
                             [](const test::Pair& p) { return p.first == p.second; }))
        << label << ": a particle in its own list";
    EXPECT_TRUE(test::minus(expect, listed).empty())
        << label << ": "
        << test::describe_pairs(test::minus(expect, listed), "missing", l.box, l.centre);
    EXPECT_TRUE(test::minus(listed, expect).empty())
        << label << ": "
        << test::describe_pairs(test::minus(listed, expect), "beyond contact + skin", l.box,
                                l.centre);
}

// The engine accepts a box iff half its shortest periodic length exceeds the largest
// contact distance by a tenth of it (EventEngine::min_room_fraction): room for a skin.
// (Boxes barely above half a contact once made the engine rebuild its lists every 1e-16
// time units and stall: event_smallest_box_test.cpp.)
template <int D> bool accepted(const Setup<D>& s) {
    double shortest = 1e300;
    for (int a = 0; a < D; ++a)
        if (s.box.periodic(a)) shortest = std::min(shortest, s.box.length(a));
    double largest = 0.0;
    for (const auto& species : s.p.species_table) largest = std::max(largest, species.radius);
    const double contact = 2.0 * largest;
    return 0.5 * shortest - contact >= EventEngine<D>::min_room_fraction * contact;
}

struct Tally {
    int cases = 0, runs = 0, refused = 0;
};

// Lists after construction and, unless the crystal is jammed (touching spheres cannot
// move), again after 3 N pair collisions. A run that stops with an error fails the case
// by name, so that it can be replayed alone.
template <int D> void check_case(const Case<D>& c, bool touching, Tally& tally) {
    const Setup<D> s = make_setup(c);
    if (s.p.size() < 2) return;
    const std::string label = c.name() + ", " + std::to_string(s.p.size()) + " particles";
    EventParams params;
    params.skin = c.skin;
    if (!accepted(s)) {
        EXPECT_THROW(EventEngine<D>(s.p, s.box, params), InputError) << label;
        ++tally.refused;
        return;
    }
    EventEngine<D> engine(s.p, s.box, params);
    expect_lists_exact(test::read_event_lists(engine), label + ", built");
    ++tally.cases;
    if (touching) return;
    // every run in the small crystals, one in four (2D) or eight (3D, by seed) beyond 64
    // sites; 3 N
    // collisions, at most N + 400: thousands of events in all, each particle's list rebuilt
    // alone many times, in a fraction of the time
    const std::size_t n = s.p.size();
    if (n > 64 && c.seed % (D == 2 ? 4 : 8) != 0) return;
    if (n > 1100) return; // the large crystals: their lists after construction only
    StopLimits limits;
    limits.pair_collisions = n <= 200 ? 3 * n : n + 400;
    try {
        engine.run(limits);
    } catch (const RunError& e) {
        ADD_FAILURE() << label << ": the run stopped: " << e.what();
        return;
    }
    EXPECT_GT(engine.counters().list_rebuilds, 0u) << label;
    expect_lists_exact(test::read_event_lists(engine),
                       label + ", after " + std::to_string(engine.counters().pair_collisions) +
                           " collisions at t = " + test::exact(engine.time()));
    EXPECT_NO_THROW(engine.check_no_overlap(1e-9)) << label;
    ++tally.runs;
}

// Cases for one lattice: radii that leave the spheres touching along the nearest
// neighbours or with a gap, skins that make the grid's cells exactly the lattice spacing
// (every site on a cell face) or a ulp either side, small and larger than the contact.
template <int D> std::vector<double> skins_for(double cell, double radius) {
    const double exact = cell - 2.0 * radius; // grid cells of the large class: `cell` wide
    std::vector<double> s = {0.1 * radius, 3.0 * radius};
    if (exact > 0.0) {
        s.push_back(exact);
        s.push_back(std::nextafter(exact, 0.0));
        s.push_back(std::nextafter(exact, 1.0));
    }
    return s;
}

template <int D> Tally check_lattices(const std::vector<int>& sizes, std::size_t most_sites) {
    Tally tally;
    std::uint64_t seed = 1;
    for (auto kind : test::lattice_kinds<D>()) {
        const double nearest = kind == test::LatticeKind::fcc ? std::sqrt(0.5) : 1.0;
        for (int n : sizes) {
            const std::size_t sites =
                test::basis<D>(kind).size() * static_cast<std::size_t>(std::pow(n, D));
            if (sites > most_sites) continue;
            for (bool touching : {false, true}) {
                const double radius = touching ? 0.5 * nearest : 0.25;
                for (double ratio : {1.0, 2.0, 5.0})
                    for (double skin : skins_for<D>(touching ? 2.0 * nearest : 1.0, radius))
                        for (int nudge : {-1, 0, 1})
                            for (int pattern : {0, 1, 2}) {
                                // the large boxes: fewer variants, the same kinds of them
                                const int pick = nudge + pattern + static_cast<int>(ratio);
                                if (sites > 400 && pick % 3 != 0) continue;
                                if (sites > 1100 &&
                                    (touching || pick != 6 || skin != 0.5 || nudge != 1))
                                    continue;
                                check_case(Case<D>{kind, n, 1.0, nudge, pattern, radius, ratio,
                                                   skin, seed++},
                                           touching, tally);
                            }
            }
        }
    }
    return tally;
}

TEST(EventGridsBruteForce, SquareAndHexagonalLattices) {
    const Tally t = check_lattices<2>({1, 2, 3, 4, 5, 6, 8, 11, 16, 20}, 800);
    EXPECT_GT(t.cases, 1000);
    EXPECT_GT(t.runs, 1000);
    EXPECT_GT(t.refused, 10) << "the smallest boxes should be refused";
    RecordProperty("cases", t.cases);
    std::printf("%d cases, %d runs, %d refused\n", t.cases, t.runs, t.refused);
}

TEST(EventGridsBruteForce, ScAndFccLattices) {
    const Tally t = check_lattices<3>({1, 2, 3, 4, 5, 6, 8, 12, 20}, 8000);
    EXPECT_GT(t.cases, 800);
    EXPECT_GT(t.runs, 300);
    EXPECT_GT(t.refused, 10) << "the smallest boxes should be refused";
    RecordProperty("cases", t.cases);
    std::printf("%d cases, %d runs, %d refused\n", t.cases, t.runs, t.refused);
}

// The earliest free-flight collision of the pair (i, j) through the periodic images of
// their separation within one box length of the minimum image (3^D of them; walled axes
// have one), and the image's shift. Enough while the relative travel up to the answer
// stays under 1.5 L - contact on every periodic axis, which the caller checks.
template <int D>
double earliest_over_images(const Box<D>& box, const Vec<D>& dr, const Vec<D>& dv, double sigma) {
    double best = never;
    for (int k = 0; k < (D == 2 ? 9 : 27); ++k) {
        Vec<D> image = dr;
        bool skip = false;
        for (int a = 0, m = k; a < D; ++a, m /= 3) {
            if (m % 3 == 1) continue;
            skip = skip || !box.periodic(a);
            image[a] += (m % 3 - 1) * box.length(a);
        }
        if (!skip) best = std::min(best, pair_collision_time(image, dv, sigma));
    }
    return best;
}

// The first pair collision of a run against the earliest over all N (N - 1) / 2 pairs
// in free flight, every pair through each of its 3^D nearest images: in boxes of 3
// cells a pair can meet through another image than the minimum one at t = 0 before any
// pair meets through that one. Cases where the brute force would need farther images,
// and walled cases where a wall comes first, compare nothing and are not counted.
template <int D> int check_first_collisions(int cases) {
    int compared = 0;
    for (int k = 0; k < cases; ++k) {
        const auto kinds = test::lattice_kinds<D>();
        const bool fcc = kinds[k % 2] == test::LatticeKind::fcc;
        const Case<D> c{kinds[k % 2],
                        3 + k % 5,
                        fcc ? std::sqrt(2.0) : 1.0,
                        k % 3 - 1,
                        k % 4 == 3 ? 2 : 0,
                        0.3 + 0.02 * (k % 7),
                        k % 3 == 0   ? 1.0
                        : k % 3 == 1 ? 2.0
                                     : 5.0,
                        0.2 + 0.05 * (k % 5),
                        static_cast<std::uint64_t>(9000 + k)};
        const Setup<D> s = make_setup(c);
        if (!accepted(s) || s.p.size() < 2) continue;
        const auto& t = s.p.species_table;
        double best = never, wall = never, fastest = 0.0, shortest = never;
        for (int a = 0; a < D; ++a)
            if (s.box.periodic(a)) shortest = std::min(shortest, s.box.length(a));
        test::Pair first{0, 0};
        for (std::uint32_t i = 0; i < s.p.size(); ++i) {
            fastest = std::max(fastest, norm(s.p.velocity[i]));
            for (int a = 0; a < D; ++a)
                if (!s.box.periodic(a) && s.p.velocity[i][a] != 0.0) {
                    const double r = t[s.p.species[i]].radius;
                    const double to = s.p.velocity[i][a] > 0 ? s.box.hi(a) - r - s.p.position[i][a]
                                                             : s.box.lo(a) + r - s.p.position[i][a];
                    wall = std::min(wall, to / s.p.velocity[i][a]);
                }
        }
        // the minimum image first; the other images only where the fastest approach could
        // bring one within contact before the earliest found
        for (bool images : {false, true}) {
            if (images && 2.0 * fastest * best < 0.5 * shortest - 2.0 * t[0].radius) break;
            for (std::uint32_t i = 0; i < s.p.size(); ++i)
                for (std::uint32_t j = i + 1; j < s.p.size(); ++j) {
                    const Vec<D> dr = s.box.minimum_image(s.p.position[i] - s.p.position[j]);
                    const Vec<D> dv = s.p.velocity[i] - s.p.velocity[j];
                    const double sigma = t[s.p.species[i]].radius + t[s.p.species[j]].radius;
                    const double tc = images ? earliest_over_images(s.box, dr, dv, sigma)
                                             : pair_collision_time(dr, dv, sigma);
                    if (tc < best) best = tc, first = {i, j};
                }
        }
        if (!(best < wall)) continue;
        if (!(2.0 * fastest * best < 1.5 * shortest - 2.0 * t[0].radius)) continue;
        EventParams params;
        params.skin = c.skin;
        EventEngine<D> engine(s.p, s.box, params);
        StopLimits limits;
        limits.pair_collisions = 1;
        engine.run(limits);
        EXPECT_NEAR(engine.time(), best, 1e-9 * (1.0 + best)) << c.name();
        // (the engine stores the particles in its own order: matched by tag)
        const ParticleStore<D>& q = engine.lazy_particles();
        const std::vector<std::uint32_t> input = s.p.index_of_tags();
        std::vector<std::uint32_t> changed;
        for (std::uint32_t k = 0; k < q.size(); ++k)
            if (!(q.velocity[k] == s.p.velocity[input[q.tag[k]]]))
                changed.push_back(input[q.tag[k]]);
        std::sort(changed.begin(), changed.end());
        EXPECT_EQ(changed, (std::vector<std::uint32_t>{first.first, first.second}))
            << c.name() << ": the first collision is not the brute-force earliest pair";
        ++compared;
    }
    return compared;
}

TEST(EventGridsBruteForce, FirstCollisionIsTheEarliestOverAllPairs) {
    EXPECT_GT(check_first_collisions<2>(150), 100);
    EXPECT_GT(check_first_collisions<3>(150), 100);
}

} // namespace
