#pragma once
// The SIMD passes over packed D-vectors (Vec<D> arrays) load four at a time as D vectors
// of four doubles, whose lanes hold the axes interleaved (3D: x y z x | y z x y | z x y z;
// 2D: x y x y); a per-axis constant is laid out the same way to meet them lane by lane.
#include "pedesis/core/simd_level.hpp"

#include <array>

#if PEDESIS_SIMD_DISPATCH
#include <immintrin.h>
#endif

namespace pedesis::detail {

// The four lanes of vector v (0 <= v < D) of the per-axis values.
template <int D>
inline void interleaved_axes(const std::array<double, D>& per_axis, int v, double (&lanes)[4]) {
    for (int e = 0; e < 4; ++e) lanes[e] = per_axis[(4 * v + e) % D];
}

#if PEDESIS_SIMD_DISPATCH
// All D vectors at once, for the AVX2 passes.
template <int D>
[[gnu::target("avx2"), gnu::always_inline]] inline void
interleaved_axes_avx2(const std::array<double, D>& per_axis, __m256d (&vectors)[D]) {
    for (int v = 0; v < D; ++v) {
        double lanes[4];
        interleaved_axes<D>(per_axis, v, lanes);
        vectors[v] = _mm256_loadu_pd(lanes);
    }
}
#endif

} // namespace pedesis::detail
