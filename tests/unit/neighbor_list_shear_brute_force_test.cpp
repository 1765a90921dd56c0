// NeighborList under Lees-Edwards shear against brute force: the rows hold exactly the
// pairs within r_list by Box::minimum_image (the sliding images across the y faces
// included), each once, and no two chunks of one colour write the same particle, on
// degenerate geometry (perfect lattices with sites on the cell faces, box lengths at exact
// multiples of the list range and one ulp either side, offsets of 0, one lattice
// spacing, exactly one cell, half a box and random ones, boxes too thin for the half
// stencil along x or y) in 2D and 3D; and while needs_rebuild says no, no pair within
// r_cut is missing, as particles move and the offset slides.
#include "pedesis/core/rng.hpp"
#include "pedesis/spatial/neighbor_list.hpp"

#include <gtest/gtest.h>
#include <omp.h>

#include <algorithm>
#include <cmath>
#include <iterator>
#include <string>
#include <utility>
#include <vector>

#include "support/neighbor_rows.hpp"
#include "support/random_positions.hpp"

using namespace pedesis;

namespace {

using test::check_colouring;
using test::listed_pairs;
using test::PairSet;

template <int D> PairSet brute_pairs(const Box<D>& box, const std::vector<Vec<D>>& pos, double r) {
    return test::brute_pairs_within(box, pos, r);
}

template <int D> Box<D> sheared(Box<D> box, double offset) {
    box.set_shear_rate(1.0);
    box.set_shear_offset(offset);
    return box;
}

template <int D> std::string describe(const Box<D>& box) {
    return test::describe_box(box) + " offset " + std::to_string(box.shear_offset());
}

// Returns the pairs listed (for the callers' check that the case had pairs across the
// sheared faces).
template <int D>
std::size_t check_against_brute_force(const Box<D>& box, const std::vector<Vec<D>>& pos,
                                      double r_cut, double skin) {
    SCOPED_TRACE(describe(box) + " r_cut " + std::to_string(r_cut) + " skin " +
                 std::to_string(skin));
    NeighborList<D> nl(box, r_cut, skin);
    nl.build(pos);
    const PairSet expect = brute_pairs(box, pos, nl.r_list());
    const PairSet listed = listed_pairs(nl);
    EXPECT_EQ(std::adjacent_find(listed.begin(), listed.end()), listed.end()) << "a pair twice";
    // (pairs a few ulps beyond r_list may be listed: the list's rounding margin)
    const PairSet outer = brute_pairs(box, pos, nl.r_list() * (1.0 + 1e-12));
    EXPECT_EQ(test::describe_pairs(test::minus(expect, listed), "missing", box, pos), "");
    EXPECT_EQ(test::describe_pairs(test::minus(listed, outer), "beyond r_list", box, pos), "");
    check_colouring(nl);
    return listed.size();
}

// Pairs whose minimum image crosses the y faces at this offset: what the shear changes.
template <int D>
std::size_t pairs_across_y(const Box<D>& box, const std::vector<Vec<D>>& pos, double r) {
    std::size_t k = 0;
    for (std::size_t i = 0; i < pos.size(); ++i)
        for (std::size_t j = i + 1; j < pos.size(); ++j) {
            const Vec<D> d = pos[i] - pos[j];
            if (std::abs(d[1]) > box.hi(1) && norm2(box.minimum_image(d)) < r * r) ++k;
        }
    return k;
}

template <int D> std::vector<Vec<D>> cubic_lattice(int n, double a, double L) {
    std::vector<Vec<D>> pos;
    std::array<int, D> c{};
    while (true) {
        Vec<D> r;
        for (int k = 0; k < D; ++k) r[k] = c[k] * a - 0.5 * L;
        pos.push_back(r);
        int k = 0;
        while (k < D && ++c[k] == n) c[k++] = 0;
        if (k == D) break;
    }
    // a site one ulp inside +L/2 on every axis
    Vec<D> tip;
    for (int k = 0; k < D; ++k) tip[k] = std::nextafter(0.5 * L, 0.0);
    pos.push_back(tip);
    return pos;
}

// The offsets of every case: none, a lattice spacing (sites onto sites), exactly one cell
// (the list range: with L = n a a multiple of 4 r_list the cells are r_list wide), half a
// cell, the ends of the range [-L_x/2, L_x/2), an ulp, and two of no particular kind.
std::vector<double> offsets(double a, double r_list, double lx) {
    return {
        0.0,     a,          r_list,      0.5 * r_list, -0.5 * lx, std::nextafter(0.5 * lx, 0.0),
        -r_list, 1e-13 * lx, 0.3719 * lx, -0.1234 * lx};
}

template <int D> void check_lattices(const std::vector<int>& sizes) {
    const int saved = omp_get_max_threads();
    std::size_t cases = 0, across = 0;
    for (int n : sizes)
        for (int per_range : {2, 3})
            for (int nudge : {-1, 0, 1})
                for (double skin_fraction : {0.0, 0.25}) {
                    const double a = 1.0, r_list = per_range * a;
                    double L = n * a;
                    if (nudge != 0) L = std::nextafter(L, nudge > 0 ? 2.0 * L : 0.0);
                    if (L < 2.0 * r_list) continue;
                    const std::vector<Vec<D>> pos = cubic_lattice<D>(n, a, L);
                    // two threads where the build runs in parallel (4096 particles); the
                    // brute force of those is slow: one case of each offset
                    const bool large = pos.size() >= 4096;
                    if (large && (nudge != 0 || skin_fraction != 0.0 || per_range != 2)) continue;
                    omp_set_num_threads(large ? 2 : 1);
                    const double r_cut = r_list / (1.0 + skin_fraction);
                    std::array<bool, D> periodic;
                    periodic.fill(true);
                    for (double off : offsets(a, r_list, L)) {
                        SCOPED_TRACE("lattice " + std::to_string(n) + "^" + std::to_string(D) +
                                     (nudge ? (nudge > 0 ? ", L + 1 ulp" : ", L - 1 ulp") : "") +
                                     ", r_list " + std::to_string(per_range) + " a");
                        const Box<D> box = sheared(Box<D>(Vec<D>::filled(L), periodic), off);
                        check_against_brute_force(box, pos, r_cut, r_list - r_cut);
                        across += pairs_across_y(box, pos, r_list);
                        ++cases;
                    }
                }
    omp_set_num_threads(saved);
    EXPECT_GT(cases, 100u);
    EXPECT_GT(across, 1000u) << "the cases had few pairs across the sheared faces";
}

TEST(NeighborListShear, MatchesBruteForceOnSquareLatticesAtMultiplesOfTheRange) {
    check_lattices<2>({4, 5, 6, 7, 8, 9, 12, 16, 21, 65});
}

TEST(NeighborListShear, MatchesBruteForceOnCubicLatticesAtMultiplesOfTheRange) {
    check_lattices<3>({4, 5, 6, 8, 9, 17});
}

// Random points (some on -L/2) in boxes of every kind the build tells apart: the half
// stencil, x too thin for a shifted row (the whole stencil), y one colour block (x made
// one block too), a walled z, dense systems (cells of r_list / 2, two deep).
template <int D>
void check_random(const std::vector<std::pair<Vec<D>, std::array<bool, D>>>& boxes, double r_cut,
                  double skin, double density, std::uint64_t seed) {
    for (const auto& [L, periodic] : boxes)
        for (int k = 0; k < 6; ++k) {
            CounterRng rng(seed, RngStream::placement, 999, static_cast<std::uint32_t>(k));
            const double off = k == 0 ? 0.0 : rng.uniform(-0.5 * L[0], 0.5 * L[0]);
            const Box<D> box = sheared(Box<D>(L, periodic), off);
            const auto n = static_cast<std::size_t>(density * box.volume());
            const auto pos = test::random_positions(box, n, ++seed, 8);
            check_against_brute_force(box, pos, r_cut, skin);
            EXPECT_GT(pairs_across_y(box, pos, r_cut + skin), 0u) << describe(box);
        }
}

TEST(NeighborListShear, MatchesBruteForceOnRandomPoints2D) {
    const std::array<bool, 2> p{true, true};
    check_random<2>({{Vec<2>{{14.0, 14.0}}, p},
                     {Vec<2>{{20.0, 11.0}}, p},
                     {Vec<2>{{5.5, 20.0}}, p}, // 2 cells along x: the whole stencil
                     {Vec<2>{{7.2, 20.0}}, p}, // 2 cells of r_list, 2 colour blocks along y
                     {Vec<2>{{41.0, 5.5}}, p}, // y 2 cells: the whole stencil, x one block
                     {Vec<2>{{40.0, 12.0}}, p}},
                    2.0, 0.5, 0.8, 100);
    // dense: cells of r_list / 2 scanned two deep
    check_random<2>({{Vec<2>{{16.0, 16.0}}, p}, {Vec<2>{{6.0, 18.0}}, p}}, 2.0, 0.5, 3.0, 200);
}

TEST(NeighborListShear, MatchesBruteForceOnRandomPoints3D) {
    const std::array<bool, 3> p{true, true, true}, z_walls{true, true, false};
    check_random<3>({{Vec<3>{{8.0, 8.0, 8.0}}, p},
                     {Vec<3>{{8.0, 8.0, 7.0}}, z_walls},
                     {Vec<3>{{5.5, 9.0, 9.0}}, p},
                     {Vec<3>{{15.0, 4.0, 9.0}}, p}, // y 2 cells: the whole stencil
                     {Vec<3>{{12.0, 9.0, 6.0}}, p}},
                    1.5, 0.3, 0.8, 300);
    check_random<3>({{Vec<3>{{9.0, 9.0, 9.0}}, p}}, 2.5, 0.3, 0.85, 400);
}

// Large systems take colour blocks wider than two cells: the rows across the sheared
// faces must still leave the chunks of one colour writing apart.
TEST(NeighborListShear, ColoursWriteApartInLargeSystems) {
    const int saved = omp_get_max_threads();
    omp_set_num_threads(2);
    for (double off : {0.0, 37.25, -123.4, 249.9}) {
        const Box<2> big = sheared(Box<2>(Vec<2>{{500.0, 500.0}}, {true, true}), off);
        check_colouring([&] {
            NeighborList<2> nl(big, 2.1, 1.0);
            nl.build(test::random_positions(big, 60000, 91, 6));
            EXPECT_GT(nl.block_width(), 2);
            return nl;
        }());
        // y one block, x many: x must become one block
        const Box<2> flat = sheared(Box<2>(Vec<2>{{500.0, 9.0}}, {true, true}), off);
        check_against_brute_force(flat, test::random_positions(flat, 3600, 92, 6), 2.1, 1.0);
    }
    omp_set_num_threads(saved);
}

// needs_rebuild's purpose under shear: while it says no, every pair now within r_cut is
// in the rows, as the particles walk and the offset slides (by up to the skin a step, so
// that some steps jump past it).
template <int D>
void walk(const Box<D>& start, std::size_t n, double r_cut, double skin, std::uint64_t seed,
          int& missing_seen, int& kept) {
    Box<D> box = start;
    auto pos = test::random_positions(box, n, seed, 4);
    NeighborList<D> nl(box, r_cut, skin);
    nl.build(pos);
    PairSet rows = listed_pairs(nl);
    double offset = box.shear_offset();
    for (std::uint32_t step = 0; step < 60; ++step) {
        CounterRng slide(seed, RngStream::placement, 777, step);
        offset += slide.uniform(0.0, skin);
        box.set_shear_offset(offset);
        nl.set_shear_offset(box.shear_offset());
        for (std::size_t i = 0; i < n; ++i) {
            CounterRng rng(seed, RngStream::thermostat, static_cast<std::uint32_t>(i), step);
            for (int a = 0; a < D; ++a) pos[i][a] += skin / 8.0 * rng.normal();
            box.wrap(pos[i]);
        }
        const bool rebuild = nl.needs_rebuild(pos);
        bool missing = false;
        for (const auto& pr : brute_pairs(box, pos, r_cut))
            missing = missing || !std::binary_search(rows.begin(), rows.end(), pr);
        missing_seen += missing ? 1 : 0;
        if (missing && !rebuild)
            ADD_FAILURE() << describe(box) << ", seed " << seed << ", step " << step
                          << ": a pair within r_cut is missing and no rebuild is asked for";
        if (!rebuild) {
            ++kept;
            continue;
        }
        nl.build(pos);
        rows = listed_pairs(nl);
    }
}

TEST(NeighborListShear, NoPairWithinTheCutoffIsMissingAsTheImagesSlide) {
    int missing = 0, kept = 0;
    std::uint64_t seed = 50;
    for (double skin : {0.3, 0.8}) {
        walk(sheared(Box<2>(Vec<2>{{14.0, 14.0}}, {true, true}), 3.1), 400, 1.5, skin, ++seed,
             missing, kept);
        walk(sheared(Box<2>(Vec<2>{{6.0, 14.0}}, {true, true}), -1.7), 200, 1.2, skin, ++seed,
             missing, kept);
        walk(sheared(Box<3>(Vec<3>{{8.0, 8.0, 8.0}}, {true, true, true}), 0.0), 500, 1.5, skin,
             ++seed, missing, kept);
    }
    // both sides of the rule were exercised
    EXPECT_GT(missing, 10);
    EXPECT_GT(kept, 30);
}

// The offset alone: a still square lattice (spacing 1) built at offset 0, r_cut 1.2,
// skin 0.2 (r_list 1.4). Across the y faces the pairs sit at (dx - s, 1) for integer dx
// once the offset has slid by s: those at dx = 1 were sqrt(2) > r_list apart at the build,
// unlisted, and come within r_cut beyond s = 1 - sqrt(0.44) = 0.337.
TEST(NeighborListShear, TheOffsetsSlideAloneAsksForARebuild) {
    const int n = 8;
    Box<2> box = sheared(Box<2>(Vec<2>{{double(n), double(n)}}, {true, true}), 0.0);
    std::vector<Vec<2>> pos;
    for (int y = 0; y < n; ++y)
        for (int x = 0; x < n; ++x) pos.push_back(Vec<2>{{x - 0.5 * n, y - 0.5 * n}});
    const double r_cut = 1.2, skin = 0.2;
    NeighborList<2> nl(box, r_cut, skin);
    nl.build(pos);
    const PairSet rows = listed_pairs(nl);
    auto slide = [&](double s) {
        box.set_shear_offset(s);
        nl.set_shear_offset(s);
        bool missing = false;
        for (const auto& pr : brute_pairs(box, pos, r_cut))
            missing = missing || !std::binary_search(rows.begin(), rows.end(), pr);
        return missing;
    };
    // slid by less than the skin, with no motion: nothing can be missing
    for (double s : {0.05, 0.19, -0.19}) {
        EXPECT_FALSE(slide(s));
        EXPECT_FALSE(nl.needs_rebuild(pos)) << "offset " << s;
        EXPECT_FALSE(nl.moved_half_skin(pos)) << "offset " << s;
    }
    for (double s : {0.35, -0.35}) {
        EXPECT_TRUE(slide(s)) << "the case must bring an unlisted pair within r_cut";
        EXPECT_TRUE(nl.needs_rebuild(pos)) << "offset " << s;
        EXPECT_TRUE(nl.moved_half_skin(pos)) << "offset " << s;
    }
    // slid by a whole box: the images are those of the build
    EXPECT_FALSE(slide(n));
    EXPECT_FALSE(nl.needs_rebuild(pos));
}

} // namespace
