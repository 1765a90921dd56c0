#pragma once
// The pair rows in mixed precision (`precision = "mixed"`): positions copied to floats,
// the pair math and the per-particle force sums in float, eight candidates per vector
// (twice the doubles' four in the same registers); the forces then added to the state's
// double forces, which the integrators step in double. The AVX-512 set runs the same
// eight lanes: sixteen (one zmm, the transposes over four 128-bit quarters) ran in.lj at
// 0.68x the speed of double here (docs/performance.md, "Mixed precision"). Energies and virials are
// not computed here: the totals (PairForce::add_totals) stay in double from the double positions.
//
// The rows of one radius and one evaluator, with the AVX2 and AVX-512 sets (the common
// case); other rows (several radii or evaluators, the SSE2 set) run in double, and the
// run says which (PairForce::precision_in_use). The order of every sum is fixed as in
// pair_rows_lanes, so the forces are bit-identical whatever the thread count.
#include "pedesis/core/lanes.hpp"
#include "pedesis/soft/pair_rows.hpp"

namespace pedesis {

// What the mixed rows read and write, beside the double rows' input (its list, box and
// evaluator).
template <int D, class Pair> struct MixedRowsInput {
    const PairRowsInput<D, Pair>* rows; // list, box, evaluator, range, inner margins
    const Padded3f* position;
    Padded3f* force; // zero before the rows; added to the state's forces after them
};

namespace detail {

// Eight records (x y z 0) to x, y and z of the eight, in lane order 0..7.
[[gnu::always_inline]] inline std::array<lanes8f, 3> transpose_to_axes(const lanes4f (&p)[8]) {
    // a holds records 0 and 4, b 1 and 5, c 2 and 6, d 3 and 7: the 4 x 4 transpose
    // then works within each 128-bit half
    const lanes8f a = __builtin_shufflevector(p[0], p[4], 0, 1, 2, 3, 4, 5, 6, 7);
    const lanes8f b = __builtin_shufflevector(p[1], p[5], 0, 1, 2, 3, 4, 5, 6, 7);
    const lanes8f c = __builtin_shufflevector(p[2], p[6], 0, 1, 2, 3, 4, 5, 6, 7);
    const lanes8f d = __builtin_shufflevector(p[3], p[7], 0, 1, 2, 3, 4, 5, 6, 7);
    const lanes8f xy01 = __builtin_shufflevector(a, b, 0, 8, 1, 9, 4, 12, 5, 13);
    const lanes8f z01 = __builtin_shufflevector(a, b, 2, 10, 3, 11, 6, 14, 7, 15);
    const lanes8f xy23 = __builtin_shufflevector(c, d, 0, 8, 1, 9, 4, 12, 5, 13);
    const lanes8f z23 = __builtin_shufflevector(c, d, 2, 10, 3, 11, 6, 14, 7, 15);
    return {__builtin_shufflevector(xy01, xy23, 0, 1, 8, 9, 4, 5, 12, 13),
            __builtin_shufflevector(xy01, xy23, 2, 3, 10, 11, 6, 7, 14, 15),
            __builtin_shufflevector(z01, z23, 0, 1, 8, 9, 4, 5, 12, 13)};
}

// x, y and z of eight forces to eight records (x y z 0).
[[gnu::always_inline]] inline std::array<lanes4f, 8>
transpose_to_neighbours(const lanes8f (&f)[3]) {
    const lanes8f zero{};
    const lanes8f xy01 = __builtin_shufflevector(f[0], f[1], 0, 8, 1, 9, 4, 12, 5, 13);
    const lanes8f xy23 = __builtin_shufflevector(f[0], f[1], 2, 10, 3, 11, 6, 14, 7, 15);
    const lanes8f z01 = __builtin_shufflevector(f[2], zero, 0, 8, 1, 9, 4, 12, 5, 13);
    const lanes8f z23 = __builtin_shufflevector(f[2], zero, 2, 10, 3, 11, 6, 14, 7, 15);
    const lanes8f r04 = __builtin_shufflevector(xy01, z01, 0, 1, 8, 9, 4, 5, 12, 13);
    const lanes8f r15 = __builtin_shufflevector(xy01, z01, 2, 3, 10, 11, 6, 7, 14, 15);
    const lanes8f r26 = __builtin_shufflevector(xy23, z23, 0, 1, 8, 9, 4, 5, 12, 13);
    const lanes8f r37 = __builtin_shufflevector(xy23, z23, 2, 3, 10, 11, 6, 7, 14, 15);
    auto low = [](lanes8f v) { return __builtin_shufflevector(v, v, 0, 1, 2, 3); };
    auto high = [](lanes8f v) { return __builtin_shufflevector(v, v, 4, 5, 6, 7); };
    return {low(r04), low(r15), low(r26), low(r37), high(r04), high(r15), high(r26), high(r37)};
}

// The vector and mask types of W float lanes.
template <int W> struct FloatLanes;
template <> struct FloatLanes<8> {
    using V = lanes8f;
    using M = mask8;
};

// The W lanes summed in a fixed order (pairs, then pairs of pairs, ...).
template <class V, int W> [[gnu::always_inline]] inline float sum_lanes(const V& v) {
    float part[W];
    for (int l = 0; l < W; ++l) part[l] = v[l];
    for (int width = W / 2; width >= 1; width /= 2)
        for (int l = 0; l < width; ++l) part[l] = part[2 * l] + part[2 * l + 1];
    return part[0];
}

template <class Pair, class V>
[[gnu::always_inline]] inline V lanes_force_over_r(const Pair& pair, V r2, double rsum) {
    if constexpr (requires { pair.force_over_r_at(r2, rsum); })
        return pair.force_over_r_at(lane_sqrt(r2), rsum);
    else
        return pair.force_over_r(r2, rsum);
}

// pair_rows_lanes in float, W candidates at a time (see there for the prefetch and the
// tail's repeated candidate).
template <int W, int D, class Pair>
[[gnu::always_inline]] inline void pair_rows_mixed(const MixedRowsInput<D, Pair>& in,
                                                   std::span<const std::uint32_t> rows) {
    using V = typename FloatLanes<W>::V;
    using M = typename FloatLanes<W>::M;
    const PairRowsInput<D, Pair>& base = *in.rows;
    const Padded3f* pos = in.position;
    Padded3f* force = in.force;
    const NeighborList<D>& nl = *base.list;
    const Pair pair = base.pairs[0]; // a copy (pair_rows_lanes says why)
    const V rc2 = V{} + static_cast<float>(base.range2);
    V half[D], length[D];
    for (int a = 0; a < D; ++a) {
        const bool periodic = base.box->periodic(a);
        half[a] = V{} + (periodic ? static_cast<float>(base.box->hi(a))
                                  : std::numeric_limits<float>::infinity());
        length[a] = V{} + (periodic ? static_cast<float>(base.box->length(a)) : 0.0f);
    }
    const bool sheared = base.box->sheared();
    const V offset = V{} + static_cast<float>(base.box->shear_offset());
    M lane;
    for (int l = 0; l < W; ++l) lane[l] = l;
    const V one = V{} + 1.0f;
    for (std::size_t r = 0; r < rows.size(); ++r) {
        const std::uint32_t i = rows[r];
        if (r + 2 < rows.size()) prefetch_row(nl, rows[r + 2], pos);
        const double rsum = 2.0 * base.table[base.species[i]].radius;
        bool interior = true;
        for (int a = 0; a < D; ++a)
            interior = interior && std::abs(base.position[i][a]) < base.inner[a];
        const Padded3f ri = pos[i];
        V fi[D] = {};
        auto group = [&]<bool Tail>(const std::uint32_t* it, std::ptrdiff_t left)
            __attribute__((always_inline)) {
            std::uint32_t j[W];
            for (int l = 0; l < W; ++l) j[l] = Tail ? it[l < left ? l : 0] : it[l];
            lanes4f pj[W];
            for (int l = 0; l < W; ++l) pj[l] = load_padded(pos[j[l]]);
            const auto xyz = transpose_to_axes(pj);
            V d[D];
            for (int a = 0; a < D; ++a) d[a] = ri.c[a] - xyz[a];
            if (sheared && !interior) {
                const M up = d[1] > half[1], down = d[1] < -half[1];
                d[1] = d[1] - select(up, length[1], V{}) + select(down, length[1], V{});
                d[0] = d[0] - select(up, offset, V{}) + select(down, offset, V{});
            }
            if (!interior)
                for (int a = 0; a < D; ++a) {
                    d[a] = d[a] - select(d[a] > half[a], length[a], V{});
                    d[a] = d[a] + select(d[a] < -half[a], length[a], V{});
                }
            V r2 = d[0] * d[0];
            for (int a = 1; a < D; ++a) r2 += d[a] * d[a];
            M active = r2 < rc2;
            if constexpr (Tail) active &= lane < static_cast<std::int32_t>(left);
            const V fr =
                select(active, lanes_force_over_r(pair, select(active, r2, one), rsum), V{});
            V fa[3] = {};
            for (int a = 0; a < D; ++a) {
                fa[a] = fr * d[a];
                fi[a] += fa[a];
            }
            const auto per_neighbour = transpose_to_neighbours(fa);
            for (int l = 0; l < W; ++l) sub_padded(force[j[l]], per_neighbour[l]);
        };
        const std::uint32_t* it = nl.begin(i);
        const std::uint32_t* const end = nl.end(i);
        for (; end - it >= W; it += W) group.template operator()<false>(it, W);
        if (it < end) group.template operator()<true>(it, end - it);
        for (int a = 0; a < D; ++a) force[i].c[a] += sum_lanes<V, W>(fi[a]);
    }
}

#if PEDESIS_SIMD_DISPATCH
template <int D, class Pair>
PEDESIS_SIMD_TARGET_AVX2 void pair_rows_mixed_avx2(const MixedRowsInput<D, Pair>& in,
                                                   std::span<const std::uint32_t> rows) {
    pair_rows_mixed<8, D, Pair>(in, rows);
}
template <int D, class Pair>
PEDESIS_SIMD_TARGET_AVX512 void pair_rows_mixed_avx512(const MixedRowsInput<D, Pair>& in,
                                                       std::span<const std::uint32_t> rows) {
    pair_rows_mixed<8, D, Pair>(in, rows);
}
#endif

} // namespace detail

// The mixed rows for the kernel set in use; null where there are none (the SSE2 set,
// or a build without the dispatch): those rows run in double.
template <int D, class Pair>
auto mixed_pair_rows_for(SimdLevel level)
    -> void (*)(const MixedRowsInput<D, Pair>&, std::span<const std::uint32_t>) {
#if PEDESIS_SIMD_DISPATCH
    if (level == SimdLevel::avx512) return &detail::pair_rows_mixed_avx512<D, Pair>;
    if (level == SimdLevel::avx2) return &detail::pair_rows_mixed_avx2<D, Pair>;
#endif
    (void)level;
    return nullptr;
}

} // namespace pedesis
