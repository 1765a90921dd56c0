#pragma once
// Philox blocks of many particles at once, for the integrators' noise. One particle's
// block is a chain of ten dependent rounds; running the chains of several particles side
// by side in SIMD lanes, two vectors at a time, hides that latency. SSE2 carries four
// particles per vector, AVX2 eight. The arithmetic is integer and the conversion to
// doubles exact, so every kernel set draws exactly the numbers of CounterRng.
#include "pedesis/core/rng.hpp"
#include "pedesis/core/simd_level.hpp"

#include <cstdint>
#include <type_traits>

#if defined(__SSE2__)
#include <immintrin.h>
#endif

// The AVX2 kernel is made by inlining the shared template into a function compiled for
// AVX2 (gnu::flatten), which GCC does when it optimises. Clang refuses to compile the
// template's AVX2 calls outside such a function, so its builds (and unoptimised ones)
// draw with SSE2 under every kernel set: the same numbers.
#if PEDESIS_SIMD_DISPATCH && defined(__OPTIMIZE__) && !defined(__clang__)
#define PEDESIS_PHILOX_AVX2 1
#else
#define PEDESIS_PHILOX_AVX2 0
#endif

namespace pedesis::detail {

#if defined(__SSE2__)

// The vector operations of a Philox round and of the conversion to doubles. All of them
// act within 128-bit lanes, so AVX2's are SSE2's twice over.
struct Sse2Lanes {
    using I = __m128i;
    using F = __m128d;
    static constexpr int width = 4; // particles per vector
    static I load(const std::uint32_t* p) { return _mm_loadu_si128(reinterpret_cast<const I*>(p)); }
    static I splat(std::uint32_t x) { return _mm_set1_epi32(static_cast<int>(x)); }
    static I splat64(std::uint64_t x) { return _mm_set1_epi64x(static_cast<long long>(x)); }
    static I mul_even(I a, I b) { return _mm_mul_epu32(a, b); }
    static I odd_to_even(I a) { return _mm_srli_epi64(a, 32); }
    static I shift11(I a) { return _mm_srli_epi64(a, 11); }
    static I unpack_lo32(I a, I b) { return _mm_unpacklo_epi32(a, b); }
    static I unpack_hi32(I a, I b) { return _mm_unpackhi_epi32(a, b); }
    static I unpack_lo64(I a, I b) { return _mm_unpacklo_epi64(a, b); }
    static I unpack_hi64(I a, I b) { return _mm_unpackhi_epi64(a, b); }
    static I bit_xor(I a, I b) { return _mm_xor_si128(a, b); }
    static I bit_or(I a, I b) { return _mm_or_si128(a, b); }
    static I bit_and(I a, I b) { return _mm_and_si128(a, b); }
    static F as_double(I a) { return _mm_castsi128_pd(a); }
    static F splat_double(double x) { return _mm_set1_pd(x); }
    static F add(F a, F b) { return _mm_add_pd(a, b); }
    static F sub(F a, F b) { return _mm_sub_pd(a, b); }
    static F mul(F a, F b) { return _mm_mul_pd(a, b); }
    // first: elements 0, 1; second: 2, 3
    static void store(double* out, F first, F second) {
        _mm_storeu_pd(out, first);
        _mm_storeu_pd(out + 2, second);
    }
};

#if PEDESIS_PHILOX_AVX2
#define PEDESIS_AVX2_ONLY [[gnu::target("avx2")]]
struct Avx2Lanes {
    using I = __m256i;
    using F = __m256d;
    static constexpr int width = 8;
    PEDESIS_AVX2_ONLY static I load(const std::uint32_t* p) {
        return _mm256_loadu_si256(reinterpret_cast<const I*>(p));
    }
    PEDESIS_AVX2_ONLY static I splat(std::uint32_t x) {
        return _mm256_set1_epi32(static_cast<int>(x));
    }
    PEDESIS_AVX2_ONLY static I splat64(std::uint64_t x) {
        return _mm256_set1_epi64x(static_cast<long long>(x));
    }
    PEDESIS_AVX2_ONLY static I mul_even(I a, I b) { return _mm256_mul_epu32(a, b); }
    PEDESIS_AVX2_ONLY static I odd_to_even(I a) { return _mm256_srli_epi64(a, 32); }
    PEDESIS_AVX2_ONLY static I shift11(I a) { return _mm256_srli_epi64(a, 11); }
    PEDESIS_AVX2_ONLY static I unpack_lo32(I a, I b) { return _mm256_unpacklo_epi32(a, b); }
    PEDESIS_AVX2_ONLY static I unpack_hi32(I a, I b) { return _mm256_unpackhi_epi32(a, b); }
    PEDESIS_AVX2_ONLY static I unpack_lo64(I a, I b) { return _mm256_unpacklo_epi64(a, b); }
    PEDESIS_AVX2_ONLY static I unpack_hi64(I a, I b) { return _mm256_unpackhi_epi64(a, b); }
    PEDESIS_AVX2_ONLY static I bit_xor(I a, I b) { return _mm256_xor_si256(a, b); }
    PEDESIS_AVX2_ONLY static I bit_or(I a, I b) { return _mm256_or_si256(a, b); }
    PEDESIS_AVX2_ONLY static I bit_and(I a, I b) { return _mm256_and_si256(a, b); }
    PEDESIS_AVX2_ONLY static F as_double(I a) { return _mm256_castsi256_pd(a); }
    PEDESIS_AVX2_ONLY static F splat_double(double x) { return _mm256_set1_pd(x); }
    PEDESIS_AVX2_ONLY static F add(F a, F b) { return _mm256_add_pd(a, b); }
    PEDESIS_AVX2_ONLY static F sub(F a, F b) { return _mm256_sub_pd(a, b); }
    PEDESIS_AVX2_ONLY static F mul(F a, F b) { return _mm256_mul_pd(a, b); }
    // first: elements 0, 1 | 4, 5; second: 2, 3 | 6, 7 (the order of in-lane unpacks)
    PEDESIS_AVX2_ONLY static void store(double* out, F first, F second) {
        _mm256_storeu_pd(out, _mm256_permute2f128_pd(first, second, 0x20));
        _mm256_storeu_pd(out + 4, _mm256_permute2f128_pd(first, second, 0x31));
    }
};
#undef PEDESIS_AVX2_ONLY
#endif

// The words (hi, lo) of each particle to (((hi << 32 | lo) >> 11) + 1) 2^-53, as
// CounterRng::uniform does, into out[0, width). The 53-bit integer is converted exactly
// in two 32-bit halves, each through the double 2^52 + half (SSE2 and AVX2 have no
// 64-bit integer conversion); separate products and sums, as in every set.
template <class L> inline void lanes_to_uniforms(typename L::I hi, typename L::I lo, double* out) {
    using I = typename L::I;
    using F = typename L::F;
    const I low32 = L::splat64(0xffffffff), exponent = L::splat64(0x4330000000000000);
    const F two52 = L::splat_double(0x1p52);
    F u[2];
    for (int h = 0; h < 2; ++h) {
        const I x = L::shift11(h == 0 ? L::unpack_lo32(lo, hi) : L::unpack_hi32(lo, hi));
        const F high = L::sub(L::as_double(L::bit_or(L::odd_to_even(x), exponent)), two52);
        const F low = L::sub(L::as_double(L::bit_or(L::bit_and(x, low32), exponent)), two52);
        const F d = L::add(L::mul(high, L::splat_double(0x1p32)), low);
        u[h] = L::mul(L::add(d, L::splat_double(1.0)), L::splat_double(0x1p-53));
    }
    L::store(out, u[0], u[1]);
}

// Philox4x32-10 of particles [0, k) of the batch, 2 L::width at a time: the counters
// (tag, step, stream, block) under the key `seed`. Returns k, the particles done.
template <class L>
inline int philox_uniforms_lanes(std::uint64_t seed, RngStream stream, const std::uint32_t* tag,
                                 std::uint32_t step, std::uint32_t block, int m, double* u1,
                                 double* u2) {
    using I = typename L::I;
    constexpr int W = L::width;
    const auto k0 = static_cast<std::uint32_t>(seed), k1 = static_cast<std::uint32_t>(seed >> 32);
    // Random123's multipliers and the Weyl increments of the key
    const I m0 = L::splat(0xD2511F53u), m1 = L::splat(0xCD9E8D57u);
    I key0[10], key1[10];
    for (std::uint32_t r = 0; r < 10; ++r) {
        key0[r] = L::splat(k0 + r * 0x9E3779B9u);
        key1[r] = L::splat(k1 + r * 0xBB67AE85u);
    }
    int k = 0;
    for (; k + 2 * W <= m; k += 2 * W) {
        I c0[2], c1[2], c2[2], c3[2];
        for (int v = 0; v < 2; ++v) {
            c0[v] = L::load(tag + k + W * v);
            c1[v] = L::splat(step);
            c2[v] = L::splat(static_cast<std::uint32_t>(stream));
            c3[v] = L::splat(block);
        }
        for (int r = 0; r < 10; ++r)
            for (int v = 0; v < 2; ++v) {
                // 32 x 32 -> 64-bit products of the even elements, then of the odd ones,
                // regrouped into the low and high words of each element
                const I e0 = L::mul_even(c0[v], m0), o0 = L::mul_even(L::odd_to_even(c0[v]), m0);
                const I e1 = L::mul_even(c2[v], m1), o1 = L::mul_even(L::odd_to_even(c2[v]), m1);
                const I a0 = L::unpack_lo32(e0, o0), b0 = L::unpack_hi32(e0, o0);
                const I a1 = L::unpack_lo32(e1, o1), b1 = L::unpack_hi32(e1, o1);
                const I lo0 = L::unpack_lo64(a0, b0), hi0 = L::unpack_hi64(a0, b0);
                const I lo1 = L::unpack_lo64(a1, b1), hi1 = L::unpack_hi64(a1, b1);
                c0[v] = L::bit_xor(L::bit_xor(hi1, c1[v]), key0[r]);
                c1[v] = lo1;
                c2[v] = L::bit_xor(L::bit_xor(hi0, c3[v]), key1[r]);
                c3[v] = lo0;
            }
        for (int v = 0; v < 2; ++v) {
            lanes_to_uniforms<L>(c0[v], c1[v], u1 + k + W * v);
            lanes_to_uniforms<L>(c2[v], c3[v], u2 + k + W * v);
        }
    }
    return k;
}

#endif // __SSE2__

// Particles [k, m) of the batch one at a time, by CounterRng itself.
inline void philox_uniforms_one_by_one(std::uint64_t seed, RngStream stream,
                                       const std::uint32_t* tag, std::uint32_t step,
                                       std::uint32_t block, int k, int m, double* u1, double* u2) {
    for (; k < m; ++k) {
        CounterRng rng(seed, stream, tag[k], step);
        for (std::uint32_t b = 0; b < block; ++b) rng.uniform(), rng.uniform();
        u1[k] = rng.uniform();
        u2[k] = rng.uniform();
    }
}

// The two uniforms of Philox block `block` of the m streams (seed, stream, tag[k], step):
// u1[k], u2[k] are exactly the (2 block + 1)-th and (2 block + 2)-th values of
// CounterRng(seed, stream, tag[k], step).uniform(). `Lanes` is the kernel set's
// (Sse2Lanes or Avx2Lanes; void: one at a time).
template <class Lanes>
inline void philox_uniforms(std::uint64_t seed, RngStream stream, const std::uint32_t* tag,
                            std::uint32_t step, std::uint32_t block, int m, double* u1,
                            double* u2) {
    int k = 0;
    if constexpr (!std::is_void_v<Lanes>)
        k = philox_uniforms_lanes<Lanes>(seed, stream, tag, step, block, m, u1, u2);
    philox_uniforms_one_by_one(seed, stream, tag, step, block, k, m, u1, u2);
}

#if defined(__SSE2__)
using DefaultLanes = Sse2Lanes;
#else
using DefaultLanes = void;
#endif

} // namespace pedesis::detail
