#pragma once
// Counter-based random numbers (Philox4x32-10 from Random123). A draw is a pure
// function of (seed, stream, tag, counter), so results do not depend on thread
// count or particle order.
#include <Random123/philox.h>
#include <Random123/uniform.hpp>

#include "pedesis/core/sincos.hpp"

#include <bit>
#include <cmath>
#include <cstdint>
#include <numbers>

#if defined(__SSE2__)
#include <emmintrin.h>
#endif

namespace pedesis {

enum class RngStream : std::uint32_t {
    placement = 1,
    velocity = 2,
    orientation = 3,
    thermostat = 4,
    initial_director = 5,
};

class CounterRng {
  public:
    CounterRng(std::uint64_t seed, RngStream stream, std::uint32_t tag, std::uint32_t step = 0)
        : key_{{static_cast<std::uint32_t>(seed), static_cast<std::uint32_t>(seed >> 32)}},
          ctr_{{tag, step, static_cast<std::uint32_t>(stream), 0u}} {}

    // uniform in (0, 1]
    double uniform() {
        if (used_ == 2) refill();
        const std::uint64_t hi = out_[2 * used_], lo = out_[2 * used_ + 1];
        ++used_;
        const std::uint64_t bits = ((hi << 32) | lo) >> 11; // 53 random bits
        return (static_cast<double>(bits) + 1.0) * 0x1.0p-53;
    }
    double uniform(double a, double b) { return a + (b - a) * uniform(); }

    // Standard normal by Box-Muller; keeps the second value for the next call.
    double normal() {
        if (has_spare_) {
            has_spare_ = false;
            return spare_;
        }
        const double u1 = uniform(), u2 = uniform();
        const double r = std::sqrt(-2.0 * std::log(u1));
        spare_ = r * std::sin(2.0 * std::numbers::pi * u2);
        has_spare_ = true;
        return r * std::cos(2.0 * std::numbers::pi * u2);
    }

