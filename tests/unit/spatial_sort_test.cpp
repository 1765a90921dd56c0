// Space-filling-curve ordering of the soft engine's storage: the order is a permutation,
// the curves keep neighbours in space close in order, and sorting inside the evolver
// does not change the physics.
#include "support/soft_builder.hpp"

#include "pedesis/setup/velocities.hpp"
#include "pedesis/soft/evolver.hpp"
#include "pedesis/soft/langevin.hpp"
#include "pedesis/soft/pair_force.hpp"
#include "pedesis/soft/pair_potentials.hpp"
#include "pedesis/soft/velocity_verlet.hpp"
#include "pedesis/spatial/spatial_sort.hpp"

#include <gtest/gtest.h>
#include <omp.h>

#include <algorithm>
#include <cstdlib>
#include <cstring>
#include <memory>
#include <numeric>
#include <random>

using namespace pedesis;

namespace {

template <int D> Box<D> periodic_box(double L) {
    std::array<bool, D> periodic;
    periodic.fill(true);
    return Box<D>(Vec<D>::filled(L), periodic);
}

bool is_permutation_of_indices(std::vector<std::uint32_t> order, std::size_t n) {
    if (order.size() != n) return false;
    std::sort(order.begin(), order.end());
    for (std::size_t i = 0; i < n; ++i)
        if (order[i] != i) return false;
    return true;
}

// Random positions, including duplicates and points on the box faces (the clamping at
// the grid's ends must not lose or repeat anyone).
template <int D> void check_permutation(std::size_t n, double cell) {
    const double L = 20.0;
    const auto box = periodic_box<D>(L);
    std::mt19937_64 gen(5);
    std::uniform_real_distribution<double> u(-0.5 * L, 0.5 * L);
    std::vector<Vec<D>> pos(n);
    for (auto& r : pos)
        for (int a = 0; a < D; ++a) r[a] = u(gen);
    for (std::size_t i = 0; i < n / 10; ++i) pos[i + n / 2] = pos[i]; // duplicates
    pos[0] = Vec<D>::filled(-0.5 * L);
    pos[1] = Vec<D>::filled(0.5 * L);
    std::vector<std::uint32_t> tag(n);
    std::iota(tag.begin(), tag.end(), 0u);
    std::shuffle(tag.begin(), tag.end(), gen);
    EXPECT_TRUE(is_permutation_of_indices(space_filling_order(box, pos, tag, cell), n))
        << "D = " << D << ", cell = " << cell;
}

TEST(SpaceFillingOrder, IsAPermutation) {
    for (double cell : {0.5, 1.0, 7.0, 100.0, 1e-9}) {
        check_permutation<2>(3000, cell);
        check_permutation<3>(3000, cell);
    }
    EXPECT_TRUE(space_filling_order(periodic_box<2>(5.0), {}, {}, 1.0).empty());
}

// Particles in one cell keep the order of their tags, whatever the storage order, so
// the sorted storage is a function of the configuration alone.
template <int D> void check_ties_by_tag() {
    const std::size_t n = 50;
    std::vector<Vec<D>> pos(n, Vec<D>::filled(0.25));
    std::vector<std::uint32_t> tag(n);
    std::iota(tag.begin(), tag.end(), 0u);
    std::mt19937_64 gen(7);
    std::shuffle(tag.begin(), tag.end(), gen);
    const auto order = space_filling_order(periodic_box<D>(10.0), pos, tag, 1.0);
    for (std::size_t i = 0; i < n; ++i) EXPECT_EQ(tag[order[i]], i);
}

TEST(SpaceFillingOrder, TiesBrokenByTag) {
    check_ties_by_tag<2>();
    check_ties_by_tag<3>();
}

// On a full 2^b x 2^b grid the Hilbert index is a bijection onto [0, 4^b) and cells
// with consecutive indices share a side: the curve never jumps.
TEST(SpaceFillingOrder, HilbertIndexVisitsNeighbouringCells) {
    for (int bits = 1; bits <= 6; ++bits) {
        const std::uint32_t side = 1u << bits;
        const std::size_t cells = std::size_t{side} * side;
        std::vector<std::array<std::int64_t, 2>> cell_of(cells, {-1, -1});
        for (std::uint32_t x = 0; x < side; ++x)
            for (std::uint32_t y = 0; y < side; ++y) {
                const std::uint64_t d = detail::hilbert_index(x, y, bits);
                ASSERT_LT(d, cells) << "bits " << bits;
                ASSERT_EQ(cell_of[d][0], -1) << "index " << d << " used twice, bits " << bits;
                cell_of[d] = {x, y};
            }
        for (std::size_t d = 1; d < cells; ++d) {
            const auto step = std::abs(cell_of[d][0] - cell_of[d - 1][0]) +
                              std::abs(cell_of[d][1] - cell_of[d - 1][1]);
            EXPECT_EQ(step, 1) << "indices " << d - 1 << " -> " << d << ", bits " << bits;
        }
    }
}

// Through the public function: one particle at the centre of every cell of a 32 x 32
// grid (the lower-left corner of the 2^16 curve, which the curve fills first), stored
// in random order. Consecutive particles in the result are one cell apart.
TEST(SpaceFillingOrder, Hilbert2DConsecutiveParticlesAreAdjacent) {
    const int side = 32;
    const double cell = 1.5, L = side * cell;
    std::vector<Vec<2>> pos;
    for (int x = 0; x < side; ++x)
        for (int y = 0; y < side; ++y)
            pos.push_back(Vec<2>{{-0.5 * L + (x + 0.5) * cell, -0.5 * L + (y + 0.5) * cell}});
    std::mt19937_64 gen(11);
    std::shuffle(pos.begin(), pos.end(), gen);
    std::vector<std::uint32_t> tag(pos.size());
    std::iota(tag.begin(), tag.end(), 0u);
    const auto order = space_filling_order(periodic_box<2>(L), pos, tag, cell);
    ASSERT_TRUE(is_permutation_of_indices(order, pos.size()));
    for (std::size_t k = 1; k < order.size(); ++k)
        EXPECT_NEAR(norm(pos[order[k]] - pos[order[k - 1]]), cell, 1e-9) << "k = " << k;
}

// Morton order in 3D: aligned runs of 8^j consecutive particles fill aligned cubes of
// side 2^j cells (8 x 8 x 8 grid, j = 1 and 2).
TEST(SpaceFillingOrder, Morton3DRunsFillCubes) {
    const int side = 8;
    const double cell = 1.0, L = side * cell;
    std::vector<Vec<3>> pos;
    for (int x = 0; x < side; ++x)
        for (int y = 0; y < side; ++y)
            for (int z = 0; z < side; ++z)
                pos.push_back(Vec<3>{{-0.5 * L + x + 0.5, -0.5 * L + y + 0.5, -0.5 * L + z + 0.5}});
    std::mt19937_64 gen(13);
    std::shuffle(pos.begin(), pos.end(), gen);
    std::vector<std::uint32_t> tag(pos.size());
    std::iota(tag.begin(), tag.end(), 0u);
    const auto order = space_filling_order(periodic_box<3>(L), pos, tag, cell);
    ASSERT_TRUE(is_permutation_of_indices(order, pos.size()));
    for (int j : {1, 2}) {
        const std::size_t run = std::size_t{1} << (3 * j);
        const int cube = 1 << j;
        for (std::size_t start = 0; start < order.size(); start += run) {
            std::array<int, 3> lo{side, side, side}, hi{-1, -1, -1};
            for (std::size_t k = start; k < start + run; ++k)
                for (int a = 0; a < 3; ++a) {
                    const int c = static_cast<int>(std::floor(pos[order[k]][a] + 0.5 * L));
                    lo[a] = std::min(lo[a], c);
                    hi[a] = std::max(hi[a], c);
                }
            for (int a = 0; a < 3; ++a) {
                EXPECT_EQ(hi[a] - lo[a] + 1, cube) << "run at " << start << ", j = " << j;
                EXPECT_EQ(lo[a] % cube, 0) << "run at " << start << ", j = " << j;
            }
        }
    }
}

// Dense harmonic particles with Maxwell-Boltzmann velocities (T = 1). narrow: the last axis 3 long,
// two cells of the list (r_list 1.3), where the list builds from the full stencil and a pair's row
// is that of its lower storage index
template <int D>
SoftState<D> dense_system_with_velocities(std::uint64_t seed, bool narrow = false) {
    const double L = D == 2 ? 25.0 : 8.0, last = narrow ? 3.0 : L;
    const auto n = static_cast<std::size_t>((D == 2 ? 800.0 : 600.0) * last / L);
    auto s = test::random_soft_system<D>(n, L, 0.5, seed);
    Vec<D> sides = Vec<D>::filled(L);
    sides[D - 1] = last;
    std::array<bool, D> periodic;
    periodic.fill(true);
    s.box = Box<D>(sides, periodic);
    for (auto& r : s.p.position) r[D - 1] *= last / L;
    VelocitySpec spec;
    for (std::size_t i = 0; i < n; ++i)
        s.p.velocity[i] = draw_velocity<D>(spec, 1.0, seed + 2, s.p.tag[i]);
    return s;
}

// Harmonic particles (skin 0.3) moved by `integrator` (velocity Verlet if none).
template <int D>
std::unique_ptr<Evolver<D>> harmonic_evolver(SoftState<D>& s,
                                             std::unique_ptr<Integrator<D>> integrator = nullptr) {
    auto e = std::make_unique<Evolver<D>>(s, 0.3);
    e->add_force(std::make_unique<PairForce<D, HarmonicPair>>("harmonic", HarmonicPair{}));
    e->add_integrator(integrator ? std::move(integrator)
                                 : std::make_unique<VelocityVerletIntegrator<D>>());
    return e;
}

// Sorting every 10 steps inside the evolver is invisible. Compared in tag order with
// an unsorted run after 200 steps of dense harmonic particles: sorting changes only the
// order in which each particle sums its neighbours' forces (rounding, 1e-16), which the
// chaos of a dense system amplifies by e^{lambda t} with t = 1 and lambda of order 1 to
// ~1e-15, far below the tolerance 1e-9. Both dynamics are checked: velocity Verlet
// (noiseless) and Langevin, whose noise is keyed by tag and so must follow the particles
// through every reordering.
template <int D, class Make> void check_sorting_invisible(Make make_integrator) {
    auto plain = dense_system_with_velocities<D>(17);
    const std::size_t n = plain.size();
    auto sorted = plain;
    auto run = [&](SoftState<D>& s, std::uint64_t interval) {
        auto e = harmonic_evolver<D>(s, make_integrator());
        e->set_sort_interval(interval);
        e->run(200, 0.005);
    };
    run(plain, 0);
    run(sorted, 10);
    std::size_t displaced = 0;
    for (std::size_t i = 0; i < n; ++i) displaced += sorted.p.tag[i] != i;
    EXPECT_GT(displaced, n / 2) << "the storage was not reordered: the test would be empty";
    const auto a = plain.p.index_of_tags(), b = sorted.p.index_of_tags();
    double dr = 0.0, dv = 0.0;
    for (std::size_t t = 0; t < n; ++t) {
        dr = std::max(dr, norm(plain.unwrapped(a[t]) - sorted.unwrapped(b[t])));
        dv = std::max(dv, norm(plain.p.velocity[a[t]] - sorted.p.velocity[b[t]]));
    }
    std::printf("sorted vs unsorted %dD: max |dr| %.3e, |dv| %.3e\n", D, dr, dv);
    EXPECT_LT(dr, 1e-9);
    EXPECT_LT(dv, 1e-9);
}

TEST(EvolverSorting, InvisibleToVelocityVerlet2D) {
    check_sorting_invisible<2>([] { return std::make_unique<VelocityVerletIntegrator<2>>(); });
}
TEST(EvolverSorting, InvisibleToVelocityVerlet3D) {
    check_sorting_invisible<3>([] { return std::make_unique<VelocityVerletIntegrator<3>>(); });
}
TEST(EvolverSorting, InvisibleToLangevin2D) {
    check_sorting_invisible<2>([] { return std::make_unique<LangevinIntegrator<2>>(1.0, 1.0, 3); });
}
TEST(EvolverSorting, InvisibleToLangevin3D) {
    check_sorting_invisible<3>([] { return std::make_unique<LangevinIntegrator<3>>(1.0, 1.0, 3); });
}

template <int D> bool same_bits(const Vec<D>& a, const Vec<D>& b) {
    return std::memcmp(a.c.data(), b.c.data(), sizeof(double) * D) == 0;
}

// After a sort the storage follows the force loops' sweep (the rows are visited in
// storage order), and the order depends on the positions and tags alone: the same
// configuration handed over shuffled is stored the same way.
template <int D> void check_storage_follows_the_sweep() {
    auto s = dense_system_with_velocities<D>(29);
    auto shuffled = s;
    std::vector<std::uint32_t> perm(s.size());
    std::iota(perm.begin(), perm.end(), 0u);
    std::shuffle(perm.begin(), perm.end(), std::mt19937(5));
    shuffled.apply_order(perm);
    auto e = harmonic_evolver(s);
    auto f = harmonic_evolver(shuffled);
    e->sort_storage();
    f->sort_storage();
    const auto& sweep = e->neighbor_list().sweep_order();
    ASSERT_EQ(sweep.size(), s.size());
    std::size_t out_of_place = 0;
    for (std::size_t i = 0; i < sweep.size(); ++i) out_of_place += sweep[i] != i;
    EXPECT_EQ(out_of_place, 0u) << "the rows are not visited in storage order";
    EXPECT_GT(e->neighbor_list().colours(), 1) << "one colour: the test would be empty";
    EXPECT_TRUE(s.p.tag == shuffled.p.tag) << "the stored order depends on the input's order";
    // the per-particle loops then share the storage out along the force loop's runs
    EXPECT_EQ(s.thread_shares, e->neighbor_list().thread_share_bounds());
    EXPECT_EQ(s.thread_shares.size(),
              static_cast<std::size_t>(e->neighbor_list().colours() * omp_get_max_threads() + 1));
}

TEST(EvolverSorting, StorageFollowsTheSweep2D) {
    check_storage_follows_the_sweep<2>();
}
TEST(EvolverSorting, StorageFollowsTheSweep3D) {
    check_storage_follows_the_sweep<3>();
}

// A checkpoint holds the storage and the positions of the last list build, and a restart
// builds its list from them. Right after a sort, before any rebuild, the restored run
// must sum every force in the order the sorting run does, and go on bit for bit.
template <int D> void check_restart_right_after_a_sort(bool narrow) {
    auto s = dense_system_with_velocities<D>(31, narrow);
    auto e = harmonic_evolver(s);
    e->run(5, 0.005);
    e->sort_storage();
    auto copy = s;
    auto r = harmonic_evolver(copy);
    r->restore_list(e->list_reference(), e->list_builds());
    e->compute_forces();
    r->compute_forces();
    std::size_t differ = 0;
    for (std::size_t i = 0; i < s.size(); ++i) differ += !same_bits(s.force[i], copy.force[i]);
    EXPECT_EQ(differ, 0u) << "forces differ in the last bits after the restart's list build";
    e->run(20, 0.005);
    r->run(20, 0.005);
    differ = 0;
    for (std::size_t i = 0; i < s.size(); ++i)
        differ += !same_bits(s.p.position[i], copy.p.position[i]);
    EXPECT_EQ(differ, 0u);
}

TEST(EvolverSorting, RestartRightAfterASortIsExact2D) {
    check_restart_right_after_a_sort<2>(false);
    check_restart_right_after_a_sort<2>(true);
}
TEST(EvolverSorting, RestartRightAfterASortIsExact3D) {
    check_restart_right_after_a_sort<3>(false);
    check_restart_right_after_a_sort<3>(true);
}

} // namespace
