#pragma once
// The neighbour-list build's inner loop with the half stencil, per kernel set
// (core/simd_level.hpp): a particle's candidates, range by range, and which of them lie
// within the list range. The SSE2 set tests one candidate at a time; the AVX2 set tests
// four per instruction and packs the hits' indices with one byte shuffle; the AVX-512 set
// eight, its ranges' ends under masks. All compute r^2 by the same operations in the same
// order, without fused multiply-adds (the AVX2 function is not compiled with FMA, the
// AVX-512 one names each operation's rounding), so every set lists the same pairs in the
// same order.
#include "pedesis/core/simd_level.hpp"
#include "pedesis/core/vec.hpp"
#include "pedesis/spatial/neighbor_list.hpp"

#include <array>
#include <cstddef>
#include <cstdint>

#if PEDESIS_SIMD_DISPATCH
#include <immintrin.h>
#endif

namespace pedesis::detail {

// A particle's candidates: ranges [range[r][0], range[r][1]) of the cell-sorted positions
// ref (indices idx), each shifted by its periodic image (ri + image[r] - ref[k]).
template <int D> struct NearRowInput {
    static_assert(sizeof(Vec<D>) == D * sizeof(double), "positions must lie packed");
    const Vec<D>* ref;
    const std::uint32_t* idx;
    const std::array<std::uint32_t, 2>* range;
    const double (*image)[D];
    int ranges;
    double range2; // the list range, squared (a pair is listed where r^2 < range2)
};

// The indices within range of ri into dst, in range order, the first range starting at
// `first`; dst has room for every candidate (each is stored, the cursor advancing on a
// hit). Returns the count.
template <int D>
[[gnu::always_inline]] inline std::size_t near_row_sse2(const NearRowInput<D>& in,
                                                        std::uint32_t first, const Vec<D>& ri,
                                                        std::uint32_t* dst) {
    std::size_t w = 0;
    for (int r = 0; r < in.ranges; ++r) {
        Vec<D> rs = ri;
        for (int a = 0; a < D; ++a) rs[a] += in.image[r][a];
        for (std::uint32_t k = r == 0 ? first : in.range[r][0]; k < in.range[r][1]; ++k) {
            dst[w] = in.idx[k];
            w += squared_length(rs - in.ref[k]) < in.range2;
        }
    }
    return w;
}

#if PEDESIS_SIMD_DISPATCH
// For each 4-bit mask of hits, the byte shuffle that moves the hit lanes' 32-bit indices
// to the front, in order.
struct PackTable {
    alignas(16) std::uint8_t shuffle[16][16];
    std::uint8_t count[16];
    constexpr PackTable() : shuffle{}, count{} {
        for (int m = 0; m < 16; ++m) {
            int out = 0;
            for (int lane = 0; lane < 4; ++lane)
                if (m & (1 << lane)) {
                    for (int b = 0; b < 4; ++b)
                        shuffle[m][4 * out + b] = static_cast<std::uint8_t>(4 * lane + b);
                    ++out;
                }
            for (int b = 4 * out; b < 16; ++b) shuffle[m][b] = 0x80; // zero
            count[m] = static_cast<std::uint8_t>(out);
        }
    }
};
inline constexpr PackTable pack_table{};

template <int D>
[[gnu::target("avx2")]] std::size_t near_row_avx2(const NearRowInput<D>& in, std::uint32_t first,
                                                  const Vec<D>& ri, std::uint32_t* dst) {
    const __m256d range2 = _mm256_set1_pd(in.range2);
    std::size_t w = 0;
    for (int r = 0; r < in.ranges; ++r) {
        Vec<D> rs = ri;
        for (int a = 0; a < D; ++a) rs[a] += in.image[r][a];
        const __m256d rx = _mm256_set1_pd(rs[0]), ry = _mm256_set1_pd(rs[1]);
        const __m256d rz = _mm256_set1_pd(D == 3 ? rs[D - 1] : 0.0);
        std::uint32_t k = r == 0 ? first : in.range[r][0];
        const std::uint32_t end = in.range[r][1];
        for (; k + 4 <= end; k += 4) {
            const double* p = in.ref[k].c.data();
            __m256d x, y, z;
            if constexpr (D == 3) {
                // x0 y0 z0 x1 | y1 z1 x2 y2 | z2 x3 y3 z3 -> x, y, z of the four
                const __m256d a = _mm256_loadu_pd(p), b = _mm256_loadu_pd(p + 4),
                              c = _mm256_loadu_pd(p + 8);
                const __m256d xy02 = _mm256_blend_pd(a, b, 0xC);         // x0 y0 x2 y2
                const __m256d zx13 = _mm256_permute2f128_pd(a, c, 0x21); // z0 x1 z2 x3
                const __m256d yz13 = _mm256_blend_pd(b, c, 0xC);         // y1 z1 y3 z3
                x = _mm256_blend_pd(xy02, zx13, 0xA);
                y = _mm256_shuffle_pd(xy02, yz13, 0x5);
                z = _mm256_blend_pd(zx13, yz13, 0xA);
            } else {
                // x0 y0 x1 y1 | x2 y2 x3 y3
                const __m256d a = _mm256_loadu_pd(p), b = _mm256_loadu_pd(p + 4);
                x = _mm256_permute4x64_pd(_mm256_unpacklo_pd(a, b), 0xD8);
                y = _mm256_permute4x64_pd(_mm256_unpackhi_pd(a, b), 0xD8);
                z = _mm256_setzero_pd();
            }
            const __m256d dx = _mm256_sub_pd(rx, x), dy = _mm256_sub_pd(ry, y);
            // squared_length's order: (dx dx + dy dy) + dz dz, each product rounded
            __m256d r2 = _mm256_add_pd(_mm256_mul_pd(dx, dx), _mm256_mul_pd(dy, dy));
            if constexpr (D == 3) {
                const __m256d dz = _mm256_sub_pd(rz, z);
                r2 = _mm256_add_pd(r2, _mm256_mul_pd(dz, dz));
            }
            const int hits = _mm256_movemask_pd(_mm256_cmp_pd(r2, range2, _CMP_LT_OQ));
            const __m128i j = _mm_loadu_si128(reinterpret_cast<const __m128i*>(in.idx + k));
            const __m128i packed = _mm_shuffle_epi8(
                j, _mm_load_si128(reinterpret_cast<const __m128i*>(pack_table.shuffle[hits])));
            // w <= k - start, so the four stores stay within the row's room
            _mm_storeu_si128(reinterpret_cast<__m128i*>(dst + w), packed);
            w += pack_table.count[hits];
        }
        for (; k < end; ++k) {
            dst[w] = in.idx[k];
            w += squared_length(rs - in.ref[k]) < in.range2;
        }
    }
    return w;
}

// The AVX-512 set: eight candidates per instruction. A range's last, partial group is
// loaded under a mask (lanes past the range are neither read nor compared), so no
// candidate is left to a scalar loop, whose varying trip count mispredicted at the end
// of every range; the hits' indices are packed in order by a compress. r^2 is computed
// with the rounding named on each operation, which GCC cannot fuse into multiply-adds:
// the same bits as the other sets.
inline constexpr std::uint32_t near_row_slack = 7; // entries a scan may write past its row

template <int D>
[[gnu::target("avx512f,avx512vl,avx512dq,avx512bw,avx2")]] std::size_t
near_row_avx512(const NearRowInput<D>& in, std::uint32_t first, const Vec<D>& ri,
                std::uint32_t* dst) {
    constexpr int rn = _MM_FROUND_TO_NEAREST_INT | _MM_FROUND_NO_EXC;
    const __m512d range2 = _mm512_set1_pd(in.range2);
    // de-interleaving permutes: lane l of axis a is double D l + a of the group
    const __m512i x_from = _mm512_set_epi64(7 * D, 6 * D, 5 * D, 4 * D, 3 * D, 2 * D, D, 0);
    const __m512i one = _mm512_set1_epi64(1);
    // (the zero-masking forms: GCC 12's plain ones start from an undefined vector, which
    // -Wmaybe-uninitialized reports)
    const __mmask8 all = 0xFF;
    std::size_t w = 0;
    for (int r = 0; r < in.ranges; ++r) {
        Vec<D> rs = ri;
        for (int a = 0; a < D; ++a) rs[a] += in.image[r][a];
        const std::uint32_t end = in.range[r][1];
        for (std::uint32_t k = r == 0 ? first : in.range[r][0]; k < end; k += 8) {
            const unsigned left = end - k < 8 ? end - k : 8;
            const auto lanes = static_cast<__mmask8>((1u << left) - 1u);
            const double* p = in.ref[k].c.data();
            const unsigned doubles = D * left; // of this group, in memory order
            // (the intrinsics stay in this function's body: a lambda would not have its
            // target)
            auto belong = [doubles](unsigned from) { // which of doubles from..from+7 do
                const unsigned n = doubles > from ? doubles - from : 0;
                return static_cast<__mmask8>(n >= 8 ? 0xFFu : (1u << n) - 1u);
            };
            const __m512d a = _mm512_maskz_loadu_pd(belong(0), p);
            const __m512d b = _mm512_maskz_loadu_pd(belong(8), p + 8);
            // 3D: doubles 16..23 (lanes 6 and 7 of x, 5..7 of y and z) lie in c
            const __m512d c = D == 3 ? _mm512_maskz_loadu_pd(belong(16), p + 16) : a;
            __m512d r2 = _mm512_setzero_pd();
            __m512i idx = x_from; // the doubles of axis 0, then 1, 2
            for (int axis = 0; axis < D; ++axis) {
                // (permutex2var reads an index's low 4 bits, permutexvar its low 3: the
                // same index vector serves both, each lane taking the right source)
                __m512d v = _mm512_permutex2var_pd(a, idx, b);
                if constexpr (D == 3)
                    v = _mm512_mask_permutexvar_pd(
                        v, _mm512_cmpge_epi64_mask(idx, _mm512_set1_epi64(16)), idx, c);
                const __m512d d = _mm512_maskz_sub_round_pd(all, _mm512_set1_pd(rs[axis]), v, rn);
                const __m512d dd = _mm512_maskz_mul_round_pd(all, d, d, rn);
                r2 = axis == 0 ? dd : _mm512_maskz_add_round_pd(all, r2, dd, rn);
                idx = _mm512_add_epi64(idx, one);
            }
            const __mmask8 hits = _mm512_mask_cmp_pd_mask(lanes, r2, range2, _CMP_LT_OQ);
            const __m256i j = _mm256_maskz_loadu_epi32(lanes, in.idx + k);
            _mm256_storeu_si256(reinterpret_cast<__m256i*>(dst + w),
                                _mm256_maskz_compress_epi32(hits, j));
            w += static_cast<unsigned>(__builtin_popcount(hits));
        }
    }
    return w;
}
#endif

template <int D>
std::size_t near_row_scalar_call(const NearRowInput<D>& in, std::uint32_t first, const Vec<D>& ri,
                                 std::uint32_t* dst) {
    return near_row_sse2<D>(in, first, ri, dst);
}

// The function for the kernel set in use.
template <int D>
auto near_row_for(SimdLevel level)
    -> std::size_t (*)(const NearRowInput<D>&, std::uint32_t, const Vec<D>&, std::uint32_t*) {
#if PEDESIS_SIMD_DISPATCH
    if (level == SimdLevel::avx512) return &near_row_avx512<D>;
    if (level == SimdLevel::avx2) return &near_row_avx2<D>;
#endif
    (void)level;
    return &near_row_scalar_call<D>;
}

} // namespace pedesis::detail
