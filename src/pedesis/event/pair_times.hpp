#pragma once
// A particle's collision times with every neighbour in its list, for the AVX2 and
// AVX-512 kernel sets: four neighbours per instruction (AVX2) and no branch. The scalar loop
// (the sse2 set) branches on whether each pair approaches, which no predictor guesses,
// and a prediction meets a dozen such branches.
//
// The kernel computes, per neighbour, the quantities pair_collision_time_before decides
// from, by the same operations in the same order and without fused multiply-adds (it
// is compiled for AVX2 without FMA, below), so that the caller's scan over them picks
// the partner and time the scalar loop picks, bit for bit, in every kernel set
// (EventEngine::predict_with).
#include "pedesis/core/lanes.hpp"
#include "pedesis/core/simd_level.hpp"
#include "pedesis/core/vec.hpp"
#include "pedesis/event/flight.hpp"
#include "pedesis/event/prediction.hpp"

#include <array>
#include <cstddef>
#include <cstdint>
#include <cstring>

namespace pedesis {

// What one batch reads: particle i at time now, and its neighbours as stored (r_j at
// their own times t_j).
template <int D> struct PairTimesInput {
    const Flight<D>* flight;
    const double* radius; // per species
    const std::uint32_t* list;
    std::size_t n;
    Vec<D> xi, vi;
    double ri, now;
    // the minimum image: half lengths (infinite on walled axes) and lengths
    std::array<double, D> half, length;
};

// Per neighbour k: b = dr.dv, c = |dr|^2 - sigma^2 and the collision time (never where
// the pair recedes or misses). pair_collision_time_before(bound) returns time[k] unless
// c[k] > -2 b[k] bound. Each array has room for n rounded up to four.
struct PairTimes {
    double* b;
    double* c;
    double* time;
};

inline constexpr std::size_t pair_times_room(std::size_t n) {
    return (n + 3) / 4 * 4;
}

namespace detail {

template <int D>
[[gnu::always_inline]] inline void pair_times_lanes(const PairTimesInput<D>& in,
                                                    const PairTimes& out) {
    const lanes4 infinity = lanes4{} + never;
    for (std::size_t k = 0; k < in.n; k += 4) {
        // lanes past the end repeat the first neighbour of the four; their results are
        // written to the arrays' spare room and never read
        std::uint32_t j[4];
        for (std::size_t l = 0; l < 4; ++l) j[l] = in.list[k + l < in.n ? k + l : k];
        const Flight<D>* f[4] = {&in.flight[j[0]], &in.flight[j[1]], &in.flight[j[2]],
                                 &in.flight[j[3]]};
        const lanes4 dt = in.now - lanes4{f[0]->t, f[1]->t, f[2]->t, f[3]->t};
        // dot's order: 0.0, then each axis's product added
        lanes4 b = {}, dr2 = {}, dv2 = {};
        for (int a = 0; a < D; ++a) {
            const lanes4 x = {f[0]->x[a], f[1]->x[a], f[2]->x[a], f[3]->x[a]};
            const lanes4 v = {f[0]->v[a], f[1]->v[a], f[2]->v[a], f[3]->v[a]};
            lanes4 d = in.xi[a] - (x + v * dt);
            // Box::minimum_image: subtract L above L/2, else add it below -L/2
            d = select(d > in.half[a], d - in.length[a],
                       select(d < -in.half[a], d + in.length[a], d));
            const lanes4 dv = in.vi[a] - v;
            b += d * dv;
            dr2 += d * d;
            dv2 += dv * dv;
        }
        lanes4 sigma;
        for (int l = 0; l < 4; ++l) sigma[l] = in.ri + in.radius[f[l]->species];
        const lanes4 c = dr2 - sigma * sigma;
        const lanes4 disc = b * b - dv2 * c;
        const mask4 hit = (b < 0.0) & (disc > 0.0);
        lanes4 t = c / (-b + lane_sqrt(select(hit, disc, lanes4{})));
        t = select(t > 0.0, t, lanes4{});
        t = select(hit, t, infinity);
        std::memcpy(out.b + k, &b, sizeof b);
        std::memcpy(out.c + k, &c, sizeof c);
        std::memcpy(out.time + k, &t, sizeof t);
    }
}

#if PEDESIS_SIMD_DISPATCH
// Compiled for AVX2 without FMA (GCC would fuse multiplies and adds where FMA is
// available, and the times would differ from the scalar loop's in the last bits); the
// AVX-512 set runs it too.
template <int D>
[[gnu::target("avx2")]] void pair_times_avx2(const PairTimesInput<D>& in, const PairTimes& out) {
    pair_times_lanes<D>(in, out);
}
#endif

} // namespace detail

template <int D> using PairTimesKernel = void (*)(const PairTimesInput<D>&, const PairTimes&);

// The batch kernel of the set in use; nullptr for sse2, which keeps the scalar loop.
template <int D> PairTimesKernel<D> pair_times_for(SimdLevel level) {
#if PEDESIS_SIMD_DISPATCH
    if (level != SimdLevel::sse2) return &detail::pair_times_avx2<D>;
#endif
    (void)level;
    return nullptr;
}

} // namespace pedesis
