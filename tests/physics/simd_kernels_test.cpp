// The pair loop's kernel sets (core/simd_level.hpp): every set this CPU runs gives the
// forces of the scalar path (sse2, the reference) to 1e-12 of the sum of the pair
// forces' magnitudes on each particle, in 2D and 3D, for each pair evaluator, with one
// radius (the SIMD kernel) and with two (the per-pair path), on random systems and on
// a perfect lattice; each set is bit-identical on one thread and on two, and adds to
// the forces earlier terms left. The integrators' noise is the same numbers under every
// set.
#include "support/pair_cases.hpp"

#include "pedesis/core/inside_box.hpp"
#include "pedesis/core/noise_log.hpp"
#include "pedesis/core/philox_batch.hpp"
#include "pedesis/core/simd_level.hpp"
#include "pedesis/soft/batch_normals.hpp"
#include "pedesis/soft/evolver.hpp"
#include "pedesis/soft/pair_force.hpp"
#include "pedesis/soft/pair_potentials.hpp"
#include "pedesis/spatial/block_moves.hpp"
#include "pedesis/spatial/neighbor_list.hpp"

#include <gtest/gtest.h>
#include <omp.h>

#include <cmath>
#include <limits>
#include <memory>
#include <string>
#include <tuple>
#include <vector>

using namespace pedesis;

namespace {

// Restores the kernel set in use when a test ends.
struct KernelSetGuard {
    SimdLevel saved = simd_level();
    ~KernelSetGuard() { set_simd_level(saved); }
};

template <int D, class Pair>
std::vector<Vec<D>> forces_with(SimdLevel level, SoftState<D> s, const Pair& pair, double skin,
                                int threads) {
    set_simd_level(level);
    omp_set_num_threads(threads);
    Evolver<D> e(s, skin);
    e.add_force(std::make_unique<PairForce<D, Pair>>("pair", pair));
    std::fill(s.force.begin(), s.force.end(), Vec<D>{});
    e.forces()[0]->add_forces(s, e.neighbor_list());
    omp_set_num_threads(1);
    return s.force;
}

// per particle, the sum of |F_ij| over its interacting pairs (brute force)
template <int D, class Pair>
std::vector<double> force_scale(const SoftState<D>& s, const Pair& pair) {
    std::vector<double> scale(s.size(), 0.0);
    for (std::size_t i = 0; i < s.size(); ++i)
        for (std::size_t j = 0; j < s.size(); ++j) {
            if (j == i) continue;
            const Vec<D> d = s.box.minimum_image(s.p.position[i] - s.p.position[j]);
            double f_over_r, energy;
            if (pair.eval(norm2(d), s.p.radius(i) + s.p.radius(j), f_over_r, energy))
                scale[i] += std::abs(f_over_r) * norm(d);
        }
    return scale;
}

template <int D, class Pair>
void check_every_set(const SoftState<D>& s, const Pair& pair, double skin,
                     const std::string& what) {
    SCOPED_TRACE(what);
    const std::vector<Vec<D>> reference = forces_with(SimdLevel::sse2, s, pair, skin, 1);
    const std::vector<double> scale = force_scale(s, pair);
    std::size_t interacting = 0;
    for (double x : scale) interacting += x > 0.0;
    ASSERT_GT(interacting, s.size() / 2) << "too few particles interact to test anything";
    for (const SimdLevel level : available_simd_levels()) {
        SCOPED_TRACE(simd_name(level));
        const std::vector<Vec<D>> one = forces_with(level, s, pair, skin, 1);
        const std::vector<Vec<D>> two = forces_with(level, s, pair, skin, 2);
        std::size_t bad = 0, unequal = 0;
        for (std::size_t i = 0; i < s.size(); ++i) {
            bad += !(norm(one[i] - reference[i]) <= 1e-12 * scale[i]);
            for (int a = 0; a < D; ++a) unequal += one[i][a] != two[i][a];
        }
        EXPECT_EQ(bad, 0u) << "particles whose force differs from the scalar path";
        EXPECT_EQ(unequal, 0u) << "force components that differ between one and two threads";
    }
}

} // namespace

TEST(SimdKernels, TheSseSetIsAlwaysThere) {
    const std::vector<SimdLevel> levels = available_simd_levels();
    ASSERT_FALSE(levels.empty());
    EXPECT_EQ(levels.front(), SimdLevel::sse2);
    EXPECT_EQ(parse_simd_level("avx2"), SimdLevel::avx2);
    EXPECT_FALSE(parse_simd_level("AVX2").has_value());
}

