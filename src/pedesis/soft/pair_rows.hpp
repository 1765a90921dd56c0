#pragma once
// The pair loop's rows, compiled once per kernel set (core/simd_level.hpp). pair_rows (the
// SSE2 set's path, and every set's for rows of several radii) and pair_rows_lanes (AVX2
// and AVX-512, rows of one radius) are written once and inlined into one wrapper per set,
// which compiles them with that set's registers; the set is chosen once per force
// evaluation, not per pair.
//
// pair_rows filters candidates in chunks: those within the pair's largest range are packed
// (branch-free) into a buffer and only they are evaluated. A third to a half of a row
// lies in the skin, at random, so testing each candidate with a branch mispredicted
// often; evaluating the packed ones keeps list order, so the sums are the same whatever
// the thread count.
#include "pedesis/core/box.hpp"
#include "pedesis/core/lanes.hpp"
#include "pedesis/core/simd_level.hpp"
#include "pedesis/core/species.hpp"
#include "pedesis/spatial/neighbor_list.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <limits>
#include <span>
#include <type_traits>

namespace pedesis {

// A 3D position or force in one aligned vector of four (the fourth lane unused: zero):
// the SIMD kernel reads four neighbours with four loads and a transpose, and adds their
// forces back with four, where three separate doubles cost three loads (and three
// lane extractions and stores for the forces) per neighbour.
struct alignas(32) Padded3 {
    double c[4];
};

// A position or force as four floats (x y z 0; in 2D z is 0 too), for the mixed rows
// (soft/pair_rows_mixed.hpp): one 16-byte load or store per neighbour.
struct alignas(16) Padded3f {
    float c[4];
};

// Whether the AVX2 and AVX-512 rows of one radius work on the padded copies (the one
// place the wrappers below and PairForce read it from).
template <int D> inline constexpr bool padded_rows = D == 3;

// What the rows read and write; one per force evaluation.
template <int D, class Pair> struct PairRowsInput {
    const Vec<D>* position;
    const std::uint16_t* species;
    const Species* table;
    const Pair* pairs;         // pairs[a * species_count + b]
    std::size_t species_count; // 1: one evaluator for all
    double range2;             // the largest range, squared
    Vec<D>* force;
    const Box<D>* box;
    const NeighborList<D>* list;
    // rows of particles this far inside every periodic face need no minimum image
    std::array<double, D> inner;
    // 3D with the AVX2 and AVX-512 sets: the positions and forces padded (the kernel
    // reads and writes these instead of position and force); null otherwise
    const Padded3* position4 = nullptr;
    Padded3* force4 = nullptr;
};

namespace detail {

inline constexpr int pair_chunk = 32;

template <int D>
[[gnu::always_inline]] inline void
pack_candidate(const Vec<D>& d, std::uint32_t j, double rsum, double rc2,
               double (&dbuf)[pair_chunk][D], double (&r2buf)[pair_chunk],
               double (&rsbuf)[pair_chunk], std::uint32_t (&jbuf)[pair_chunk], int& m) {
    const double r2 = squared_length(d);
    for (int a = 0; a < D; ++a) dbuf[m][a] = d[a];
    r2buf[m] = r2;
    rsbuf[m] = rsum;
    jbuf[m] = j;
    m += r2 < rc2;
}

// With one radius for all species (Uniform, the common case) the sum of radii is a
// constant and the rows never read the species of a neighbour.
template <int D, class Pair, bool Uniform>
[[gnu::always_inline]] inline void pair_rows(const PairRowsInput<D, Pair>& in,
                                             std::span<const std::uint32_t> rows) {
    constexpr int chunk = pair_chunk;
    const Vec<D>* pos = in.position;
    const std::uint16_t* sp = in.species;
    const Species* table = in.table;
    const std::size_t ns = in.species_count;
    const double rc2 = in.range2;
    const Box<D>& box = *in.box;
    const NeighborList<D>& nl = *in.list;
    Vec<D>* force = in.force;
    for (const std::uint32_t i : rows) {
        const Vec<D> ri = pos[i];
        const double rad_i = table[sp[i]].radius;
        const Pair* pair_row = in.pairs + (Uniform || ns == 1 ? 0 : sp[i] * ns);
        bool interior = true;
        for (int a = 0; a < D; ++a) interior = interior && std::abs(ri[a]) < in.inner[a];
        Vec<D> f{};
        // plain arrays: a std::array of Vec would be zeroed for every row
        double dbuf[chunk][D], r2buf[chunk], rsbuf[chunk];
        std::uint32_t jbuf[chunk];
        std::uint16_t sbuf[chunk]; // the neighbours' species (non-uniform path)
        for (const std::uint32_t* it = nl.begin(i); it != nl.end(i);) {
            const std::uint32_t* const stop = it + std::min<std::ptrdiff_t>(chunk, nl.end(i) - it);
            int m = 0;
            if (interior)
                for (; it != stop; ++it) {
                    const Vec<D> d = ri - pos[*it];
                    if constexpr (!Uniform) sbuf[m] = sp[*it];
                    pack_candidate<D>(d, *it, Uniform ? 0.0 : rad_i + table[sp[*it]].radius, rc2,
                                      dbuf, r2buf, rsbuf, jbuf, m);
                }
            else
                for (; it != stop; ++it) {
                    const Vec<D> d = box.minimum_image(ri - pos[*it]);
                    if constexpr (!Uniform) sbuf[m] = sp[*it];
                    pack_candidate<D>(d, *it, Uniform ? 0.0 : rad_i + table[sp[*it]].radius, rc2,
                                      dbuf, r2buf, rsbuf, jbuf, m);
                }
            double frbuf[chunk];
            if constexpr (Uniform) {
                // Every packed pair lies within the one range: F/r for all of them in a
                // loop without branches (several pairs per SIMD instruction).
                const double rsum_uniform = 2.0 * rad_i;
                const Pair& pair = in.pairs[0];
                for (int q = 0; q < m; ++q) frbuf[q] = pair.force_over_r(r2buf[q], rsum_uniform);
            } else {
                for (int q = 0; q < m; ++q) {
                    double energy;
                    const Pair& pair = pair_row[ns == 1 ? 0 : sbuf[q]];
                    if (!pair.eval(r2buf[q], rsbuf[q], frbuf[q], energy)) frbuf[q] = 0.0;
                }
            }
            // summed in list order; each neighbour gets the opposite force
            for (int q = 0; q < m; ++q) {
                Vec<D>& fj = force[jbuf[q]];
                for (int a = 0; a < D; ++a) {
                    const double fa = frbuf[q] * dbuf[q][a];
                    f[a] += fa;
                    fj[a] -= fa;
                }
            }
        }
        force[i] += f;
    }
}

// The vector of one padded record: four doubles, or four floats (the mixed rows).
template <class Record>
using record_lanes = std::conditional_t<std::is_same_v<Record, Padded3>, lanes4, lanes4f>;

template <class Record>
[[gnu::always_inline]] inline record_lanes<Record> load_padded(const Record& p) {
    record_lanes<Record> v;
    std::memcpy(&v, p.c, sizeof v);
    return v;
}
template <class Record>
[[gnu::always_inline]] inline void sub_padded(Record& p, record_lanes<Record> v) {
    record_lanes<Record> now = load_padded(p);
    now -= v;
    std::memcpy(p.c, &now, sizeof now);
}

// Four padded records (x y z 0 each) to x, y and z of the four.
[[gnu::always_inline]] inline std::array<lanes4, 3> transpose_to_axes(const lanes4 (&p)[4]) {
    const lanes4 xz01 = __builtin_shufflevector(p[0], p[1], 0, 4, 2, 6); // x0 x1 z0 z1
    const lanes4 y01 = __builtin_shufflevector(p[0], p[1], 1, 5, 3, 7);  // y0 y1 0 0
    const lanes4 xz23 = __builtin_shufflevector(p[2], p[3], 0, 4, 2, 6); // x2 x3 z2 z3
    const lanes4 y23 = __builtin_shufflevector(p[2], p[3], 1, 5, 3, 7);  // y2 y3 0 0
    return {__builtin_shufflevector(xz01, xz23, 0, 1, 4, 5),
            __builtin_shufflevector(y01, y23, 0, 1, 4, 5),
            __builtin_shufflevector(xz01, xz23, 2, 3, 6, 7)};
}

// x, y and z of four forces to four padded records (x y z 0 each).
[[gnu::always_inline]] inline std::array<lanes4, 4> transpose_to_neighbours(const lanes4 (&f)[3]) {
    const lanes4 zero{};
    const lanes4 xy02 = __builtin_shufflevector(f[0], f[1], 0, 4, 2, 6); // x0 y0 x2 y2
    const lanes4 xy13 = __builtin_shufflevector(f[0], f[1], 1, 5, 3, 7); // x1 y1 x3 y3
    const lanes4 z02 = __builtin_shufflevector(f[2], zero, 0, 4, 2, 6);  // z0 0 z2 0
    const lanes4 z13 = __builtin_shufflevector(f[2], zero, 1, 5, 3, 7);  // z1 0 z3 0
    return {__builtin_shufflevector(xy02, z02, 0, 1, 4, 5),
            __builtin_shufflevector(xy13, z13, 0, 1, 4, 5),
            __builtin_shufflevector(xy02, z02, 2, 3, 6, 7),
            __builtin_shufflevector(xy13, z13, 2, 3, 6, 7)};
}

// The first two lines of row k's list and its particle's record.
template <int D, class Record>
[[gnu::always_inline]] inline void prefetch_row(const NeighborList<D>& nl, std::uint32_t k,
                                                const Record* pos) {
    const std::uint32_t* ahead = nl.begin(k);
    __builtin_prefetch(ahead);
    if (nl.count(k) > 16) __builtin_prefetch(ahead + 16); // (within the row)
    __builtin_prefetch(&pos[k]);
}

// The SIMD kernel for one radius and one evaluator (the common case): four candidates at
// a time in GCC's vector types, which each wrapper compiles for its own registers (AVX2:
// one ymm per four; AVX-512: the same with masks). Candidates beyond the range are
// computed too and their force zeroed, which costs less than packing them away once four
// lanes share an instruction. Each row's own force is summed per lane and the four lanes
// added at the end, in a fixed order: bit-identical for any thread count, not equal in
// the last bits to pair_rows (the sse2 set). In 3D (Padded) the rows read and write
// padded copies of the positions and forces (Padded3): the same arithmetic in the same
// order, so the same bits, with about a third fewer instructions per four candidates.
template <class Pair>
[[gnu::always_inline]] inline lanes4 lanes_force_over_r(const Pair& pair, lanes4 r2, double rsum) {
    if constexpr (requires { pair.force_over_r_at(r2, rsum); })
        return pair.force_over_r_at(lane_sqrt(r2), rsum);
    else
        return pair.force_over_r(r2, rsum);
}

template <int D, class Pair, bool Padded>
[[gnu::always_inline]] inline void pair_rows_lanes(const PairRowsInput<D, Pair>& in,
                                                   std::span<const std::uint32_t> rows) {
    static_assert(!Padded || D == 3);
    const Vec<D>* pos = in.position;
    const Padded3* pos4 = in.position4;
    Padded3* force4 = in.force4;
    const NeighborList<D>& nl = *in.list;
    // a copy: read through a reference, the parameters could alias the forces the loop
    // writes, and the compiler would load them again for every four candidates
    const Pair pair = in.pairs[0];
    const double rc2 = in.range2;
    Vec<D>* force = in.force;
    // the minimum image as the box makes it: d -= L where d > L/2, d += L where d < -L/2
    // (under Lees-Edwards shear y first, its crossing moving x by the offset: core/box.hpp)
    lanes4 half[D], length[D];
    for (int a = 0; a < D; ++a) {
        const bool periodic = in.box->periodic(a);
        half[a] = lanes4{} + (periodic ? in.box->hi(a) : std::numeric_limits<double>::infinity());
        length[a] = lanes4{} + (periodic ? in.box->length(a) : 0.0);
    }
    const bool sheared = in.box->sheared();
    const lanes4 offset = lanes4{} + in.box->shear_offset();
    const mask4 lane = {0, 1, 2, 3};
    const lanes4 one = lanes4{} + 1.0;
    for (std::size_t r = 0; r < rows.size(); ++r) {
        const std::uint32_t i = rows[r];
        // Two rows ahead: the first two lines of that row's list and its particle. The
        // rows go in colour-block order, not in storage order, so a row's list starts
        // where the hardware prefetcher did not look, and the row's first loads waited
        // on it (in.lj 1.03 with this alone, docs/performance.md).
        if (r + 2 < rows.size()) prefetch_row(nl, rows[r + 2], pos);
        const Vec<D> ri = pos[i];
        const double rsum = 2.0 * in.table[in.species[i]].radius;
        bool interior = true;
        for (int a = 0; a < D; ++a) interior = interior && std::abs(ri[a]) < in.inner[a];
        lanes4 fi[D] = {};
        // Full iterations need no lane mask and read their four candidates straight; the
        // row's last, partial one (Tail) repeats its first candidate in the lanes past the
        // end, with no force. (The split saved about a tenth of the loop's instructions:
        // in.lj 1.05x, docs/performance.md.) always_inline like the kernel: a lambda does
        // not take its caller's target, so GCC, where it judged one too big to inline (the
        // partial one, once the shear's lines came in, and only in some translation
        // units), called a copy compiled for SSE2 without fused multiply-adds, whose last
        // bits differed from the set's, and the CLI from the Python module.
        auto four = [&]<bool Tail>(const std::uint32_t* it, std::ptrdiff_t left)
            __attribute__((always_inline)) {
            std::uint32_t j[4];
            for (int l = 0; l < 4; ++l) j[l] = Tail ? it[l < left ? l : 0] : it[l];
            lanes4 d[D];
            if constexpr (Padded) {
                const lanes4 pj[4] = {load_padded(pos4[j[0]]), load_padded(pos4[j[1]]),
                                      load_padded(pos4[j[2]]), load_padded(pos4[j[3]])};
                const auto xyz = transpose_to_axes(pj);
                for (int a = 0; a < D; ++a) d[a] = ri[a] - xyz[a];
            } else {
                for (int a = 0; a < D; ++a) {
                    const lanes4 pa = {pos[j[0]][a], pos[j[1]][a], pos[j[2]][a], pos[j[3]][a]};
                    d[a] = ri[a] - pa;
                }
            }
            if (sheared && !interior) {
                const mask4 up = d[1] > half[1], down = d[1] < -half[1];
                d[1] = d[1] - select(up, length[1], lanes4{}) + select(down, length[1], lanes4{});
                d[0] = d[0] - select(up, offset, lanes4{}) + select(down, offset, lanes4{});
            }
            for (int a = 0; a < D; ++a) {
                if (!interior) {
                    d[a] = d[a] - select(d[a] > half[a], length[a], lanes4{});
                    d[a] = d[a] + select(d[a] < -half[a], length[a], lanes4{});
                }
            }
            lanes4 r2 = d[0] * d[0];
            for (int a = 1; a < D; ++a) r2 += d[a] * d[a];
            mask4 active = r2 < rc2;
            if constexpr (Tail) active &= lane < left;
            const lanes4 fr =
                select(active, lanes_force_over_r(pair, select(active, r2, one), rsum), lanes4{});
            lanes4 fa[D];
            for (int a = 0; a < D; ++a) {
                fa[a] = fr * d[a];
                fi[a] += fa[a];
            }
            if constexpr (Padded) {
                const auto per_neighbour = transpose_to_neighbours(fa);
                for (int l = 0; l < 4; ++l) sub_padded(force4[j[l]], per_neighbour[l]);
            } else {
                for (int l = 0; l < 4; ++l)
                    for (int a = 0; a < D; ++a) force[j[l]][a] -= fa[a][l];
            }
        };
        const std::uint32_t* it = nl.begin(i);
        const std::uint32_t* const end = nl.end(i);
        for (; end - it >= 4; it += 4) four.template operator()<false>(it, 4);
        if (it < end) four.template operator()<true>(it, end - it);
        for (int a = 0; a < D; ++a) {
            const double own = (fi[a][0] + fi[a][1]) + (fi[a][2] + fi[a][3]);
            if constexpr (Padded)
                force4[i].c[a] += own;
            else
                force[i][a] += own;
        }
    }
}

template <int D, class Pair, bool Uniform>
void pair_rows_sse2(const PairRowsInput<D, Pair>& in, std::span<const std::uint32_t> rows) {
    pair_rows<D, Pair, Uniform>(in, rows);
}

#if PEDESIS_SIMD_DISPATCH
template <int D, class Pair, bool Uniform>
PEDESIS_SIMD_TARGET_AVX2 void pair_rows_avx2(const PairRowsInput<D, Pair>& in,
                                             std::span<const std::uint32_t> rows) {
    if constexpr (Uniform)
        pair_rows_lanes<D, Pair, padded_rows<D>>(in, rows);
    else
        pair_rows<D, Pair, Uniform>(in, rows);
}
template <int D, class Pair, bool Uniform>
PEDESIS_SIMD_TARGET_AVX512 void pair_rows_avx512(const PairRowsInput<D, Pair>& in,
                                                 std::span<const std::uint32_t> rows) {
    if constexpr (Uniform)
        pair_rows_lanes<D, Pair, padded_rows<D>>(in, rows);
    else
        pair_rows<D, Pair, Uniform>(in, rows);
}
#endif

} // namespace detail

// The rows' function for the kernel set in use.
template <int D, class Pair, bool Uniform>
auto pair_rows_for(SimdLevel level)
    -> void (*)(const PairRowsInput<D, Pair>&, std::span<const std::uint32_t>) {
#if PEDESIS_SIMD_DISPATCH
    if (level == SimdLevel::avx512) return &detail::pair_rows_avx512<D, Pair, Uniform>;
    if (level == SimdLevel::avx2) return &detail::pair_rows_avx2<D, Pair, Uniform>;
#endif
    (void)level;
    return &detail::pair_rows_sse2<D, Pair, Uniform>;
}

} // namespace pedesis
