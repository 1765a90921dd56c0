#pragma once
// Whether every particle of a block lies inside the box's bounds, per kernel set
// (core/simd_level.hpp): the soft engine's wrap after each step (Evolver::wrap_all) asks
// this of every particle, and almost every particle is inside. The scalar test branched
// and compared one axis at a time and took 3.5% of a 3D WCA step; the AVX2 set tests
// four particles per instruction. Inside means lo <= x < hi on every axis, so a NaN is
// outside, as in the scalar test (the wrap then reports or handles it).
#include "pedesis/core/interleaved_axes.hpp"
#include "pedesis/core/simd_level.hpp"
#include "pedesis/core/vec.hpp"

#include <array>
#include <cstddef>

#if PEDESIS_SIMD_DISPATCH
#include <immintrin.h>
#endif

namespace pedesis::detail {

template <int D> struct BoxBounds {
    std::array<double, D> lo, hi; // +-infinity on an axis that is not tested
};

template <int D>
[[gnu::always_inline]] inline bool inside_bounds(const BoxBounds<D>& b, const Vec<D>& r) {
    bool inside = true;
    for (int a = 0; a < D; ++a) inside &= (r[a] >= b.lo[a]) & (r[a] < b.hi[a]);
    return inside;
}

template <int D>
bool all_inside_sse2(const BoxBounds<D>& b, const Vec<D>* pos, std::size_t first,
                     std::size_t last) {
    bool inside = true;
    for (std::size_t k = first; k < last; ++k) inside &= inside_bounds<D>(b, pos[k]);
    return inside;
}

#if PEDESIS_SIMD_DISPATCH
template <int D>
[[gnu::target("avx2")]] bool all_inside_avx2(const BoxBounds<D>& b, const Vec<D>* pos,
                                             std::size_t first, std::size_t last) {
    static_assert(sizeof(Vec<D>) == D * sizeof(double), "positions must lie packed");
    __m256d lo[D], hi[D];
    interleaved_axes_avx2<D>(b.lo, lo);
    interleaved_axes_avx2<D>(b.hi, hi);
    __m256d inside = _mm256_castsi256_pd(_mm256_set1_epi64x(-1));
    std::size_t k = first;
    for (; k + 4 <= last; k += 4) {
        const double* p = pos[k].c.data();
        for (int v = 0; v < D; ++v) {
            const __m256d x = _mm256_loadu_pd(p + 4 * v);
            inside = _mm256_and_pd(inside, _mm256_and_pd(_mm256_cmp_pd(x, lo[v], _CMP_GE_OQ),
                                                         _mm256_cmp_pd(x, hi[v], _CMP_LT_OQ)));
        }
    }
    bool all = _mm256_movemask_pd(inside) == 0xF;
    for (; k < last; ++k) all &= inside_bounds<D>(b, pos[k]);
    return all;
}
#endif

// The function for the kernel set in use (AVX-512 machines take the AVX2 one).
template <int D>
auto all_inside_for(SimdLevel level)
    -> bool (*)(const BoxBounds<D>&, const Vec<D>*, std::size_t, std::size_t) {
#if PEDESIS_SIMD_DISPATCH
    if (level != SimdLevel::sse2) return &all_inside_avx2<D>;
#endif
    (void)level;
    return &all_inside_sse2<D>;
}

} // namespace pedesis::detail