TEST(SimdKernels, EverySetGivesTheScalarForces2D) {
    KernelSetGuard guard;
    test::for_each_pair_case<2>(
        [](const auto& s, const auto& pair, double skin, const std::string& what) {
            check_every_set(s, pair, skin, what);
        });
}

TEST(SimdKernels, EverySetGivesTheScalarForces3D) {
    KernelSetGuard guard;
    test::for_each_pair_case<3>(
        [](const auto& s, const auto& pair, double skin, const std::string& what) {
            check_every_set(s, pair, skin, what);
        });
}

// A pair force adds to what the terms before it left in the forces: the 3D SIMD sets work
// on padded copies (soft/pair_rows.hpp), which must start from the state's forces and
// go back to them. Each particle starts with a force of order one, unlike any pair's.
TEST(SimdKernels, EverySetAddsToTheForcesAlreadyThere) {
    KernelSetGuard guard;
    SoftState<3> s = test::pair_case_system<3>(1000, 0.8, false, 7);
    const LjPair pair{1.0, -1.0, 2.5};
    std::vector<Vec<3>> before(s.size());
    for (std::size_t i = 0; i < s.size(); ++i)
        before[i] = Vec<3>{{1.0 + 0.001 * double(i), -2.0, 0.5 * double(i % 7)}};
    const std::vector<double> scale = force_scale(s, pair);
    for (const SimdLevel level : available_simd_levels()) {
        SCOPED_TRACE(simd_name(level));
        const std::vector<Vec<3>> alone = forces_with(level, s, pair, 0.3, 1);
        set_simd_level(level);
        Evolver<3> e(s, 0.3);
        e.add_force(std::make_unique<PairForce<3, LjPair>>("pair", pair));
        s.force = before;
        e.forces()[0]->add_forces(s, e.neighbor_list());
        std::size_t bad = 0;
        for (std::size_t i = 0; i < s.size(); ++i)
            bad += !(norm(s.force[i] - (before[i] + alone[i])) <= 1e-12 * (scale[i] + 4.0));
        EXPECT_EQ(bad, 0u) << "particles whose force is not the earlier force plus the pairs'";
    }
}

// in.lj's fcc lattice (6^3 cells) and a square lattice of spacing 1 in a box of 20, each
// nudged off its symmetric sites so that forces do not cancel: every row of a lattice has
// the most candidates, and rows end at every lane of the kernel
TEST(SimdKernels, EverySetGivesTheScalarForcesOnLattices) {
    KernelSetGuard guard;
    SoftState<3> fcc = test::fcc_soft_state(6, 0.8442);
    for (std::size_t i = 0; i < fcc.size(); ++i) fcc.p.position[i][0] += 1e-3 * std::sin(1.0 * i);
    check_every_set(fcc, LjPair{1.0, 1.0, 2.5}, 0.3, "lj on fcc");
    SoftState<2> square = test::random_soft_system<2>(400, 20.0, 0.5, 1);
    for (std::size_t i = 0; i < square.size(); ++i)
        square.p.position[i] =
            Vec<2>{{-10.0 + static_cast<double>(i % 20) + 0.01 * std::cos(1.0 * i),
                    -10.0 + static_cast<double>(i / 20)}};
    check_every_set(square, WcaPair{1.0, 1.05}, 0.4, "wca on a square lattice");
}

// The list build's inner loop is per set too, and must list the same pairs in the same
// order in every set (r^2 by the same operations, no fused multiply-add).
template <int D>
std::vector<std::vector<std::uint32_t>> rows_with(SimdLevel level, const SoftState<D>& s,
                                                  double r_cut, double skin) {
    set_simd_level(level);
    NeighborList<D> nl(s.box, r_cut, skin);
    nl.build(s.p.position);
    std::vector<std::vector<std::uint32_t>> rows(s.size());
    for (std::size_t i = 0; i < s.size(); ++i) rows[i].assign(nl.begin(i), nl.end(i));
    return rows;
}

template <int D>
void check_lists(const SoftState<D>& s, double r_cut, double skin, const std::string& what) {
    SCOPED_TRACE(what);
    const auto reference = rows_with(SimdLevel::sse2, s, r_cut, skin);
    std::size_t entries = 0;
    for (const auto& r : reference) entries += r.size();
    ASSERT_GT(entries, s.size()) << "too few pairs to test anything";
    for (const SimdLevel level : available_simd_levels()) {
        SCOPED_TRACE(simd_name(level));
        EXPECT_TRUE(rows_with(level, s, r_cut, skin) == reference)
            << "rows differ from the scalar build";
    }
}