  private:
    using Philox = r123::Philox4x32;
    void refill() {
        out_ = Philox()(ctr_, key_);
        ctr_[3]++;
        used_ = 0;
    }
    Philox::key_type key_;
    Philox::ctr_type ctr_;
    Philox::ctr_type out_{};
    int used_ = 2;
    bool has_spare_ = false;
    double spare_ = 0.0;
};

namespace detail {

// The two uniforms of Philox block `block` of the m streams (seed, stream, tag[k], step):
// u1[k], u2[k] are exactly the (2 block + 1)-th and (2 block + 2)-th values of
// CounterRng(seed, stream, tag[k], step).uniform(). One particle's Philox block is a
// chain of ten dependent rounds; with SSE2 eight particles go through the rounds
// together (two chains of four lanes), at about 60% of the cost of one block at a time.
inline void philox_uniforms(std::uint64_t seed, RngStream stream, const std::uint32_t* tag,
                            std::uint32_t step, std::uint32_t block, int m, double* u1,
                            double* u2) {
    int k = 0;
#if defined(__SSE2__)
    const auto k0 = static_cast<std::uint32_t>(seed), k1 = static_cast<std::uint32_t>(seed >> 32);
    const auto st = static_cast<std::uint32_t>(stream);
    // Random123's constants: multipliers and the Weyl increments of the key
    const __m128i m0 = _mm_set1_epi32(static_cast<int>(0xD2511F53u));
    const __m128i m1 = _mm_set1_epi32(static_cast<int>(0xCD9E8D57u));
    __m128i key0[10], key1[10];
    for (std::uint32_t r = 0; r < 10; ++r) {
        key0[r] = _mm_set1_epi32(static_cast<int>(k0 + r * 0x9E3779B9u));
        key1[r] = _mm_set1_epi32(static_cast<int>(k1 + r * 0xBB67AE85u));
    }
    // (hi, lo) words to (((hi << 32 | lo) >> 11) + 1) 2^-53, as CounterRng::uniform: the
    // 53-bit integer is converted exactly in two 32-bit halves (SSE2 has no 64-bit
    // integer to double conversion).
    auto to_uniform = [](__m128i hi, __m128i lo, double* out) {
        const __m128i low32 = _mm_set1_epi64x(0xffffffff);
        const __m128i exponent = _mm_set1_epi64x(0x4330000000000000); // 2^52
        const __m128d two52 = _mm_set1_pd(0x1p52), two32 = _mm_set1_pd(0x1p32);
        for (int h = 0; h < 2; ++h) {
            const __m128i x = _mm_srli_epi64(
                h == 0 ? _mm_unpacklo_epi32(lo, hi) : _mm_unpackhi_epi32(lo, hi), 11);
            const __m128d dh =
                _mm_sub_pd(_mm_castsi128_pd(_mm_or_si128(_mm_srli_epi64(x, 32), exponent)), two52);
            const __m128d dl = _mm_sub_pd(
                _mm_castsi128_pd(_mm_or_si128(_mm_and_si128(x, low32), exponent)), two52);
            const __m128d d = _mm_add_pd(_mm_mul_pd(dh, two32), dl);
            _mm_storeu_pd(out + 2 * h,
                          _mm_mul_pd(_mm_add_pd(d, _mm_set1_pd(1.0)), _mm_set1_pd(0x1p-53)));
        }
    };
    for (; k + 8 <= m; k += 8) {
        __m128i c0[2], c1[2], c2[2], c3[2];
        for (int v = 0; v < 2; ++v) {
            c0[v] = _mm_loadu_si128(reinterpret_cast<const __m128i*>(tag + k + 4 * v));
            c1[v] = _mm_set1_epi32(static_cast<int>(step));
            c2[v] = _mm_set1_epi32(static_cast<int>(st));
            c3[v] = _mm_set1_epi32(static_cast<int>(block));
        }
        for (int r = 0; r < 10; ++r)
            for (int v = 0; v < 2; ++v) {
                // 32 x 32 -> 64-bit products of the even lanes, then of the odd ones,
                // regrouped into the low and high words of the four lanes
                const __m128i e0 = _mm_mul_epu32(c0[v], m0);
                const __m128i o0 = _mm_mul_epu32(_mm_srli_epi64(c0[v], 32), m0);
                const __m128i e1 = _mm_mul_epu32(c2[v], m1);
                const __m128i o1 = _mm_mul_epu32(_mm_srli_epi64(c2[v], 32), m1);
                const __m128i a0 = _mm_unpacklo_epi32(e0, o0), b0 = _mm_unpackhi_epi32(e0, o0);
                const __m128i a1 = _mm_unpacklo_epi32(e1, o1), b1 = _mm_unpackhi_epi32(e1, o1);
                const __m128i lo0 = _mm_unpacklo_epi64(a0, b0), hi0 = _mm_unpackhi_epi64(a0, b0);
                const __m128i lo1 = _mm_unpacklo_epi64(a1, b1), hi1 = _mm_unpackhi_epi64(a1, b1);
                c0[v] = _mm_xor_si128(_mm_xor_si128(hi1, c1[v]), key0[r]);
                c1[v] = lo1;
                c2[v] = _mm_xor_si128(_mm_xor_si128(hi0, c3[v]), key1[r]);
                c3[v] = lo0;
            }
        for (int v = 0; v < 2; ++v) {
            to_uniform(c0[v], c1[v], u1 + k + 4 * v);
            to_uniform(c2[v], c3[v], u2 + k + 4 * v);
        }
    }
#endif
    for (; k < m; ++k) {
        CounterRng rng(seed, stream, tag[k], step);
        for (std::uint32_t b = 0; b < block; ++b) rng.uniform(), rng.uniform();
        u1[k] = rng.uniform();
        u2[k] = rng.uniform();
    }
}

} // namespace detail

} // namespace pedesis
