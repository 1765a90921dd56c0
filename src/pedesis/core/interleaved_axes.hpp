#pragma once
// The SIMD passes over packed D-vectors (Vec<D> arrays) load four at a time as D vectors
// of four doubles, whose lanes hold the axes interleaved (3D: x y z x | y z x y | z x y z;
// 2D: x y x y); a per-axis constant is laid out the same way to meet them lane by lane.
#include <array>

namespace pedesis::detail {

// The four lanes of vector v (0 <= v < D) of the per-axis values.
template <int D>
inline void interleaved_axes(const std::array<double, D>& per_axis, int v, double (&lanes)[4]) {
    for (int e = 0; e < 4; ++e) lanes[e] = per_axis[(4 * v + e) % D];
}

} // namespace pedesis::detail
