// CellList: for random configurations the pairs found through for_each_near within the
// cutoff are exactly the brute-force pairs, in periodic and walled boxes of several
// shapes, including axes with only 1 or 2 cells; and no particle is visited twice. The
// same for a reach of several cells (for_each_within, as the event engine's size classes
// use it), including axes with fewer cells than the reach spans.
#include "pedesis/core/rng.hpp"
#include "pedesis/spatial/cell_list.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <set>
#include <string>
#include <utility>
#include <vector>

#include "support/random_positions.hpp"

using namespace pedesis;

namespace {

template <int D>
std::set<std::pair<std::uint32_t, std::uint32_t>>
brute_pairs(const Box<D>& box, const std::vector<Vec<D>>& pos, double cutoff) {
    std::set<std::pair<std::uint32_t, std::uint32_t>> s;
    for (std::uint32_t i = 0; i < pos.size(); ++i)
        for (std::uint32_t j = i + 1; j < pos.size(); ++j)
            if (norm2(box.minimum_image(pos[i] - pos[j])) < cutoff * cutoff) s.insert({i, j});
    return s;
}

template <int D>
std::set<std::pair<std::uint32_t, std::uint32_t>>
cell_pairs(const Box<D>& box, const CellList<D>& cells, const std::vector<Vec<D>>& pos,
           double cutoff, const std::vector<bool>& present) {
    const int m = cells.cells_to_reach(cutoff);
    std::set<std::pair<std::uint32_t, std::uint32_t>> s;
    for (std::uint32_t i = 0; i < pos.size(); ++i) {
        if (!present[i]) continue;
        std::vector<int> visits(pos.size(), 0);
        cells.for_each_within(pos[i], m, [&](std::uint32_t j) {
            ++visits[j];
            if (j == i) return;
            if (norm2(box.minimum_image(pos[i] - pos[j])) < cutoff * cutoff)
                s.insert({std::min(i, j), std::max(i, j)});
        });
        for (std::uint32_t j = 0; j < pos.size(); ++j) {
            EXPECT_LE(visits[j], 1) << "particle " << j << " visited twice from " << i;
            if (!present[j]) {
                EXPECT_EQ(visits[j], 0) << "removed particle " << j << " still listed";
            }
        }
        EXPECT_EQ(visits[i], 1) << "particle " << i << " not found in its own cell";
    }
    return s;
}

template <int D>
void check_box(const Box<D>& box, double cutoff, std::size_t n, std::uint64_t seed,
               double min_cell = 0.0) {
    if (min_cell == 0.0) min_cell = cutoff;
    SCOPED_TRACE(test::describe_box(box) + " cutoff " + std::to_string(cutoff) + " cell " +
                 std::to_string(min_cell));
    auto pos = test::random_positions(box, n, seed, 4);
    CellList<D> cells(box, min_cell);
    for (int a = 0; a < D; ++a)
        EXPECT_GE(cells.cell_width(a), std::min(min_cell, box.length(a)) * (1 - 1e-12));
    cells.build(pos);
    std::vector<bool> present(n, true);
    const auto expected = brute_pairs(box, pos, cutoff);
    EXPECT_EQ(cell_pairs(box, cells, pos, cutoff, present), expected);

    // incremental: move a third of the particles (remove + insert), remove a few for good
    CounterRng rng(seed + 1000, RngStream::placement, 0);
    for (std::uint32_t i = 0; i < n; i += 3) {
        cells.remove(i);
        for (int a = 0; a < D; ++a) pos[i][a] = rng.uniform(box.lo(a), box.hi(a));
        box.wrap(pos[i]);
        cells.insert(i, pos[i]);
    }
    for (std::uint32_t i = 1; i < n; i += 7) {
        cells.remove(i);
        present[i] = false;
    }
    auto after = brute_pairs(box, pos, cutoff);
    std::erase_if(after, [&](const auto& pr) { return !present[pr.first] || !present[pr.second]; });
    EXPECT_EQ(cell_pairs(box, cells, pos, cutoff, present), after);
}

} // namespace

