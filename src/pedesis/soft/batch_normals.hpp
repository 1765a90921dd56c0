#pragma once
// Standard normals for a batch of particles from the counter-based Philox stream, for
// the integrators' noise (brownian, brownian_rotation, langevin).
#include "pedesis/core/noise_log.hpp"
#include "pedesis/core/philox_batch.hpp"
#include "pedesis/core/simd_level.hpp"

#include <cmath>
#include <cstdint>

namespace pedesis::detail {

// Particles per batch of the integrator loops.
constexpr int noise_batch = 64;

// `Per` standard normals for each of the m <= noise_batch particles with tags tag[0..m),
// into z[k * Per + c]: Box-Muller on the Philox stream (seed, stream, tag, step), both
// halves of each draw used (2D translation needs one Philox block and one logarithm).
// The work runs in phases over the batch (Philox blocks, logarithms, polynomials)
// rather than particle by particle: one particle's chain of dependent operations is
// long, the processor overlaps many short independent ones far better, and each phase
// runs several particles per SIMD instruction. Each number is computed by the same
// operations as alone, so nothing depends on batching, nor on the kernel set: `Lanes`
// (philox_batch.hpp) and the width of the other phases' vectors change only the speed.
template <int Per, class Lanes>
inline void batch_normals_with(std::uint64_t seed, RngStream stream, const std::uint32_t* tag,
                               std::uint32_t step, int m, double* z) {
    constexpr int pairs = (Per + 1) / 2;
    constexpr int B = noise_batch;
    // draw p of particle k at [p * B + k]
    double u1[B * pairs], u2[B * pairs];
    for (int p = 0; p < pairs; ++p)
        philox_uniforms<Lanes>(seed, stream, tag, step, static_cast<std::uint32_t>(p), m,
                               u1 + p * B, u2 + p * B);
    double r[B * pairs], sn[B * pairs], cs[B * pairs];
    for (int p = 0; p < pairs; ++p) {
        for (int k = p * B; k < p * B + m; ++k) r[k] = std::sqrt(-2.0 * noise_log(u1[k]));
        for (int k = p * B; k < p * B + m; ++k) sincos_turns(u2[k], sn[k], cs[k]);
    }
    for (int k = 0; k < m; ++k)
        for (int c = 0; c < Per; ++c) {
            const int q = (c / 2) * B + k;
            z[k * Per + c] = r[q] * (c % 2 == 0 ? cs[q] : sn[q]);
        }
}

#if PEDESIS_PHILOX_AVX2
// AVX2 without FMA: the phases' sums and products round as in SSE2.
template <int Per>
[[gnu::target("avx2"), gnu::flatten]] void
batch_normals_avx2(std::uint64_t seed, RngStream stream, const std::uint32_t* tag,
                   std::uint32_t step, int m, double* z) {
    batch_normals_with<Per, Avx2Lanes>(seed, stream, tag, step, m, z);
}
#endif

// The normals, with the kernel set in use.
template <int Per>
void batch_normals(std::uint64_t seed, RngStream stream, const std::uint32_t* tag,
                   std::uint32_t step, int m, double* z) {
#if PEDESIS_PHILOX_AVX2
    if (simd_level() != SimdLevel::sse2)
        return batch_normals_avx2<Per>(seed, stream, tag, step, m, z);
#endif
    batch_normals_with<Per, DefaultLanes>(seed, stream, tag, step, m, z);
}

} // namespace pedesis::detail
