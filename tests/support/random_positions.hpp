#pragma once
// Random test configurations for the spatial structures (cell list, neighbour list).
#include "pedesis/core/box.hpp"
#include "pedesis/core/rng.hpp"

#include <algorithm>
#include <string>
#include <vector>

namespace pedesis::test {

// "L = (10p, 4w)": the box in a failure message.
template <int D> std::string describe_box(const Box<D>& box) {
    std::string s = "L = (";
    for (int a = 0; a < D; ++a)
        s += std::to_string(box.length(a)) + (box.periodic(a) ? "p" : "w") +
             (a + 1 < D ? ", " : ")");
    return s;
}

// n positions uniform in the box, the first `on_boundary` of them moved exactly onto
// the boundaries (walls, or -L/2 on periodic axes), where cell assignment and minimum
// image are most fragile.
template <int D>
std::vector<Vec<D>> random_positions(const Box<D>& box, std::size_t n, std::uint64_t seed,
                                     std::size_t on_boundary) {
    std::vector<Vec<D>> pos(n);
    for (std::size_t i = 0; i < n; ++i) {
        CounterRng rng(seed, RngStream::placement, static_cast<std::uint32_t>(i));
        for (int a = 0; a < D; ++a) pos[i][a] = rng.uniform(box.lo(a), box.hi(a));
        box.wrap(pos[i]);
    }
    for (std::size_t i = 0; i < std::min(n, on_boundary); ++i)
        for (int a = 0; a < D; ++a) {
            if (i % 2 == 0)
                pos[i][a] = box.lo(a);
            else if (!box.periodic(a))
                pos[i][a] = box.hi(a);
        }
    return pos;
}

} // namespace pedesis::test
