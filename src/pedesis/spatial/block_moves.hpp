#pragma once
// NeighborList::needs_rebuild's pass over every particle, block by block, per kernel set
// (core/simd_level.hpp): how far each particle moved since the build (minimum image),
// whether any moved more than the skin or is not finite, the largest squared move, and
// how many moved more than skin/2. It runs every step (4% of a 3D WCA step in scalar
// code, whose minimum image branched per axis). The AVX2 set takes four particles per
// instruction. Both compute each move by Box::minimum_image's operations and its square
// by norm2's, without fused multiply-adds (the AVX2 function is not compiled with FMA),
// so every set counts the same movers and finds the same largest move.
#include "pedesis/core/interleaved_axes.hpp"
#include "pedesis/core/simd_level.hpp"
#include "pedesis/core/vec.hpp"

#include <algorithm>
#include <array>
#include <cstddef>
#include <cstdint>

#if PEDESIS_SIMD_DISPATCH
#include <immintrin.h>
#endif

namespace pedesis::detail {

template <int D> struct BlockMovesInput {
    const Vec<D>* pos;
    const Vec<D>* home;
    // the minimum image: d -= length where d > half, then d += length where d < -half
    // (never both); between walls half is infinite and length 0
    std::array<double, D> half, length;
    double skin2, half_skin2;
};

struct BlockMoves {
    bool far = false; // a move beyond the skin, or not finite
    double most2 = 0.0;
    std::size_t movers = 0; // moves beyond skin/2
};

template <int D>
[[gnu::always_inline]] inline void add_move_sse2(const BlockMovesInput<D>& in, std::size_t k,
                                                 BlockMoves& m) {
    Vec<D> d = in.pos[k] - in.home[k];
    for (int a = 0; a < D; ++a) {
        d[a] -= d[a] > in.half[a] ? in.length[a] : 0.0;
        d[a] += d[a] < -in.half[a] ? in.length[a] : 0.0;
    }
    const double d2 = norm2(d);
    // written as !(<=) so that a NaN position asks for a rebuild (which reports it)
    m.far = m.far || !(d2 <= in.skin2);
    m.most2 = std::max(m.most2, d2);
    m.movers += d2 > in.half_skin2 ? 1 : 0;
}

template <int D>
BlockMoves block_moves_sse2(const BlockMovesInput<D>& in, std::size_t first, std::size_t last) {
    BlockMoves m;
    for (std::size_t k = first; k < last; ++k) add_move_sse2<D>(in, k, m);
    return m;
}

#if PEDESIS_SIMD_DISPATCH
template <int D>
[[gnu::target("avx2")]] BlockMoves block_moves_avx2(const BlockMovesInput<D>& in, std::size_t first,
                                                    std::size_t last) {
    static_assert(sizeof(Vec<D>) == D * sizeof(double), "positions must lie packed");
    __m256d half[D], length[D];
    interleaved_axes_avx2<D>(in.half, half);
    interleaved_axes_avx2<D>(in.length, length);
    const __m256d zero = _mm256_setzero_pd();
    const __m256d skin2 = _mm256_set1_pd(in.skin2), half_skin2 = _mm256_set1_pd(in.half_skin2);
    __m256d most2 = zero;
    bool far = false;
    std::size_t movers = 0;
    std::size_t k = first;
    for (; k + 4 <= last; k += 4) {
        const double* p = in.pos[k].c.data();
        const double* h = in.home[k].c.data();
        __m256d sq[D];
        for (int v = 0; v < D; ++v) {
            __m256d d = _mm256_sub_pd(_mm256_loadu_pd(p + 4 * v), _mm256_loadu_pd(h + 4 * v));
            d = _mm256_sub_pd(d, _mm256_and_pd(_mm256_cmp_pd(d, half[v], _CMP_GT_OQ), length[v]));
            const __m256d below = _mm256_cmp_pd(d, _mm256_sub_pd(zero, half[v]), _CMP_LT_OQ);
            d = _mm256_add_pd(d, _mm256_and_pd(below, length[v]));
            sq[v] = _mm256_mul_pd(d, d);
        }
        __m256d x, y, z;
        if constexpr (D == 3) {
            // x0 y0 z0 x1 | y1 z1 x2 y2 | z2 x3 y3 z3 -> x, y, z of the four
            const __m256d xy02 = _mm256_blend_pd(sq[0], sq[1], 0xC);
            const __m256d zx13 = _mm256_permute2f128_pd(sq[0], sq[2], 0x21);
            const __m256d yz13 = _mm256_blend_pd(sq[1], sq[2], 0xC);
            x = _mm256_blend_pd(xy02, zx13, 0xA);
            y = _mm256_shuffle_pd(xy02, yz13, 0x5);
            z = _mm256_blend_pd(zx13, yz13, 0xA);
        } else {
            x = _mm256_permute4x64_pd(_mm256_unpacklo_pd(sq[0], sq[1]), 0xD8);
            y = _mm256_permute4x64_pd(_mm256_unpackhi_pd(sq[0], sq[1]), 0xD8);
            z = zero;
        }
        // norm2's order: (x^2 + y^2) + z^2
        __m256d d2 = _mm256_add_pd(x, y);
        if constexpr (D == 3) d2 = _mm256_add_pd(d2, z);
        far = far || _mm256_movemask_pd(_mm256_cmp_pd(d2, skin2, _CMP_NLE_UQ)) != 0;
        // (a NaN move leaves the maximum as it was, as std::max(most, NaN) does)
        most2 = _mm256_max_pd(d2, most2);
        movers += static_cast<std::size_t>(
            __builtin_popcount(_mm256_movemask_pd(_mm256_cmp_pd(d2, half_skin2, _CMP_GT_OQ))));
    }
    BlockMoves m;
    double lanes[4];
    _mm256_storeu_pd(lanes, most2);
    m.most2 = std::max(std::max(lanes[0], lanes[1]), std::max(lanes[2], lanes[3]));
    m.far = far;
    m.movers = movers;
    for (; k < last; ++k) add_move_sse2<D>(in, k, m);
    return m;
}
#endif

// The function for the kernel set in use (AVX-512 machines take the AVX2 one).
template <int D>
auto block_moves_for(SimdLevel level)
    -> BlockMoves (*)(const BlockMovesInput<D>&, std::size_t, std::size_t) {
#if PEDESIS_SIMD_DISPATCH
    if (level != SimdLevel::sse2) return &block_moves_avx2<D>;
#endif
    (void)level;
    return &block_moves_sse2<D>;
}

} // namespace pedesis::detail