TEST(SimdKernels, EverySetListsTheSamePairsInTheSameOrder) {
    KernelSetGuard guard;
    // a square lattice of spacing 1 in a box of 12 with list range 1.5 + 0.5 = 2: pairs
    // at exactly 2 lie at the range, on cell faces (cells of width 2)
    SoftState<2> square = test::random_soft_system<2>(144, 12.0, 0.5, 1);
    for (std::size_t i = 0; i < square.size(); ++i)
        square.p.position[i] =
            Vec<2>{{-6.0 + static_cast<double>(i % 12), -6.0 + static_cast<double>(i / 12)}};
    check_lists(square, 1.5, 0.5, "square lattice, pairs at the range");
    check_lists(test::fcc_soft_state(6, 0.8442), 2.5, 0.3, "fcc, in.lj");
    check_lists(test::pair_case_system<3>(1000, 0.8, false, 7), 2.5, 0.3, "random 3D");
    check_lists(test::pair_case_system<2>(900, 0.7, true, 8), 1.2, 0.4, "random 2D");
}

TEST(SimdKernels, ASetTheCpuLacksIsRefused) {
    KernelSetGuard guard;
    const std::vector<SimdLevel> levels = available_simd_levels();
    if (levels.back() == SimdLevel::avx512) {
        // every set is here: nothing to refuse, but each one must be accepted
        for (SimdLevel l : levels) EXPECT_NO_THROW(set_simd_level(l));
    } else {
        EXPECT_THROW(set_simd_level(SimdLevel::avx512), std::invalid_argument);
    }
}

namespace {

// The tags of a batch: small, large and neighbouring values, the top bit set.
std::vector<std::uint32_t> batch_tags() {
    std::vector<std::uint32_t> tags;
    for (int k = 0; k < detail::noise_batch; ++k)
        tags.push_back(k % 3 == 0 ? 0xffffffffu - static_cast<std::uint32_t>(k)
                                  : static_cast<std::uint32_t>(k * 2654435761u));
    tags[1] = 0;
    return tags;
}

// Per normals of each of m particles, from CounterRng's uniforms one by one, through the
// same Box-Muller steps as the batches.
std::vector<double> reference_normals(int per, std::uint64_t seed, RngStream stream,
                                      const std::uint32_t* tag, std::uint32_t step, int m) {
    std::vector<double> z(static_cast<std::size_t>(m * per));
    for (int k = 0; k < m; ++k) {
        CounterRng rng(seed, stream, tag[k], step);
        for (int c = 0; c < per; c += 2) {
            const double u1 = rng.uniform(), u2 = rng.uniform();
            const double r = std::sqrt(-2.0 * noise_log(u1));
            double sn, cs;
            detail::sincos_turns(u2, sn, cs);
            z[static_cast<std::size_t>(k * per + c)] = r * cs;
            if (c + 1 < per) z[static_cast<std::size_t>(k * per + c + 1)] = r * sn;
        }
    }
    return z;
}

template <int Per> void check_normals(SimdLevel level, int m) {
    const std::vector<std::uint32_t> tags = batch_tags();
    const std::uint64_t seed = 0x9e3779b97f4a7c15ull;
    const std::uint32_t step = 0xfffffff0u;
    std::vector<double> z(detail::noise_batch * Per, -1.0);
    detail::batch_normals<Per>(seed, RngStream::orientation, tags.data(), step, m, z.data());
    const std::vector<double> want =
        reference_normals(Per, seed, RngStream::orientation, tags.data(), step, m);
    for (int q = 0; q < m * Per; ++q)
        ASSERT_EQ(z[static_cast<std::size_t>(q)], want[static_cast<std::size_t>(q)])
            << simd_name(level) << ": " << Per << " normals per particle, batch of " << m
            << ", number " << q;
}

// The uniform noise (batch_normals.hpp) from the same draws: sqrt 3 ((2u - 1) - 2^-53).
template <int Per> void check_uniform_noise(SimdLevel level, int m) {
    const std::vector<std::uint32_t> tags = batch_tags();
    const std::uint64_t seed = 0x243f6a8885a308d3ull;
    const std::uint32_t step = 11;
    std::vector<double> z(detail::noise_batch * Per, -1.0);
    detail::batch_noise<Per>(detail::NoiseShape::uniform, seed, RngStream::thermostat, tags.data(),
                             step, m, z.data());
    for (int k = 0; k < m; ++k) {
        CounterRng rng(seed, RngStream::thermostat, tags[static_cast<std::size_t>(k)], step);
        for (int c = 0; c < Per; ++c) {
            const double want = 1.7320508075688772 * ((2.0 * rng.uniform() - 1.0) - 0x1p-53);
            ASSERT_EQ(z[static_cast<std::size_t>(k * Per + c)], want)
                << simd_name(level) << ": " << Per << " per particle, batch of " << m
                << ", particle " << k << ", component " << c;
        }
    }
}

} // namespace

