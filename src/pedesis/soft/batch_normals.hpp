#pragma once
// Standard normals for a batch of particles from the counter-based Philox stream, for
// the integrators' noise (brownian, brownian_rotation, langevin).
#include "pedesis/core/chunk_shares.hpp"
#include "pedesis/core/noise_log.hpp"
#include "pedesis/core/philox_batch.hpp"
#include "pedesis/core/simd_level.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <span>

namespace pedesis::detail {

// Particles per batch of the integrator loops.
constexpr int noise_batch = 64;
// Batches a thread takes at a time from its share (core/chunk_shares.hpp): 256 particles,
// a few microseconds of drawing and moving, against some 10 ns to take the chunk.
constexpr std::int64_t batches_per_chunk = 4;
// Normals a particle's rotation draws per step: an angle in 2D, a vector in 3D. (Array
// bounds inside the integrators' lambdas come from namespace constants: GCC 12 fails on
// local ones.)
template <int D> constexpr int normals_per_rotation = D == 2 ? 1 : 3;

// body(first, m) for every batch of [0, n): particles first .. first + m - 1 (m is
// noise_batch but in the last), in parallel, shared out by ChunkShares along the
// particle ranges `bounds` where they fit. (No reduction clause: the integrators gather
// a rare blow-up through detail::FirstBadMove.)
template <class Body>
void parallel_for_each_batch(std::int64_t n, std::span<const std::int64_t> bounds, Body&& body) {
    ChunkShares shares(n, batches_per_chunk, noise_batch, bounds);
#pragma omp parallel
    shares.run([&](std::int64_t first_batch, std::int64_t last_batch) {
        for (std::int64_t b = first_batch; b < last_batch; ++b) {
            const std::int64_t first = b * noise_batch;
            body(first, static_cast<int>(std::min<std::int64_t>(noise_batch, n - first)));
        }
    });
}

// The Philox uniforms of the (Per + 1) / 2 blocks of each particle, block p of particle k
// at [p * noise_batch + k]: the first and second of each block in u1 and u2.
template <int Per, class Lanes>
inline void batch_draws(std::uint64_t seed, RngStream stream, const std::uint32_t* tag,
                        std::uint32_t step, int m, double* u1, double* u2) {
    for (int p = 0; p < (Per + 1) / 2; ++p)
        philox_uniforms<Lanes>(seed, stream, tag, step, static_cast<std::uint32_t>(p), m,
                               u1 + p * noise_batch, u2 + p * noise_batch);
}

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
    double u1[B * pairs], u2[B * pairs];
    batch_draws<Per, Lanes>(seed, stream, tag, step, m, u1, u2);
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

// The shape of the translational noise of brownian and langevin (their uniform_noise
// flag): standard normals, or uniforms on [-sqrt 3, sqrt 3], whose mean (0) and variance
// (1) are the same. The second is what LAMMPS' fix langevin draws (and fix brownian by
// default): without the logarithm and sine of Box-Muller, for about a sixth of a 2D WCA
// Langevin step (docs/performance.md). Diffusion and the temperature are the same, and
// the velocities of a langevin run become Gaussian by the sum of many kicks;
// docs/engines.md ("Uniform noise") says what differs.
enum class NoiseShape : std::uint8_t { gaussian, uniform };

// `Per` uniform variates of mean 0 and variance 1 per particle, from the same Philox
// draws that batch_normals_with turns into normals.
template <int Per, class Lanes>
inline void batch_uniform_noise_with(std::uint64_t seed, RngStream stream, const std::uint32_t* tag,
                                     std::uint32_t step, int m, double* z) {
    constexpr int B = noise_batch;
    double u1[B * ((Per + 1) / 2)], u2[B * ((Per + 1) / 2)];
    batch_draws<Per, Lanes>(seed, stream, tag, step, m, u1, u2);
    constexpr double sqrt3 = 1.7320508075688772;
    for (int k = 0; k < m; ++k)
        for (int c = 0; c < Per; ++c) {
            const int q = (c / 2) * B + k;
            const double u = c % 2 == 0 ? u1[q] : u2[q]; // in (0, 1], a multiple of 2^-53
            // (2u - 1) - 2^-53 is exact and takes values symmetric about 0
            z[k * Per + c] = sqrt3 * ((2.0 * u - 1.0) - 0x1p-53);
        }
}

#if PEDESIS_PHILOX_AVX2
template <int Per>
[[gnu::target("avx2"), gnu::flatten]] void
batch_uniform_noise_avx2(std::uint64_t seed, RngStream stream, const std::uint32_t* tag,
                         std::uint32_t step, int m, double* z) {
    batch_uniform_noise_with<Per, Avx2Lanes>(seed, stream, tag, step, m, z);
}

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

// The noise of the given shape, with the kernel set in use.
template <int Per>
void batch_noise(NoiseShape shape, std::uint64_t seed, RngStream stream, const std::uint32_t* tag,
                 std::uint32_t step, int m, double* z) {
    if (shape == NoiseShape::gaussian) return batch_normals<Per>(seed, stream, tag, step, m, z);
#if PEDESIS_PHILOX_AVX2
    if (simd_level() != SimdLevel::sse2)
        return batch_uniform_noise_avx2<Per>(seed, stream, tag, step, m, z);
#endif
    batch_uniform_noise_with<Per, DefaultLanes>(seed, stream, tag, step, m, z);
}

} // namespace pedesis::detail
