// CellList::for_each_in_box (the event engine's scans across sliding faces) against brute
// force: every particle whose minimum-image displacement from the box's centre lies
// within its half-widths on each axis is given, and none twice, for lattices whose points
// sit on cell faces, boxes at exact multiples of the cell width, centres on faces and
// outside the box, spans wider than the box, and walled axes.
#include "pedesis/spatial/cell_list.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <random>
#include <vector>

using namespace pedesis;

namespace {

template <int D>
void expect_box_scan_complete(const Box<D>& box, double cell, const std::vector<Vec<D>>& points,
                              const Vec<D>& centre, const Vec<D>& half) {
    CellList<D> cells(box, cell);
    cells.build(points);
    std::vector<int> seen(points.size(), 0);
    cells.for_each_in_box(centre, half, [&](std::uint32_t j) { ++seen[j]; });
    for (std::size_t j = 0; j < points.size(); ++j) {
        ASSERT_LE(seen[j], 1) << "particle " << j << " given twice";
        Vec<D> d = points[j] - centre;
        bool inside = true;
        for (int a = 0; a < D; ++a) {
            if (box.periodic(a)) d[a] -= box.length(a) * std::round(d[a] / box.length(a));
            inside = inside && std::abs(d[a]) <= half[a];
        }
        if (inside) {
            ASSERT_EQ(seen[j], 1) << "particle " << j << " missed";
        }
    }
}

TEST(CellListBoxScan, LatticesOnCellFacesInBoxesAtExactMultiples) {
    // a 12 x 12 square lattice of spacing 1 in a 12 x 12 box with cells of exactly 1 and
    // 1.5 (points on every cell face), centres on faces, inside and outside the box
    std::vector<Vec<2>> lattice;
    for (int i = 0; i < 12; ++i)
        for (int j = 0; j < 12; ++j) lattice.push_back(Vec<2>{{i - 6.0, j - 6.0}});
    const Box<2> box(Vec<2>{{12.0, 12.0}}, {true, true});
    for (double cell : {1.0, 1.5, 4.0})
        for (const Vec<2>& centre :
             {Vec<2>{{0.0, 0.0}}, Vec<2>{{-6.0, 5.0}}, Vec<2>{{3.5, -17.25}}, Vec<2>{{13.0, 6.0}}})
            for (const Vec<2>& half : {Vec<2>{{1.0, 1.0}}, Vec<2>{{3.0, 1.5}}, Vec<2>{{7.0, 2.0}}})
                expect_box_scan_complete<2>(box, cell, lattice, centre, half);
}

TEST(CellListBoxScan, RandomPointsAndBoxesIn3DWithAWalledAxis) {
    std::mt19937_64 rng(17);
    std::uniform_real_distribution<double> u(-0.5, 0.5);
    for (int trial = 0; trial < 40; ++trial) {
        const Vec<3> L{{6.0 + 6.0 * (u(rng) + 0.5), 5.0 + 4.0 * (u(rng) + 0.5), 7.0}};
        const Box<3> box(L, {true, true, trial % 2 == 0});
        std::vector<Vec<3>> points;
        for (int k = 0; k < 400; ++k)
            points.push_back(Vec<3>{{L[0] * u(rng), L[1] * u(rng), L[2] * u(rng)}});
        const Vec<3> centre{{2.0 * L[0] * u(rng), 2.0 * L[1] * u(rng), L[2] * u(rng)}};
        const Vec<3> half{{3.0 * (u(rng) + 0.5) + 0.1, 1.0 + u(rng), 1.0 + u(rng)}};
        expect_box_scan_complete<3>(box, 1.0 + u(rng) + 0.5, points, centre, half);
    }
}

} // namespace
