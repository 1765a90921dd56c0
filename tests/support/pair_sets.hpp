#pragma once
// Pair sets for the differential tests: the O(N^2) minimum-image scan a spatial
// structure is compared with, and failure messages that name a pair by its exact
// coordinates (hexadecimal floating point), so that a failing case can be replayed
// bit for bit from the message alone.
#include "pedesis/core/box.hpp"

#include <algorithm>
#include <cstdint>
#include <cstdio>
#include <iterator>
#include <string>
#include <utility>
#include <vector>

namespace pedesis::test {

using Pair = std::pair<std::uint32_t, std::uint32_t>;
using PairSet = std::vector<Pair>; // sorted

// "(0x1.8p+1, -0x1p-3)": a position exactly.
template <int D> std::string exact(const Vec<D>& r) {
    std::string s = "(";
    for (int a = 0; a < D; ++a) {
        char buf[40];
        std::snprintf(buf, sizeof buf, "%a", r[a]);
        s += buf;
        s += a + 1 < D ? ", " : ")";
    }
    return s;
}

inline std::string exact(double x) {
    char buf[40];
    std::snprintf(buf, sizeof buf, "%a", x);
    return buf;
}

// "L = (0x1.4p+3 periodic, 0x1p+2 walled)": a box exactly.
template <int D> std::string exact_box(const Box<D>& box) {
    std::string s = "L = (";
    for (int a = 0; a < D; ++a)
        s += exact(box.length(a)) + (box.periodic(a) ? " periodic" : " walled") +
             (a + 1 < D ? ", " : ")");
    return s;
}

// Pairs i < j whose minimum-image distance squared is below cut2(i, j), sorted.
template <int D, class Cut2>
PairSet brute_pairs(const Box<D>& box, const std::vector<Vec<D>>& pos, Cut2&& cut2) {
    PairSet s;
    const auto n = static_cast<std::uint32_t>(pos.size());
    for (std::uint32_t i = 0; i < n; ++i)
        for (std::uint32_t j = i + 1; j < n; ++j)
            if (norm2(box.minimum_image(pos[i] - pos[j])) < cut2(i, j)) s.push_back({i, j});
    return s;
}

template <int D>
PairSet brute_pairs_within(const Box<D>& box, const std::vector<Vec<D>>& pos, double cut) {
    return brute_pairs(box, pos, [c2 = cut * cut](std::uint32_t, std::uint32_t) { return c2; });
}

inline PairSet minus(const PairSet& a, const PairSet& b) {
    PairSet d;
    std::set_difference(a.begin(), a.end(), b.begin(), b.end(), std::back_inserter(d));
    return d;
}

// "3 pairs missing, the first 4 and 17 at (..) and (..), 0x1.fffp-1 apart": empty when
// `pairs` is. The distance is the minimum image's.
template <int D>
std::string describe_pairs(const PairSet& pairs, const char* what, const Box<D>& box,
                           const std::vector<Vec<D>>& pos) {
    if (pairs.empty()) return "";
    const auto [i, j] = pairs.front();
    return std::to_string(pairs.size()) + " pairs " + what + ", the first " + std::to_string(i) +
           " at " + exact(pos[i]) + " and " + std::to_string(j) + " at " + exact(pos[j]) + ", " +
           exact(norm(box.minimum_image(pos[i] - pos[j]))) + " apart";
}

// Both orders of every pair, sorted: what a scan from every particle finds.
inline PairSet both_orders(const PairSet& s) {
    PairSet out;
    out.reserve(2 * s.size());
    for (const auto& [i, j] : s) {
        out.push_back({i, j});
        out.push_back({j, i});
    }
    std::sort(out.begin(), out.end());
    return out;
}

} // namespace pedesis::test