// The rebuild check's moves (spatial/block_moves.hpp) by Box::minimum_image and norm2,
// one particle at a time: what every set must give.
template <int D>
detail::BlockMoves reference_moves(const Box<D>& box, const std::vector<Vec<D>>& pos,
                                   const std::vector<Vec<D>>& home, std::size_t first,
                                   std::size_t last, double skin) {
    detail::BlockMoves m;
    for (std::size_t k = first; k < last; ++k) {
        const double d2 = norm2(box.minimum_image(pos[k] - home[k]));
        m.far = m.far || !(d2 <= skin * skin);
        if (d2 > m.most2) m.most2 = d2;
        m.movers += d2 > 0.25 * skin * skin ? 1 : 0;
    }
    return m;
}

// Moves across periodic faces both ways, moves of exactly skin/2 and skin along an axis,
// moves beside walls, and blocks of every length from 0 to 13 at every offset.
template <int D> void check_block_moves(const std::array<bool, D>& periodic, bool with_nan) {
    const Box<D> box(Vec<D>::filled(8.0), periodic);
    const double skin = 0.5;
    std::vector<Vec<D>> home, pos;
    for (int k = 0; k < 40; ++k) {
        Vec<D> h, p;
        for (int a = 0; a < D; ++a) {
            h[a] = -3.9 + 0.19 * ((k * (a + 3)) % 41);
            p[a] = h[a];
        }
        switch (k % 5) {
        case 0: // across the face: home just below +L/2, now just above -L/2
            h[0] = 3.99;
            p[0] = -3.99;
            break;
        case 1: // the other way, on the last axis
            h[D - 1] = -3.95;
            p[D - 1] = 3.97;
            break;
        case 2: // exactly skin/2, then exactly the skin, along axis 0
            p[0] = h[0] + (k % 10 == 2 ? 0.5 * skin : skin);
            break;
        case 3: // a small move on every axis
            for (int a = 0; a < D; ++a) p[a] += 0.1 * (a + 1) * (k % 2 ? 1 : -1);
            break;
        default: // beyond the skin
            p[1] -= 0.6;
        }
        home.push_back(h);
        pos.push_back(p);
    }
    if (with_nan) pos[17][0] = std::numeric_limits<double>::quiet_NaN();
    detail::BlockMovesInput<D> in{pos.data(), home.data(), {}, {}, skin * skin, 0.25 * skin * skin};
    for (int a = 0; a < D; ++a) {
        in.half[a] = periodic[a] ? box.hi(a) : std::numeric_limits<double>::infinity();
        in.length[a] = periodic[a] ? box.length(a) : 0.0;
    }
    for (SimdLevel level : available_simd_levels()) {
        const auto moves = detail::block_moves_for<D>(level);
        for (std::size_t first = 0; first < 8; ++first)
            for (std::size_t last = first; last <= first + 13 && last <= pos.size(); ++last) {
                const auto got = moves(in, first, last);
                const auto want = reference_moves(box, pos, home, first, last, skin);
                const std::string where = std::string(simd_name(level)) + " " + std::to_string(D) +
                                          "D particles " + std::to_string(first) + ".." +
                                          std::to_string(last);
                EXPECT_EQ(got.far, want.far) << where;
                EXPECT_EQ(got.movers, want.movers) << where;
                // (a NaN move is left out of the maximum by all)
                EXPECT_EQ(got.most2, want.most2) << where;
            }
    }
}

TEST(SimdKernels, EverySetFindsTheSameMovesSinceTheBuild) {
    check_block_moves<2>({true, true}, false);
    check_block_moves<2>({false, true}, false);
    check_block_moves<3>({true, true, true}, false);
    check_block_moves<3>({true, false, true}, false);
    check_block_moves<3>({true, true, true}, true);
    check_block_moves<2>({true, true}, true);
}