TEST(CellList, CellCountsAlongAxes) {
    Box<3> box(Vec<3>{{1.5, 3.5, 10.0}}, {true, true, false});
    CellList<3> cells(box, 1.5);
    EXPECT_EQ(cells.cells_along(0), 1);
    EXPECT_EQ(cells.cells_along(1), 2);
    EXPECT_EQ(cells.cells_along(2), 6);
    EXPECT_EQ(cells.cell_count(), 12u);
    // a box smaller than the cell still has one cell
    CellList<3> tiny(box, 100.0);
    EXPECT_EQ(tiny.cell_count(), 1u);
}

// A ratio of box to cell far outside int's range (a crafted checkpoint once gave 6.5e128,
// undefined behaviour in the cast) or NaN gives a capped grid, and far-off or NaN
// positions still land in a cell of the grid.
TEST(CellList, AbsurdRatiosGiveACappedGrid) {
    Box<2> box2(Vec<2>{{20.0, 20.0}}, {true, false});
    CellList<2> fine(box2, 3e-128);
    EXPECT_EQ(fine.cells_along(0), CellList<2>::max_cells_along);
    EXPECT_EQ(fine.cells_along(1), CellList<2>::max_cells_along);
    CellList<2> nan_cell(box2, std::nan(""));
    EXPECT_EQ(nan_cell.cell_count(), 1u);
    Box<3> huge(Vec<3>{{1e300, 1e300, 1e300}}, {true, true, true});
    CellList<3> sparse(huge, 1.0);
    EXPECT_LE(sparse.cell_count(), std::size_t{1} << 26);
    for (double x : {1e250, -1e250, std::nan("")}) {
        const auto c = fine.cell_index(Vec<2>{{x, x}});
        EXPECT_GE(c, 0) << x;
        EXPECT_LT(c, static_cast<std::int32_t>(fine.cell_count())) << x;
    }
    EXPECT_GE(fine.cells_to_reach(1e300), 1);
}

TEST(CellList, NeighbourCellsAreDistinct) {
    for (bool periodic : {true, false}) {
        for (double Lx : {1.0, 2.5, 3.5, 7.0}) {
            Box<2> box(Vec<2>{{Lx, 5.0}}, {periodic, periodic});
            CellList<2> cells(box, 1.0);
            for (std::int32_t c = 0; c < static_cast<std::int32_t>(cells.cell_count()); ++c) {
                std::vector<std::int32_t> seen;
                cells.for_each_neighbor_cell(c, [&](std::int32_t x) { seen.push_back(x); });
                std::sort(seen.begin(), seen.end());
                EXPECT_EQ(std::adjacent_find(seen.begin(), seen.end()), seen.end())
                    << "cell " << c << " Lx " << Lx << " periodic " << periodic;
                EXPECT_TRUE(std::binary_search(seen.begin(), seen.end(), c));
                for (auto x : seen) {
                    EXPECT_GE(x, 0);
                    EXPECT_LT(x, static_cast<std::int32_t>(cells.cell_count()));
                }
            }
        }
    }
}

TEST(CellList, MatchesBruteForce2D) {
    std::uint64_t seed = 1;
    // cutoff 1: axes with 1, 2, 3 and many cells; square and elongated boxes
    for (bool periodic : {true, false}) {
        for (const auto& L :
             {Vec<2>{{1.5, 1.5}}, Vec<2>{{2.5, 2.5}}, Vec<2>{{1.2, 9.0}}, Vec<2>{{2.9, 7.3}},
              Vec<2>{{3.0, 3.0}}, Vec<2>{{10.0, 10.0}}, Vec<2>{{17.3, 4.1}}}) {
            check_box(Box<2>(L, {periodic, periodic}), 1.0, 120, seed++);
        }
    }
    // mixed: one periodic axis, one walled
    check_box(Box<2>(Vec<2>{{2.2, 8.0}}, {true, false}), 1.0, 150, seed++);
    check_box(Box<2>(Vec<2>{{8.0, 1.7}}, {false, true}), 1.0, 150, seed++);
    // cutoff not dividing the box evenly, dense
    check_box(Box<2>(Vec<2>{{11.0, 6.0}}, {true, true}), 1.37, 400, seed++);
}

