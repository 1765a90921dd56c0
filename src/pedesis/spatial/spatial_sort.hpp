#pragma once
// Orders particles along a space-filling curve (Hilbert in 2D, Morton in 3D) so that
// particles close in space are close in memory: the neighbour rows of a particle then
// point at a few cache lines instead of N random ones. The order depends only on the
// positions and tags (ties broken by tag), never on the thread count.
#include "pedesis/core/box.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <numeric>
#include <utility>
#include <vector>

namespace pedesis {

namespace detail {

// Position of cell (x, y) along a Hilbert curve over a 2^bits x 2^bits grid.
inline std::uint64_t hilbert_index(std::uint32_t x, std::uint32_t y, int bits) {
    const std::uint32_t n = 1u << bits;
    std::uint64_t d = 0;
    for (std::uint32_t s = n / 2; s > 0; s /= 2) {
        const std::uint32_t rx = (x & s) ? 1u : 0u, ry = (y & s) ? 1u : 0u;
        d += static_cast<std::uint64_t>(s) * s * ((3u * rx) ^ ry);
        if (ry == 0) { // turn the sub-square so that the curve stays continuous
            if (rx == 1) {
                x = n - 1 - x;
                y = n - 1 - y;
            }
            std::swap(x, y);
        }
    }
    return d;
}

inline std::uint64_t spread_bits_3(std::uint64_t v) { // 21 bits -> every third bit
    v &= 0x1fffff;
    v = (v | v << 32) & 0x1f00000000ffffull;
    v = (v | v << 16) & 0x1f0000ff0000ffull;
    v = (v | v << 8) & 0x100f00f00f00f00full;
    v = (v | v << 4) & 0x10c30c30c30c30c3ull;
    v = (v | v << 2) & 0x1249249249249249ull;
    return v;
}

} // namespace detail

// The storage order along the curve: result[i] is the current index of the particle
// that should come i-th. `cell` is the grid spacing (about the interaction range: finer
// grids do not improve locality).
template <int D>
std::vector<std::uint32_t> space_filling_order(const Box<D>& box, const std::vector<Vec<D>>& pos,
                                               const std::vector<std::uint32_t>& tag, double cell) {
    constexpr int bits = D == 2 ? 16 : 21;
    constexpr double max_cell = static_cast<double>((1u << bits) - 1);
    std::array<double, D> scale;
    for (int a = 0; a < D; ++a)
        scale[a] = std::min(1.0 / cell, max_cell / box.length(a)); // grid within 2^bits
    const std::size_t n = pos.size();
    std::vector<std::pair<std::uint64_t, std::uint32_t>> key(n);
    for (std::size_t i = 0; i < n; ++i) {
        std::array<std::uint32_t, D> c;
        for (int a = 0; a < D; ++a) {
            const double x = (pos[i][a] + 0.5 * box.length(a)) * scale[a];
            // (a NaN goes to cell 0: the order stays defined for any input)
            c[a] = static_cast<std::uint32_t>(x > 0.0 ? std::min(x, max_cell) : 0.0);
        }
        std::uint64_t k;
        if constexpr (D == 2)
            k = detail::hilbert_index(c[0], c[1], bits);
        else
            k = detail::spread_bits_3(c[0]) | detail::spread_bits_3(c[1]) << 1 |
                detail::spread_bits_3(c[2]) << 2;
        key[i] = {k, static_cast<std::uint32_t>(i)};
    }
    std::sort(key.begin(), key.end(), [&](const auto& a, const auto& b) {
        return a.first != b.first ? a.first < b.first : tag[a.second] < tag[b.second];
    });
    std::vector<std::uint32_t> order(n);
    for (std::size_t i = 0; i < n; ++i) order[i] = key[i].second;
    return order;
}

} // namespace pedesis
