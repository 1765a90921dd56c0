#pragma once
// The cells a CellList scan visits, against brute force: shared by the cell-list suites.
#include "pedesis/spatial/cell_list.hpp"
#include "support/pair_sets.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <string>
#include <vector>

namespace pedesis::test {

// How a scan chooses its cells: the 3-cell stencil (for_each_near), the stencil of
// cells_to_reach (for_each_within), or that less the cells out of reach
// (for_each_reaching, the event engine's list rebuilds).
enum class Scan { near, within, reaching };

// The particles the scan from `r` visits, in its order.
template <int D>
std::vector<std::uint32_t> scan_from(const CellList<D>& cells, const Vec<D>& r, double reach,
                                     Scan how) {
    std::vector<std::uint32_t> seen;
    auto visit = [&](std::uint32_t j) { seen.push_back(j); };
    if (how == Scan::near)
        cells.for_each_near(r, visit);
    else if (how == Scan::within)
        cells.for_each_within(r, cells.cells_to_reach(reach), visit);
    else
        cells.for_each_reaching(r, reach, visit);
    return seen;
}

// The scan from every particle: (i, j) for every j within `reach` that the cells around
// i hold. A particle visited twice, or i not visited from itself, is a failure.
template <int D>
PairSet scanned_pairs(const Box<D>& box, const CellList<D>& cells, const std::vector<Vec<D>>& pos,
                      double reach, Scan how, const std::string& label) {
    const double r2 = reach * reach;
    PairSet found;
    std::vector<int> visits(pos.size(), 0);
    for (std::uint32_t i = 0; i < pos.size(); ++i) {
        const std::vector<std::uint32_t> seen = scan_from(cells, pos[i], reach, how);
        for (std::uint32_t j : seen) {
            if (++visits[j] == 2)
                ADD_FAILURE() << label << ": particle " << j << " visited twice from " << i;
            if (j != i && norm2(box.minimum_image(pos[i] - pos[j])) < r2) found.push_back({i, j});
        }
        if (visits[i] != 1)
            ADD_FAILURE() << label << ": particle " << i << " at " << test::exact(pos[i])
                          << " not in the cells around itself";
        for (std::uint32_t j : seen) visits[j] = 0;
    }
    std::sort(found.begin(), found.end());
    return found;
}

// Fails (naming the case) unless the scan finds exactly the brute-force pairs; then the
// same for for_each_reaching, whose visits must also come in the order of the whole
// stencil's (the event engine's lists, and so its trajectories, keep that order).
template <int D>
void expect_scan_complete(const Box<D>& box, const CellList<D>& cells,
                          const std::vector<Vec<D>>& pos, double reach, bool near_only,
                          const std::string& label) {
    const PairSet expect = test::both_orders(test::brute_pairs_within(box, pos, reach));
    const Scan full = near_only ? Scan::near : Scan::within;
    for (const Scan how : {full, Scan::reaching}) {
        const std::string what = label + (how == Scan::reaching ? ", for_each_reaching" : "");
        const PairSet found = scanned_pairs(box, cells, pos, reach, how, what);
        const PairSet missing = test::minus(expect, found);
        EXPECT_TRUE(missing.empty())
            << what << ": " << test::describe_pairs(missing, "missed", box, pos);
        EXPECT_EQ(found.size(), expect.size()) << what;
    }
    // (against for_each_within's stencil, which for_each_reaching trims where the cells
    // are as wide as the reach and is otherwise)
    for (std::uint32_t i = 0; i < pos.size(); ++i) {
        const std::vector<std::uint32_t> all = scan_from(cells, pos[i], reach, Scan::within);
        const std::vector<std::uint32_t> some = scan_from(cells, pos[i], reach, Scan::reaching);
        // `some` a subsequence of `all`: each visit found after the one before it
        auto at = all.begin();
        bool in_order = true;
        for (std::uint32_t j : some) {
            at = std::find(at, all.end(), j);
            if (at == all.end()) {
                in_order = false;
                break;
            }
            ++at;
        }
        if (!in_order) {
            ADD_FAILURE() << label << ": for_each_reaching from particle " << i
                          << " visits out of the full stencil's order";
            return;
        }
    }
}

template <int D> std::string describe_cells(const CellList<D>& cells) {
    std::string s = "cells";
    for (int a = 0; a < D; ++a) s += (a ? " x " : " ") + std::to_string(cells.cells_along(a));
    return s;
}

} // namespace pedesis::test
