// CellList against an O(N^2) minimum-image scan on random rectangular boxes (lengths a
// whole number of reaches, one ulp either side, or anything; periodic and walled axes
// at random) with pairs placed where rounding decides the cell: on cell faces exactly
// and a ulp either side, at -L/2, one ulp inside +L/2, on walls, their partners a ulp
// either side of the reach, across the face or the periodic boundary. The promise
// checked: the cells a scan visits from particle i (for_each_near for the reach
// min_cell, for_each_within with cells_to_reach(reach) for wider reaches) hold every
// particle within the reach of i, minimum image, and each particle once; fresh, and
// after particles are moved by remove and insert. The lattices are in
// cell_list_brute_force_test.cpp. Every failure names its case (seed, box and reach in
// hexadecimal) and the first pair missed with exact coordinates, so it can be replayed.
#include "pedesis/spatial/cell_list.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <random>
#include <string>
#include <vector>

#include "support/cell_scans.hpp"
#include "support/face_pairs.hpp"
#include "support/lattices.hpp"
#include "support/pair_sets.hpp"
#include "support/random_positions.hpp"

using namespace pedesis;
using test::describe_cells;
using test::expect_scan_complete;
using test::PairSet;

namespace {

// A random rectangular box whose lengths are whole numbers of the reach, one ulp either
// side, or anything; axes periodic or walled at random; uniform particles plus pairs on
// cell faces. Scanned fresh, then again after a third of the particles have moved to
// other fragile places through remove and insert (the event engine's path).
template <int D> int check_random_boxes(int cases, std::uint64_t seed0) {
    int scans = 0;
    for (int k = 0; k < cases; ++k) {
        const std::uint64_t seed = seed0 + static_cast<std::uint64_t>(k);
        std::mt19937_64 gen(seed);
        const double reach = std::uniform_real_distribution<double>(0.3, 2.0)(gen);
        const int split = 1 + static_cast<int>(gen() % 3);
        Vec<D> L;
        std::array<bool, D> periodic;
        for (int a = 0; a < D; ++a) {
            const int whole = 1 + static_cast<int>(gen() % (D == 2 ? 20 : 8));
            const int nudge = static_cast<int>(gen() % 4) - 1; // 2: not a multiple
            L[a] = nudge == 2
                       ? whole * reach * std::uniform_real_distribution<double>(0.8, 1.2)(gen)
                       : test::nudged(whole * reach, nudge);
            periodic[a] = gen() % 3 != 0;
        }
        const Box<D> box(L, periodic);
        CellList<D> cells(box, reach / split);
        std::array<int, D> slabs;
        for (int a = 0; a < D; ++a) slabs[a] = cells.cells_along(a);
        const double per_reach = D == 2 ? 3.0 : 2.0;
        const auto n_uniform = static_cast<std::size_t>(
            std::min(400.0, per_reach * box.volume() / std::pow(reach, D)));
        auto pos = test::random_positions(box, n_uniform, seed, 4);
        test::add_face_pairs(box, slabs, 40, test::near_reach(reach), gen, pos);
        cells.build(pos);
        const std::string label = "random box, seed " + std::to_string(seed) + ", " +
                                  test::exact_box(box) + ", reach " + test::exact(reach) +
                                  ", min_cell reach/" + std::to_string(split) + ", " +
                                  describe_cells(cells);
        expect_scan_complete(box, cells, pos, reach, split == 1, label);
        // move a third of them, a pair at a time, onto other fragile places
        std::vector<Vec<D>> moved;
        test::add_face_pairs(box, slabs, pos.size() / 6, test::near_reach(reach), gen, moved);
        for (std::size_t m = 0; m < moved.size() && m < pos.size(); ++m) {
            const auto i = static_cast<std::uint32_t>((3 * m) % pos.size());
            cells.remove(i);
            pos[i] = moved[m];
            cells.insert(i, pos[i]);
        }
        expect_scan_complete(box, cells, pos, reach, split == 1, label + ", after moves");
        scans += 2;
    }
    return scans;
}

TEST(CellListRandomFacesBruteForce, RandomBoxesWithPairsOnCellFaces2D) {
    EXPECT_EQ(check_random_boxes<2>(600, 1000), 1200);
}

TEST(CellListRandomFacesBruteForce, RandomBoxesWithPairsOnCellFaces3D) {
    EXPECT_EQ(check_random_boxes<3>(600, 5000), 1200);
}

} // namespace
