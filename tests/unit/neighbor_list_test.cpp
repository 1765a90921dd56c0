// NeighborList: the rows hold exactly the brute-force pairs within r_list, each once
// (periodic, walled and mixed boxes, axes with 1, 2 and 3 cells, elongated boxes,
// clusters, positions just outside a periodic box), the colouring of the row sweep
// never lets two blocks of one colour write the same particle, the rows do not depend
// on the thread count, moved_half_skin follows the skin/2 rule without mistaking a
// periodic wrap for motion (needs_rebuild: neighbor_list_rebuild_brute_force_test), buffers are
// reused, and bad parameters are reported by name.
#include "support/soft_builder.hpp"

#include "pedesis/core/rng.hpp"
#include "pedesis/spatial/neighbor_list.hpp"

#include <gtest/gtest.h>
#include <omp.h>

#include <algorithm>
#include <atomic>
#include <cmath>
#include <iterator>
#include <limits>
#include <string>
#include <utility>
#include <vector>

#include "support/neighbor_rows.hpp"
#include "support/random_positions.hpp"

using namespace pedesis;

namespace {

using PairList = std::vector<std::pair<std::uint32_t, std::uint32_t>>;

// Half the particles packed into a ball around the box corner (so that on periodic axes
// the cluster straddles the boundary), as in a phase-separated active system: cells
// with many particles next to nearly empty ones.
template <int D>
std::vector<Vec<D>> clustered_positions(const Box<D>& box, std::size_t n, double radius,
                                        std::uint64_t seed) {
    auto pos = test::random_positions(box, n, seed, 6);
    for (std::size_t i = n / 2; i < n; ++i) {
        CounterRng rng(seed, RngStream::orientation, static_cast<std::uint32_t>(i));
        Vec<D> d;
        do {
            for (int a = 0; a < D; ++a) d[a] = rng.uniform(-radius, radius);
        } while (norm2(d) > radius * radius);
        for (int a = 0; a < D; ++a)
            pos[i][a] = box.periodic(a) ? box.lo(a) + d[a] : box.lo(a) + std::abs(d[a]);
        box.wrap(pos[i]);
    }
    return pos;
}

// Pairs (i, j) with i < j, sorted.
template <int D> PairList brute_pairs(const Box<D>& box, const std::vector<Vec<D>>& pos, double r) {
    PairList s;
    for (std::uint32_t i = 0; i < pos.size(); ++i)
        for (std::uint32_t j = i + 1; j < pos.size(); ++j)
            if (norm2(box.minimum_image(pos[i] - pos[j])) < r * r) s.push_back({i, j});
    return s;
}

template <int D> struct Case {
    Vec<D> L;
    std::array<bool, D> periodic;
    double r_cut, skin;
};

template <int D>
void check_against_brute_force(const Box<D>& box, const std::vector<Vec<D>>& pos, double r_cut,
                               double skin) {
    NeighborList<D> nl(box, r_cut, skin);
    nl.build(pos);
    SCOPED_TRACE(test::describe_box(box) + " r_cut " + std::to_string(r_cut) + " skin " +
                 std::to_string(skin));
    const std::size_t n = pos.size();
    ASSERT_EQ(nl.size(), n);
    std::size_t total = 0;
    for (std::uint32_t i = 0; i < n; ++i) {
        total += nl.count(i);
        EXPECT_EQ(nl.end(i) - nl.begin(i), static_cast<std::ptrdiff_t>(nl.count(i)));
    }
    EXPECT_EQ(total, nl.entries());
    // every pair closer than r_list, none twice, and none further than r_list to within the
    // list's rounding margin (a relative 1e-12 on r^2: pairs a few ulps from r_list
    // round either way)
    const PairList expect = brute_pairs(box, pos, nl.r_list());
    EXPECT_GT(expect.size(), 0u) << "case too sparse to test anything";
    const PairList listed = test::listed_pairs(nl);
    EXPECT_EQ(std::adjacent_find(listed.begin(), listed.end()), listed.end()) << "a pair twice";
    PairList missing, extra;
    std::set_difference(expect.begin(), expect.end(), listed.begin(), listed.end(),
                        std::back_inserter(missing));
    const PairList outer = brute_pairs(box, pos, nl.r_list() * (1.0 + 1e-12));
    std::set_difference(listed.begin(), listed.end(), outer.begin(), outer.end(),
                        std::back_inserter(extra));
    EXPECT_TRUE(missing.empty()) << missing.size() << " pairs missing, the first ("
                                 << (missing.empty() ? 0 : missing[0].first) << ", "
                                 << (missing.empty() ? 0 : missing[0].second) << ")";
    EXPECT_TRUE(extra.empty()) << extra.size() << " pairs beyond r_list";
    test::check_colouring(nl);
}

template <int D> void check_against_brute_force(const Case<D>& c, std::uint64_t seed) {
    const Box<D> box(c.L, c.periodic);
    const auto n = static_cast<std::size_t>(std::clamp(0.8 * box.volume(), 30.0, 1500.0));
    check_against_brute_force(box, test::random_positions(box, n, seed, 6), c.r_cut, c.skin);
}

TEST(NeighborList, MatchesBruteForce2D) {
    const std::vector<Case<2>> cases = {
        {{{20.0, 20.0}}, {true, true}, 2.0, 0.5},   // 8 x 8 cells
        {{{20.0, 20.0}}, {false, false}, 2.0, 0.5}, // walls
        {{{20.0, 13.0}}, {true, false}, 2.0, 0.5},  // mixed
        {{{13.0, 20.0}}, {false, true}, 1.5, 0.3},  // mixed the other way
        {{{5.5, 5.5}}, {true, true}, 2.0, 0.5},     // L = 2.2 r_list: 2 cells per axis
        {{{5.0, 5.0}}, {true, true}, 2.0, 0.5},     // L = 2 r_list exactly
        {{{8.0, 5.5}}, {true, true}, 2.0, 0.5},     // 3 x 2 cells
        {{{60.0, 5.5}}, {true, true}, 2.0, 0.5},    // elongated
        {{{60.0, 1.5}}, {true, false}, 2.0, 0.5},   // 1 cell across a thin walled slab
        {{{3.0, 3.0}}, {false, false}, 2.0, 0.5},   // 1 cell in all
        {{{5.5, 40.0}}, {false, true}, 2.0, 0.5},   // 2 walled cells, long periodic axis
        {{{12.0, 12.0}}, {true, true}, 2.5, 0.0},   // no skin
    };
    for (std::size_t k = 0; k < cases.size(); ++k)
        for (std::uint64_t seed : {11u, 12u}) check_against_brute_force(cases[k], 100 * k + seed);
}

TEST(NeighborList, MatchesBruteForce3D) {
    const std::vector<Case<3>> cases = {
        {{{8.0, 8.0, 8.0}}, {true, true, true}, 1.2, 0.3},
        {{{8.0, 8.0, 8.0}}, {false, false, false}, 1.2, 0.3},
        {{{3.3, 3.3, 3.3}}, {true, true, true}, 1.2, 0.3},    // 2.2 r_list: 2 cells per axis
        {{{3.0, 8.0, 4.0}}, {true, true, false}, 1.2, 0.3},   // 2 r_list exactly on x
        {{{15.0, 3.3, 1.0}}, {true, true, false}, 1.2, 0.3},  // elongated, 1 walled cell
        {{{4.6, 20.0, 3.3}}, {true, false, true}, 1.2, 0.3},  // 3, 13 and 2 cells
        {{{1.2, 1.4, 30.0}}, {false, false, true}, 1.0, 0.2}, // a walled channel
    };
    for (std::size_t k = 0; k < cases.size(); ++k)
        for (std::uint64_t seed : {21u, 22u}) check_against_brute_force(cases[k], 100 * k + seed);
}

// Dense systems with long cutoffs (more than 8 particles per r_list^D) use cells of
// r_list / 2 and a stencil two cells deep: the same pairs.
TEST(NeighborList, MatchesBruteForceWithHalfWidthCells) {
    const std::vector<Case<3>> cases3 = {
        {{{12.0, 12.0, 12.0}}, {true, true, true}, 2.5, 0.3}, // 8 cells per axis
        {{{12.0, 12.0, 12.0}}, {false, false, false}, 2.5, 0.3},
        {{{8.0, 12.0, 6.0}}, {true, false, true}, 2.5, 0.3}, // 5, 8 and 4 cells
    };
    for (std::size_t k = 0; k < cases3.size(); ++k) check_against_brute_force(cases3[k], 500 + k);
    const std::vector<Case<2>> cases2 = {
        {{{20.0, 20.0}}, {true, true}, 3.0, 0.5},
        {{{20.0, 9.0}}, {true, false}, 3.0, 0.5},
    };
    for (std::size_t k = 0; k < cases2.size(); ++k) check_against_brute_force(cases2[k], 600 + k);
}

TEST(NeighborList, MatchesBruteForceClustered) {
    for (bool periodic : {true, false}) {
        const Box<2> box2(Vec<2>{{30.0, 24.0}}, {periodic, true});
        check_against_brute_force(box2, clustered_positions(box2, 1200, 3.0, 41), 2.0, 0.5);
        const Box<3> box3(Vec<3>{{9.0, 7.0, 8.0}}, {periodic, true, !periodic});
        check_against_brute_force(box3, clustered_positions(box3, 1000, 1.6, 42), 1.2, 0.3);
    }
}

// Between wrapping and the next build a particle may sit a little outside a periodic
// box; its cell and its minimum image must still come out right.
// Perfect fcc crystals at in.lj's density (0.8442) with Lennard-Jones cutoffs and skins:
// every cell holds the same number of particles and every row the most candidates, the
// geometry whose build once repeated its pass for ever (4000 atoms, cut 2.5, skin 0.3:
// the storage grown after an overflow was again too small). m^3 unit cells, m = 3..12.
TEST(NeighborList, MatchesBruteForceOnPerfectFccLattices) {
    for (int m = 3; m <= 12; ++m)
        for (const auto& [r_cut, skin] : {std::pair{2.5, 0.3}, {2.5, 0.5}, {3.0, 0.3}}) {
            const auto s = test::fcc_soft_state(m, 0.8442);
            if (s.box.length(0) < 2.0 * (r_cut + skin)) continue;
            SCOPED_TRACE("fcc " + std::to_string(m) + "^3 cells");
            check_against_brute_force(s.box, s.p.position, r_cut, skin);
        }
}

// A simple cubic (3D) or square (2D) lattice of n sites per axis, spacing a, in a
// periodic box of n a: sites exactly on -L/2 and on every cell face the grid puts at a
// multiple of a.
template <int D> std::vector<Vec<D>> cubic_lattice(int n, double a) {
    std::vector<Vec<D>> pos;
    std::array<int, D> c{};
    const double half = 0.5 * n * a;
    while (true) {
        Vec<D> r;
        for (int k = 0; k < D; ++k) r[k] = c[k] * a - half;
        pos.push_back(r);
        int k = 0;
        while (k < D && ++c[k] == n) c[k++] = 0;
        if (k == D) break;
    }
    return pos;
}

// Degenerate geometry against brute force: lattices whose box is an exact multiple of
// the list range (cells of exactly r_list or r_list / 2), and one ulp either side of it;
// a site exactly at -L/2 and one a ulp inside +L/2 on every axis; skins from 0 to more
// than the cutoff; 1 and 2 threads on lattices large enough to run in parallel. Each
// failure names its case.
template <int D> void check_lattices_at_multiples_of_the_range(const std::vector<int>& sizes) {
    const int saved = omp_get_max_threads();
    int cases = 0;
    for (int n : sizes)
        for (int per_range : {2, 3}) // lattice spacings per list range
            for (int nudge : {-1, 0, 1})
                for (double skin_fraction : {0.0, 0.25, 1.5})
                    for (int threads : {1, 2}) {
                        const double a = 1.0;
                        std::vector<Vec<D>> pos = cubic_lattice<D>(n, a);
                        double L = n * a;
                        if (nudge != 0) L = std::nextafter(L, nudge > 0 ? 2.0 * L : 0.0);
                        Vec<D> tip;
                        for (int k = 0; k < D; ++k) tip[k] = std::nextafter(0.5 * L, 0.0);
                        pos.push_back(tip);
                        const double r_list = per_range * a;
                        if (L < 2.0 * r_list) continue;
                        // below 4096 particles the build runs serially whatever the thread
                        // count: a second thread would repeat the same case
                        if (threads > 1 && pos.size() < 4096) continue;
                        const double r_cut = r_list / (1.0 + skin_fraction);
                        std::array<bool, D> periodic;
                        periodic.fill(true);
                        omp_set_num_threads(threads);
                        SCOPED_TRACE("lattice " + std::to_string(n) + "^" + std::to_string(D) +
                                     ", L = n a " +
                                     (nudge ? (nudge > 0 ? "+ 1 ulp" : "- 1 ulp") : "exactly") +
                                     ", r_list = " + std::to_string(per_range) +
                                     " a, skin = " + std::to_string(skin_fraction) +
                                     " r_cut, threads " + std::to_string(threads));
                        check_against_brute_force(Box<D>(Vec<D>::filled(L), periodic), pos, r_cut,
                                                  r_list - r_cut);
                        ++cases;
                    }
    omp_set_num_threads(saved);
    EXPECT_GT(cases, 0);
}

TEST(NeighborList, MatchesBruteForceOnSquareLatticesAtMultiplesOfTheRange) {
    check_lattices_at_multiples_of_the_range<2>({4, 5, 6, 7, 8, 9, 12, 16, 20, 33, 65});
}

TEST(NeighborList, MatchesBruteForceOnCubicLatticesAtMultiplesOfTheRange) {
    check_lattices_at_multiples_of_the_range<3>({4, 5, 6, 7, 8, 9, 12, 17});
}

TEST(NeighborList, MatchesBruteForceWithPositionsJustOutsideThePeriodicBox) {
    const Box<2> box(Vec<2>{{20.0, 11.0}}, {true, true});
    auto pos = test::random_positions(box, 600, 8, 6);
    std::size_t moved = 0;
    for (auto& r : pos)
        for (int a = 0; a < 2; ++a)
            if (r[a] < box.lo(a) + 0.2 * box.length(a)) {
                r[a] += box.length(a); // the same point of the torus, outside the box
                ++moved;
            }
    ASSERT_GT(moved, 100u);
    check_against_brute_force(box, pos, 2.0, 0.5);
}

// Colours: 2 per axis where an axis has 2 blocks or more, else 1. Blocks are 2 cells
// wide (the whole of a periodic axis shorter than 4 cells), and a periodic axis of 4
// cells or more has a multiple of 4. With r_list 2.5: 20 / 2.5 = 8 cells, 4 blocks;
// 5.5 / 2.5 = 2 periodic cells, one block; 5.0 / 2.5 = 2 cells between walls, one
// block; 12.5 / 2.5 = 5 cells between walls, blocks of 2, 2 and 1. In 3D,
// 8 / 1.5 = 5 periodic cells become 4, 2 blocks.
TEST(NeighborList, ColoursFollowTheBlocks) {
    auto colours = [](const Box<2>& box) {
        NeighborList<2> nl(box, 2.0, 0.5);
        return nl.colours();
    };
    EXPECT_EQ(colours(Box<2>(Vec<2>{{20.0, 20.0}}, {true, true})), 4);
    EXPECT_EQ(colours(Box<2>(Vec<2>{{20.0, 20.0}}, {false, false})), 4);
    EXPECT_EQ(colours(Box<2>(Vec<2>{{20.0, 5.5}}, {true, true})), 2);
    EXPECT_EQ(colours(Box<2>(Vec<2>{{5.0, 5.5}}, {false, true})), 1);
    EXPECT_EQ(colours(Box<2>(Vec<2>{{12.5, 5.5}}, {false, true})), 2);
    NeighborList<3> nl3(Box<3>(Vec<3>{{8.0, 8.0, 8.0}}, {true, true, true}), 1.2, 0.3);
    EXPECT_EQ(nl3.colours(), 8);
}

// Chunks of one colour run at the same time: no particle may be written (as a row's
// owner or as an entry of its row) by two of them. Large systems take blocks wider than
// two cells (set_grid); the colouring must keep their writes apart all the same, on
// random points and on a lattice whose points lie on the cell faces.
template <int D>
void check_colours_write_apart(const Box<D>& box, const std::vector<Vec<D>>& pos, double r_cut,
                               double skin, int expected_width) {
    SCOPED_TRACE(test::describe_box(box));
    NeighborList<D> nl(box, r_cut, skin);
    nl.build(pos);
    EXPECT_EQ(nl.block_width(), expected_width);
    std::vector<std::size_t> seen(pos.size());
    std::size_t rows = 0;
    for (int k = 0; k < nl.colours(); ++k) {
        const auto [first, last] = nl.chunks_of_colour(k);
        std::fill(seen.begin(), seen.end(), std::size_t(-1));
        for (std::size_t c = first; c < last; ++c) {
            auto mark = [&](std::uint32_t p) {
                ASSERT_TRUE(seen[p] == std::size_t(-1) || seen[p] == c)
                    << "particle " << p << " written by chunks " << seen[p] << " and " << c
                    << " of colour " << k;
                seen[p] = c;
            };
            for (std::uint32_t i : nl.chunk(c)) {
                ++rows;
                mark(i);
                for (const std::uint32_t* j = nl.begin(i); j != nl.end(i); ++j) mark(*j);
            }
        }
    }
    EXPECT_EQ(rows, pos.size());
}

TEST(NeighborList, WideBlocksOfOneColourWriteApart) {
    // 2D, r_list 3.1: 161 cells along, rounded to 160 (cells of 3.125) for blocks of 10
    // (8 blocks of each colour along an axis at most)
    const Box<2> big(Vec<2>{{500.0, 500.0}}, {true, true});
    check_colours_write_apart(big, test::random_positions(big, 99000, 91, 6), 2.1, 1.0, 10);
    std::vector<Vec<2>> lattice; // spacing 1.5625: a point on every cell face
    for (int x = 0; x < 320; ++x)
        for (int y = 0; y < 320; ++y)
            lattice.push_back(Vec<2>{{-250.0 + 1.5625 * x, -250.0 + 1.5625 * y}});
    check_colours_write_apart(big, lattice, 2.1, 1.0, 10);
    // walls: no rounding, and the last block is narrower
    const Box<2> walled(Vec<2>{{500.0, 400.0}}, {false, false});
    check_colours_write_apart(walled, test::random_positions(walled, 80000, 92, 6), 2.1, 1.0, 8);
    // 3D, r_list 1.5: 49 cells, 48 for blocks of 12 (two blocks of each colour along an
    // axis; the narrowest blocks, of 2, round to 48 cells too)
    const Box<3> cube(Vec<3>{{75.0, 75.0, 75.0}}, {true, true, true});
    check_colours_write_apart(cube, test::random_positions(cube, 100000, 93, 6), 1.2, 0.3, 12);
    // in.lj's box with the WCA cutoff: r_list 1.42, 23 cells, 20 for blocks of 5 as of 2
    const Box<3> wca(Vec<3>::filled(33.59192382765015), {true, true, true});
    check_colours_write_apart(wca, test::random_positions(wca, 32000, 96, 6),
                              std::pow(2.0, 1.0 / 6.0), 0.3, 5);
    // the widest blocks: 516 cells along, 512 for blocks of 32
    const Box<2> huge(Vec<2>{{1600.0, 1600.0}}, {true, true});
    check_colours_write_apart(huge, test::random_positions(huge, 200000, 95, 6), 2.1, 1.0, 32);
    // a small system keeps blocks of two cells
    const Box<2> small(Vec<2>{{60.0, 60.0}}, {true, true});
    check_colours_write_apart(small, test::random_positions(small, 1400, 94, 6), 2.1, 1.0, 2);
}

// Rows identical (content and order) with 1, 2 and 3 threads, so force sums are too.
template <int D>
void check_thread_independence(const Box<D>& box, const std::vector<Vec<D>>& pos, double r_cut,
                               double skin) {
    SCOPED_TRACE(test::describe_box(box) + " r_cut " + std::to_string(r_cut) + " skin " +
                 std::to_string(skin));
    const int saved = omp_get_max_threads();
    // (where the rows lie in storage may differ: each thread writes into its own chunks)
    std::vector<std::vector<std::uint32_t>> rows1;
    for (int threads : {1, 2, 3}) {
        omp_set_num_threads(threads);
        NeighborList<D> nl(box, r_cut, skin);
        nl.build(pos);
        nl.build(pos); // the second build reuses the storage the first one sized
        std::vector<std::vector<std::uint32_t>> rows(pos.size());
        for (std::size_t i = 0; i < pos.size(); ++i) rows[i].assign(nl.begin(i), nl.end(i));
        if (threads == 1) {
            rows1 = rows;
            EXPECT_GT(nl.entries(), pos.size());
        } else {
            EXPECT_EQ(rows, rows1) << threads << " threads";
        }
    }
    omp_set_num_threads(saved);
}

TEST(NeighborList, SameRowsWhateverTheThreadCount) {
    // large enough for build() to go parallel
    const double L = std::sqrt(20000 / 0.4);
    for (bool periodic : {true, false}) {
        const Box<2> box(Vec<2>{{L, L}}, {periodic, periodic});
        check_thread_independence(box, test::random_positions(box, 20000, 77, 6), 2.0, 0.5);
        check_thread_independence(box, clustered_positions(box, 20000, 40.0, 78), 2.0, 0.5);
    }
    const Box<3> box3(Vec<3>{{24.0, 24.0, 24.0}}, {true, true, false});
    check_thread_independence(box3, test::random_positions(box3, 11000, 79, 6), 1.2, 0.3);
}

// The threads' first runs of each colour, as sweep positions for the per-particle loops:
// each colour's runs start where its chunks do and end where the next colour's start,
// cut only at chunk starts; and for_each_chunk, whatever the team, visits every row once.
TEST(NeighborList, ThreadSharesFollowTheColoursChunks) {
    const int saved = omp_get_max_threads();
    const Box<2> box(Vec<2>{{120.0, 120.0}}, {true, true});
    const auto pos = test::random_positions(box, 5000, 81, 6);
    for (int threads : {1, 2, 3}) {
        omp_set_num_threads(threads);
        NeighborList<2> nl(box, 2.0, 0.5);
        nl.build(pos);
        const std::vector<std::int64_t> b = nl.thread_share_bounds();
        const auto at = [&](std::size_t c) {
            return static_cast<std::int64_t>(nl.chunk(c).data() - nl.sweep_order().data());
        };
        ASSERT_EQ(b.size(), static_cast<std::size_t>(nl.colours() * threads + 1));
        EXPECT_TRUE(std::is_sorted(b.begin(), b.end()));
        EXPECT_EQ(b.back(), static_cast<std::int64_t>(pos.size()));
        std::vector<std::int64_t> starts; // every chunk's start
        for (std::size_t c = 0; c < nl.chunks_of_colour(nl.colours() - 1)[1]; ++c)
            starts.push_back(at(c));
        for (int k = 0; k < nl.colours(); ++k) {
            EXPECT_EQ(b[static_cast<std::size_t>(k * threads)], at(nl.chunks_of_colour(k)[0]));
            for (int t = 0; t < threads; ++t)
                EXPECT_TRUE(std::binary_search(starts.begin(), starts.end(),
                                               b[static_cast<std::size_t>(k * threads + t)]));
        }
        std::vector<std::atomic<int>> visits(pos.size());
        nl.for_each_chunk([&](std::span<const std::uint32_t> rows) {
            for (std::uint32_t i : rows) ++visits[i];
        });
        int wrong = 0;
        for (const auto& v : visits) wrong += v.load() != 1;
        EXPECT_EQ(wrong, 0) << threads << " threads";
    }
    omp_set_num_threads(saved);
}

TEST(NeighborList, MovedHalfSkinFollowsTheSkinHalf) {
    const double skin = 0.4, half = 0.5 * skin;
    const Box<2> box(Vec<2>{{20.0, 20.0}}, {true, false});
    auto pos = test::random_positions(box, 400, 9, 6);
    NeighborList<2> nl(box, 2.0, skin);
    EXPECT_TRUE(nl.moved_half_skin(pos)) << "never built";
    nl.build(pos);
    EXPECT_FALSE(nl.moved_half_skin(pos));

    // every particle just under skin/2, in random directions
    auto moved = pos;
    for (std::size_t i = 0; i < moved.size(); ++i) {
        CounterRng rng(3, RngStream::velocity, static_cast<std::uint32_t>(i));
        const double phi = rng.uniform(0.0, 6.283185307179586);
        moved[i] += 0.99 * half * Vec<2>{{std::cos(phi), std::sin(phi)}};
        box.wrap(moved[i]);
    }
    EXPECT_FALSE(nl.moved_half_skin(moved));

    // one particle just over skin/2, along the periodic and along the walled axis
    for (int a = 0; a < 2; ++a) {
        auto one = moved;
        one[200] = pos[200];
        one[200][a] += (pos[200][a] < 0 ? 1.01 : -1.01) * half;
        EXPECT_TRUE(nl.moved_half_skin(one)) << "axis " << a;
    }
    auto diag = moved;
    diag[17] = pos[17] + Vec<2>::filled(1.01 * half / std::sqrt(2.0));
    box.wrap(diag[17]);
    EXPECT_TRUE(nl.moved_half_skin(diag));

    nl.build(diag);
    EXPECT_FALSE(nl.moved_half_skin(diag)) << "reference positions not updated by build";
    EXPECT_TRUE(nl.moved_half_skin(pos)) << "reference positions not updated by build";

    auto fewer = diag;
    fewer.pop_back();
    EXPECT_TRUE(nl.moved_half_skin(fewer)) << "particle count changed";
}

TEST(NeighborList, PeriodicWrapIsNotMotion) {
    const double skin = 0.4, half = 0.5 * skin;
    const Box<2> box(Vec<2>{{20.0, 20.0}}, {true, true});
    auto pos = test::random_positions(box, 100, 4, 6);
    pos[0] = Vec<2>{{box.hi(0) - 0.05, 1.0}};  // about to leave through +x
    pos[1] = Vec<2>{{-3.0, box.lo(1) + 0.02}}; // about to leave through -y
    NeighborList<2> nl(box, 2.0, skin);
    nl.build(pos);

    for (double step : {0.5 * half, 0.99 * half}) {
        auto p = pos;
        p[0][0] += step;
        p[1][1] -= step;
        box.wrap(p[0]);
        box.wrap(p[1]);
        ASSERT_LT(p[0][0], 0.0) << "test setup: particle 0 should have wrapped";
        ASSERT_GT(p[1][1], 0.0) << "test setup: particle 1 should have wrapped";
        EXPECT_FALSE(nl.moved_half_skin(p)) << "wrap of a particle moved by " << step;
        EXPECT_FALSE(nl.needs_rebuild(p)) << "wrap of a particle moved by " << step;
    }
    for (int k = 0; k < 2; ++k) {
        auto p = pos;
        if (k == 0)
            p[0][0] += 1.01 * half;
        else
            p[1][1] -= 1.01 * half;
        box.wrap(p[k]);
        EXPECT_TRUE(nl.moved_half_skin(p))
            << "particle " << k << " moved over skin/2 across the edge";
    }
}

TEST(NeighborList, ZeroSkinRebuildsOnAnyMotion) {
    const Box<2> box(Vec<2>{{10.0, 10.0}}, {true, true});
    auto pos = test::random_positions(box, 50, 2, 6);
    NeighborList<2> nl(box, 2.0, 0.0);
    nl.build(pos);
    EXPECT_FALSE(nl.needs_rebuild(pos));
    pos[7][0] += 1e-9;
    EXPECT_TRUE(nl.needs_rebuild(pos));
}

// Free particles in a large box (only one-body forces: r_list is the skin) keep a grid of
// a few cells per particle, widened cells holding the same pairs, from construction on.
// (A 3D box 200 wide took 406^3 cells, 256 MB, whatever N.)
TEST(NeighborList, SparseBoxesKeepTheirGridSmall) {
    for (bool periodic : {true, false}) {
        const Box<3> box3(Vec<3>::filled(200.0), {periodic, true, !periodic});
        const auto pos3 = clustered_positions(box3, 1000, 2.0, 51);
        check_against_brute_force(box3, pos3, 1e-3, 0.5);
        NeighborList<3> nl3(box3, 1e-3, 0.5);
        EXPECT_LT(nl3.memory_bytes(), std::size_t{1} << 20) << "before the first build";
        nl3.build(pos3);
        EXPECT_LT(nl3.memory_bytes(), 1000 * 200 + (std::size_t{1} << 20));
        const Box<2> box2(Vec<2>::filled(4000.0), {true, periodic});
        const auto pos2 = clustered_positions(box2, 2000, 3.0, 52);
        check_against_brute_force(box2, pos2, 1e-3, 0.5);
        NeighborList<2> nl2(box2, 1e-3, 0.5);
        nl2.build(pos2);
        EXPECT_LT(nl2.memory_bytes(), 2000 * 200 + (std::size_t{1} << 20));
    }
}

TEST(NeighborList, CountsBuildsAndReusesBuffers) {
    const std::size_t n = 36000;
    const double L = std::sqrt(n / 0.4);
    const Box<2> box(Vec<2>{{L, L}}, {true, true});
    auto pos = test::random_positions(box, n, 31, 6);
    NeighborList<2> nl(box, 2.0, 0.5);
    EXPECT_EQ(nl.builds(), 0u);
    nl.build(pos);
    EXPECT_EQ(nl.builds(), 1u);
    const auto* nb = nl.storage();
    const std::size_t bytes = nl.memory_bytes();
    // the soft engine's budget is 200 bytes per particle in all (2D, density 0.4,
    // r_list 2.5); the list may take under half of it (82 here: the rows with their
    // headroom, the cell order, and the build's positions in cell and storage order)
    EXPECT_LT(static_cast<double>(bytes) / n, 90.0);
    EXPECT_GT(static_cast<double>(bytes) / n, 4.0 * 7.0) << "memory_bytes misses the rows";

    for (int k = 0; k < 3; ++k) {
        for (std::size_t i = 0; i < n; ++i) {
            CounterRng rng(7, RngStream::velocity, static_cast<std::uint32_t>(i),
                           static_cast<std::uint32_t>(k));
            pos[i] += Vec<2>{{rng.uniform(-0.3, 0.3), rng.uniform(-0.3, 0.3)}};
            box.wrap(pos[i]);
        }
        nl.build(pos);
    }
    EXPECT_EQ(nl.builds(), 4u);
    EXPECT_EQ(nl.storage(), nb) << "rows reallocated on a rebuild";
    EXPECT_EQ(nl.memory_bytes(), bytes);
}

template <class F> std::string error_of(F&& f) {
    try {
        f();
    } catch (const InputError& e) {
        return e.what();
    }
    return "(no InputError)";
}

TEST(NeighborList, RejectsBadParametersByName) {
    const Box<2> box(Vec<2>{{20.0, 20.0}}, {true, true});
    const double nan = std::numeric_limits<double>::quiet_NaN();
    const double inf = std::numeric_limits<double>::infinity();
    for (double r : {0.0, -1.0, nan, inf})
        EXPECT_NE(error_of([&] { NeighborList<2>(box, r, 0.5); }).find("r_cut"), std::string::npos)
            << "r_cut = " << r;
    for (double s : {-0.1, nan, inf})
        EXPECT_NE(error_of([&] { NeighborList<2>(box, 2.0, s); }).find("skin"), std::string::npos)
            << "skin = " << s;
    EXPECT_NO_THROW(NeighborList<2>(box, 2.0, 0.0));
}

TEST(NeighborList, RejectsPeriodicBoxShorterThanTwiceRList) {
    // r_list = 2.5: the y axis (4.9) is too short, x is fine
    const std::string msg = error_of([] {
        NeighborList<2>(Box<2>(Vec<2>{{20.0, 4.9}}, {true, true}), 2.0, 0.5);
    });
    EXPECT_NE(msg.find("too small"), std::string::npos) << msg;
    EXPECT_NE(msg.find("axis 1"), std::string::npos) << msg;
    EXPECT_NE(msg.find("4.9"), std::string::npos) << msg;
    EXPECT_NE(msg.find("2.5"), std::string::npos) << msg;
    // the same short axis between walls needs no minimum image
    EXPECT_NO_THROW(NeighborList<2>(Box<2>(Vec<2>{{20.0, 4.9}}, {true, false}), 2.0, 0.5));
    EXPECT_NO_THROW(NeighborList<2>(Box<2>(Vec<2>{{20.0, 5.0}}, {true, true}), 2.0, 0.5));
    const std::string msg3 = error_of([] {
        NeighborList<3>(Box<3>(Vec<3>{{3.0, 3.0, 2.9}}, {true, true, true}), 1.2, 0.3);
    });
    EXPECT_NE(msg3.find("axis 2"), std::string::npos) << msg3;
}

TEST(NeighborList, BadPositionNamesTheParticle) {
    const Box<2> box(Vec<2>{{20.0, 20.0}}, {true, true});
    auto pos = test::random_positions(box, 30, 1, 6);
    NeighborList<2> nl(box, 2.0, 0.5);
    nl.build(pos);
    for (double x : {std::numeric_limits<double>::quiet_NaN(), 16.0}) {
        auto p = pos;
        p[13][1] = x;
        try {
            nl.build(p);
            ADD_FAILURE() << "no error for position " << x;
        } catch (const RunError& e) {
            EXPECT_NE(std::string(e.what()).find("particle 13"), std::string::npos) << e.what();
        }
        EXPECT_TRUE(nl.needs_rebuild(p));
        EXPECT_EQ(nl.size(), pos.size()) << "a failed build must leave the previous list";
        EXPECT_EQ(nl.builds(), 1u);
    }
}

} // namespace