// The wrap's test (Evolver::wrap_all): particles inside, on the lower bound (inside) and
// on the upper one (outside), beyond either, NaN, and an axis between walls (never
// outside); one odd particle at each place of blocks of every length from 0 to 13, so
// that the vector lanes and the scalar tail are each the one that must see it.
template <int D> void check_all_inside(const std::array<bool, D>& periodic) {
    detail::BoxBounds<D> b;
    for (int a = 0; a < D; ++a) {
        b.lo[a] = periodic[a] ? -4.0 : -std::numeric_limits<double>::infinity();
        b.hi[a] = periodic[a] ? 4.0 : std::numeric_limits<double>::infinity();
    }
    std::vector<Vec<D>> inside;
    for (int k = 0; k < 24; ++k) {
        Vec<D> r;
        for (int a = 0; a < D; ++a) r[a] = -3.9 + 0.33 * ((k * (a + 5)) % 24);
        if (k % 7 == 3) r[D - 1] = -4.0; // exactly on the lower bound: inside
        inside.push_back(r);
    }
    const double nan = std::numeric_limits<double>::quiet_NaN();
    // (axis, value, outside when that axis is periodic)
    const std::vector<std::tuple<int, double, bool>> odd = {
        {0, 4.0, true},        {D - 1, 4.0, true}, {1, -4.0000001, true}, {0, 1e300, true},
        {D - 1, -1e300, true}, {1, nan, true},     {0, 3.9999999, false}};
    for (SimdLevel level : available_simd_levels()) {
        const auto all_inside = detail::all_inside_for<D>(level);
        for (std::size_t first = 0; first < 4; ++first)
            for (std::size_t last = first; last <= first + 13; ++last) {
                const std::string where = std::string(simd_name(level)) + " " + std::to_string(D) +
                                          "D particles " + std::to_string(first) + ".." +
                                          std::to_string(last);
                EXPECT_TRUE(all_inside(b, inside.data(), first, last)) << where;
                for (const auto& [axis, value, out] : odd)
                    for (std::size_t at = first; at < last; ++at) {
                        std::vector<Vec<D>> pos = inside;
                        pos[at][axis] = value;
                        // NaN is outside on any axis: not inside [lo, hi), walls or not
                        const bool want = !(std::isnan(value) || (out && periodic[axis]));
                        EXPECT_EQ(all_inside(b, pos.data(), first, last), want)
                            << where << ", particle " << at << " at " << value << " on axis "
                            << axis;
                    }
            }
    }
}

TEST(SimdKernels, EverySetFindsTheParticlesOutsideTheBox) {
    check_all_inside<2>({true, true});
    check_all_inside<2>({true, false});
    check_all_inside<3>({true, true, true});
    check_all_inside<3>({false, true, true});
}

TEST(SimdKernels, EverySetDrawsTheSameUniformNoise) {
    KernelSetGuard guard;
    for (SimdLevel level : available_simd_levels()) {
        set_simd_level(level);
        for (int m = 0; m <= detail::noise_batch; ++m) {
            check_uniform_noise<1>(level, m);
            check_uniform_noise<2>(level, m);
            check_uniform_noise<3>(level, m);
        }
    }
}

TEST(SimdKernels, EverySetDrawsTheNumbersOfCounterRng) {
    KernelSetGuard guard;
    const std::vector<std::uint32_t> tags = batch_tags();
    // the SSE2 lanes alone, block by block, against CounterRng
    for (std::uint32_t block = 0; block < 3; ++block) {
        double u1[detail::noise_batch], u2[detail::noise_batch];
        detail::philox_uniforms<detail::DefaultLanes>(12345, RngStream::thermostat, tags.data(), 7,
                                                      block, detail::noise_batch, u1, u2);
        for (int k = 0; k < detail::noise_batch; ++k) {
            CounterRng rng(12345, RngStream::thermostat, tags[static_cast<std::size_t>(k)], 7);
            for (std::uint32_t b = 0; b < block; ++b) rng.uniform(), rng.uniform();
            ASSERT_EQ(u1[k], rng.uniform()) << "block " << block << ", particle " << k;
            ASSERT_EQ(u2[k], rng.uniform()) << "block " << block << ", particle " << k;
        }
    }
    // every set's normals, for every batch size (whole vectors, and the rest one by one)
    for (SimdLevel level : available_simd_levels()) {
        set_simd_level(level);
        for (int m = 0; m <= detail::noise_batch; ++m) {
            check_normals<1>(level, m);
            check_normals<2>(level, m);
            check_normals<3>(level, m);
        }
    }
}
