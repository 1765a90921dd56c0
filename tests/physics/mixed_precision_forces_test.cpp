// The pair rows in mixed precision (soft/pair_rows_mixed.hpp) against a brute-force sum
// in double over every pair by minimum image: in 2D and 3D, for each evaluator, on random
// systems, lattices (points on cell faces), a sheared box and walls, under each kernel
// set that has mixed rows. The bound: float positions round each coordinate by up to half
// an ulp of L/2 (2.4e-7 where L/2 < 8, 9.5e-7 where L/2 < 32: the 2D boxes here are 36
// wide), twice per distance and on three axes, and a force going as r^-13 multiplies the
// relative error of a distance by 13: up to 7e-5 of a particle's force scale (the sum of
// its pairs' |F|, plus 1 eps/sigma so that particles whose pairs all lie near the cutoff,
// where F ~ 0 and a float sum cancels, are not judged relative to nothing). Bound 1.5e-4;
// a missing, doubled or misplaced pair shows at order 1. The rows are bit-identical on 1,
// 2 and 3 threads; rows that have no mixed version (two radii, the sse2 set) give exactly
// the double forces, and say so.
#include "support/pair_cases.hpp"

#include "pedesis/core/simd_level.hpp"
#include "pedesis/soft/evolver.hpp"
#include "pedesis/soft/pair_force.hpp"
#include "pedesis/soft/pair_potentials.hpp"

#include <gtest/gtest.h>
#include <omp.h>

#include <cmath>
#include <memory>
#include <string>
#include <vector>

using namespace pedesis;

namespace {

struct KernelSetGuard {
    SimdLevel saved = simd_level();
    ~KernelSetGuard() { set_simd_level(saved); }
};

template <int D, class Pair> struct Forces {
    std::vector<Vec<D>> force;
    Precision ran = Precision::full;
};

template <int D, class Pair>
Forces<D, Pair> forces_with(Precision precision, SoftState<D> s, const Pair& pair, double skin,
                            int threads) {
    omp_set_num_threads(threads);
    s.pair_precision = precision;
    Evolver<D> e(s, skin);
    e.add_force(std::make_unique<PairForce<D, Pair>>("pair", pair));
    std::fill(s.force.begin(), s.force.end(), Vec<D>{});
    e.forces()[0]->add_forces(s, e.neighbor_list());
    omp_set_num_threads(1);
    return {s.force, *e.forces()[0]->rows_precision(s)};
}

// The largest |F_mixed - F_brute| over the particle's force scale; counts the pairs.
template <int D, class Pair>
double worst_relative_error(const SoftState<D>& s, const Pair& pair,
                            const std::vector<Vec<D>>& force, std::size_t& interacting) {
    double worst = 0.0;
    for (std::size_t i = 0; i < s.size(); ++i) {
        double scale;
        const Vec<D> f = test::brute_force_on(s, pair, i, scale, interacting);
        if (scale > 0.0) worst = std::max(worst, norm(force[i] - f) / (scale + 1.0));
    }
    return worst;
}

template <int D, class Pair>
void check_mixed(const SoftState<D>& s, const Pair& pair, double skin, const std::string& what) {
    const KernelSetGuard guard;
    bool uniform = true;
    for (const auto& sp : s.p.species_table)
        uniform = uniform && sp.radius == s.p.species_table[0].radius;
    for (const SimdLevel level : available_simd_levels()) {
        SCOPED_TRACE(what + " under " + simd_name(level));
        set_simd_level(level);
        const auto one = forces_with(Precision::mixed, s, pair, skin, 1);
        const bool has_mixed_rows = uniform && level != SimdLevel::sse2;
        EXPECT_EQ(one.ran, has_mixed_rows ? Precision::mixed : Precision::full);
        if (!has_mixed_rows) { // the double rows, exactly
            const auto full = forces_with(Precision::full, s, pair, skin, 1);
            EXPECT_TRUE(one.force == full.force) << "rows without a mixed version changed";
            continue;
        }
        std::size_t interacting = 0;
        const double worst = worst_relative_error(s, pair, one.force, interacting);
        EXPECT_GT(interacting, s.size()) << "too few pairs in range to test anything";
        EXPECT_LT(worst, 1.5e-4);
        EXPECT_GT(worst, 0.0) << "no rounding at all: were the rows in float?";
        for (int threads : {2, 3})
            EXPECT_TRUE(forces_with(Precision::mixed, s, pair, skin, threads).force == one.force)
                << "not bit-identical on " << threads << " threads";
    }
}

template <int D> void check_every_case() {
    test::for_each_pair_case<D>(
        [](const auto& s, const auto& pair, double skin, const std::string& what) {
            check_mixed<D>(s, pair, skin, what);
        });
}

} // namespace

TEST(MixedPrecisionForces, TwoDimensions) {
    check_every_case<2>();
}

TEST(MixedPrecisionForces, ThreeDimensions) {
    check_every_case<3>();
}

// in.lj's fcc lattice (6^3 cells, the box an exact multiple of the cell: points on cell
// faces) and a square lattice, each nudged off its symmetric sites so that forces do not
// cancel: every row has the most candidates, and rows end at every lane of the kernel.
TEST(MixedPrecisionForces, Lattices) {
    SoftState<3> fcc = test::fcc_soft_state(6, 0.8442);
    for (std::size_t i = 0; i < fcc.size(); ++i) fcc.p.position[i][0] += 1e-3 * std::sin(1.0 * i);
    check_mixed<3>(fcc, LjPair{1.0, 1.0, 2.5}, 0.3, "lj on fcc");
    SoftState<2> square = test::random_soft_system<2>(400, 20.0, 0.5, 1);
    for (std::size_t i = 0; i < square.size(); ++i)
        square.p.position[i] =
            Vec<2>{{-10.0 + static_cast<double>(i % 20) + 0.01 * std::cos(1.0 * i),
                    -10.0 + static_cast<double>(i / 20)}};
    check_mixed<2>(square, WcaPair{1.0, 1.05}, 0.4, "wca on a square lattice");
}

// Lees-Edwards: the y crossing moves x by the offset in the float rows too.
TEST(MixedPrecisionForces, ShearedBox) {
    auto s = test::pair_case_system<3>(1000, 0.8, false, 9);
    s.box.set_shear_rate(0.1);
    s.box.set_shear_offset(0.37 * s.box.length(0));
    check_mixed<3>(s, LjPair{1.0, -1.0, 2.5}, 0.3, "sheared lj");
}

// Walls along y: no minimum image across them (an infinite half-length in the rows).
TEST(MixedPrecisionForces, WallsAlongOneAxis) {
    auto s = test::pair_case_system<3>(1000, 0.8, false, 10);
    s.box = Box<3>(s.box.lengths(), {true, false, true});
    check_mixed<3>(s, WcaPair{1.0, -1.0}, 0.3, "wca between walls");
}