TEST(CellList, MatchesBruteForce3D) {
    std::uint64_t seed = 100;
    for (bool periodic : {true, false}) {
        for (const auto& L :
             {Vec<3>{{1.5, 1.5, 1.5}}, Vec<3>{{2.5, 2.5, 2.5}}, Vec<3>{{1.2, 2.2, 6.0}},
              Vec<3>{{3.0, 4.5, 5.0}}, Vec<3>{{6.0, 6.0, 6.0}}}) {
            check_box(Box<3>(L, {periodic, periodic, periodic}), 1.0, 150, seed++);
        }
    }
    check_box(Box<3>(Vec<3>{{2.4, 5.0, 1.1}}, {true, false, true}), 1.0, 150, seed++);
    check_box(Box<3>(Vec<3>{{5.0, 2.1, 3.3}}, {false, true, false}), 1.0, 150, seed++);
}

TEST(CellList, WiderReachMatchesBruteForce) {
    std::uint64_t seed = 500;
    // cells of 0.3-0.45 and a cutoff of 1: reaches of 3-4 cells; axes with fewer cells
    // than the 2m + 1 the reach spans, and walls
    for (bool periodic : {true, false}) {
        for (const auto& L : {Vec<2>{{1.5, 1.5}}, Vec<2>{{2.5, 9.0}}, Vec<2>{{10.0, 10.0}}})
            check_box(Box<2>(L, {periodic, periodic}), 1.0, 200, seed++, 0.3);
        for (const auto& L : {Vec<3>{{1.5, 2.0, 2.5}}, Vec<3>{{4.0, 4.0, 4.0}}})
            check_box(Box<3>(L, {periodic, periodic, periodic}), 1.0, 200, seed++, 0.45);
    }
    check_box(Box<3>(Vec<3>{{2.4, 5.0, 1.1}}, {true, false, true}), 1.0, 150, seed++, 0.35);
    // the usual stencil: a grid whose cells are as wide as the reach scans one cell each
    // way; a box of exactly 4 cells of 2.5 gets 3 (cells are a relative 1e-10 wider than
    // asked, against the rounding of binning)
    CellList<2> cells(Box<2>(Vec<2>{{10.5, 10.0}}, {true, true}), 2.5);
    EXPECT_EQ(cells.cells_along(0), 4);
    EXPECT_EQ(cells.cells_along(1), 3);
    EXPECT_EQ(cells.cells_to_reach(2.5), 1);
    EXPECT_EQ(cells.cells_to_reach(2.62), 1);
    // exactly the narrower width: rounding in the binning could put such a pair two
    // cells apart, so it takes two
    EXPECT_EQ(cells.cells_to_reach(2.625), 2);
}

// The event engine's scan from a position outside a periodic box (a whole number of box
// lengths off, as an unwrapped position would be) finds the same particles as from the
// wrapped one: the cell is found by wrapping, so the cells' gaps must not be measured
// from the unwrapped coordinate.
TEST(CellList, ReachingScanFromOutsideThePeriodicBoxSeesTheWrappedOne) {
    const Box<3> box(Vec<3>{{6.0, 7.5, 9.0}}, {true, true, true});
    const double reach = 1.4;
    const auto pos = test::random_positions(box, 300, 77, 0);
    CellList<3> cells(box, reach);
    cells.build(pos);
    auto scan = [&](const Vec<3>& r) {
        std::vector<std::uint32_t> seen;
        cells.for_each_reaching(r, reach, [&](std::uint32_t j) { seen.push_back(j); });
        return seen;
    };
    int checked = 0;
    for (std::size_t i = 0; i < pos.size(); ++i)
        for (const Vec<3>& shift :
             {Vec<3>{{6.0, 0.0, 0.0}}, Vec<3>{{0.0, -15.0, 0.0}}, Vec<3>{{-6.0, 7.5, 18.0}}}) {
            const auto wrapped = scan(pos[i]);
            const auto unwrapped = scan(pos[i] + shift);
            // every particle within the reach of the wrapped position is seen from both
            for (std::uint32_t j = 0; j < pos.size(); ++j)
                if (norm2(box.minimum_image(pos[i] - pos[j])) < reach * reach) {
                    EXPECT_NE(std::find(wrapped.begin(), wrapped.end(), j), wrapped.end());
                    EXPECT_NE(std::find(unwrapped.begin(), unwrapped.end(), j), unwrapped.end())
                        << "particle " << i << " shifted by " << shift[0] << ", " << shift[1]
                        << ", " << shift[2] << " misses " << j;
                    ++checked;
                }
        }
    EXPECT_GT(checked, 300);
}
