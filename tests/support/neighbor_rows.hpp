#pragma once
// The rows of a built NeighborList for the tests that compare them with brute force: every
// entry as a pair, and the promise of its colour sweep.
#include "pedesis/spatial/neighbor_list.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cstdint>
#include <span>
#include <vector>

#include "support/pair_sets.hpp"

namespace pedesis::test {

// Every entry of the list as (lower, higher) index, duplicates kept: a pair listed in
// both rows, or twice in one, shows up twice; a particle listing itself shows up as (i, i).
template <int D> PairSet listed_pairs(const NeighborList<D>& nl) {
    PairSet s;
    for (std::uint32_t i = 0; i < nl.size(); ++i)
        for (const std::uint32_t* p = nl.begin(i); p != nl.end(i); ++p)
            s.push_back({std::min(i, *p), std::max(i, *p)});
    std::sort(s.begin(), s.end());
    return s;
}

// The sweep's promise: the chunks hold every particle once, and within one colour the
// particles a chunk's rows write (its own and their row entries) are written by no
// other chunk of that colour.
template <int D> void check_colouring(const NeighborList<D>& nl) {
    std::vector<int> seen(nl.size(), 0);
    for (int k = 0; k < nl.colours(); ++k) {
        std::vector<std::int64_t> writer(nl.size(), -1);
        const auto [first, last] = nl.chunks_of_colour(k);
        for (std::size_t c = first; c < last; ++c)
            for (std::uint32_t i : nl.chunk(c)) {
                ++seen[i];
                auto claim = [&](std::uint32_t p) {
                    const auto me = static_cast<std::int64_t>(c);
                    EXPECT_TRUE(writer[p] == -1 || writer[p] == me)
                        << "particle " << p << " written by chunks " << writer[p] << " and " << c
                        << " of colour " << k;
                    writer[p] = me;
                };
                claim(i);
                for (const std::uint32_t* p = nl.begin(i); p != nl.end(i); ++p) claim(*p);
            }
    }
    for (std::size_t i = 0; i < nl.size(); ++i)
        EXPECT_EQ(seen[i], 1) << "particle " << i << " in " << seen[i] << " chunks";
    // for_each_chunk hands out the same chunks
    std::vector<int> visits(nl.size(), 0);
    nl.for_each_chunk([&](std::span<const std::uint32_t> rows) {
        for (std::uint32_t i : rows) ++visits[i];
    });
    EXPECT_EQ(std::count(visits.begin(), visits.end(), 1), static_cast<std::ptrdiff_t>(nl.size()));
}

} // namespace pedesis::test
