#pragma once
// The cells a CellList scan visits, against brute force: shared by the cell-list suites.
#include "pedesis/spatial/cell_list.hpp"
#include "support/pair_sets.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <string>
#include <vector>

namespace pedesis::test {

// The scan from every particle: (i, j) for every j within `reach` that the cells around
// i hold. A particle visited twice, or i not visited from itself, is a failure.
template <int D>
PairSet scanned_pairs(const Box<D>& box, const CellList<D>& cells, const std::vector<Vec<D>>& pos,
                      double reach, bool near_only, const std::string& label) {
    const int m = near_only ? 1 : cells.cells_to_reach(reach);
    const double r2 = reach * reach;
    PairSet found;
    std::vector<int> visits(pos.size(), 0);
    for (std::uint32_t i = 0; i < pos.size(); ++i) {
        std::vector<std::uint32_t> seen;
        auto visit = [&](std::uint32_t j) {
            if (++visits[j] == 2)
                ADD_FAILURE() << label << ": particle " << j << " visited twice from " << i;
            seen.push_back(j);
            if (j != i && norm2(box.minimum_image(pos[i] - pos[j])) < r2) found.push_back({i, j});
        };
        if (near_only)
            cells.for_each_near(pos[i], visit);
        else
            cells.for_each_within(pos[i], m, visit);
        if (visits[i] != 1)
            ADD_FAILURE() << label << ": particle " << i << " at " << test::exact(pos[i])
                          << " not in the cells around itself";
        for (std::uint32_t j : seen) visits[j] = 0;
    }
    std::sort(found.begin(), found.end());
    return found;
}

// Fails (naming the case) unless the scan finds exactly the brute-force pairs.
template <int D>
void expect_scan_complete(const Box<D>& box, const CellList<D>& cells,
                          const std::vector<Vec<D>>& pos, double reach, bool near_only,
                          const std::string& label) {
    const PairSet expect = test::both_orders(test::brute_pairs_within(box, pos, reach));
    const PairSet found = scanned_pairs(box, cells, pos, reach, near_only, label);
    const PairSet missing = test::minus(expect, found);
    EXPECT_TRUE(missing.empty()) << label << ": "
                                 << test::describe_pairs(missing, "missed", box, pos);
    EXPECT_EQ(found.size(), expect.size()) << label;
}

template <int D> std::string describe_cells(const CellList<D>& cells) {
    std::string s = "cells";
    for (int a = 0; a < D; ++a) s += (a ? " x " : " ") + std::to_string(cells.cells_along(a));
    return s;
}

} // namespace pedesis::test
