// Conservation laws over long elastic runs and the hard-core constraint in dense runs.
// These hold to rounding, so the tolerances are rounding bounds, not statistics:
// each collision changes the energy and momentum by a few ulp of the pair's values and
// those errors add up like a random walk (1e6 collisions x 1e-16 x sqrt(1e6) ~ 1e-13).
#include "pedesis/core/error.hpp"
#include "pedesis/event/event_engine.hpp"
#include "pedesis/setup/random_placement.hpp"
#include "pedesis/setup/velocities.hpp"
#include "support/gas_builder.hpp"

#include <gtest/gtest.h>

#include <cmath>

using namespace pedesis;
using namespace pedesis::test;

namespace {

// Independent O(N^2) overlap check on a snapshot (does not trust any cell list).
template <int D>
void expect_no_overlap_brute(const ParticleStore<D>& s, const Box<D>& box, const char* when) {
    double worst = INFINITY;
    for (std::size_t i = 0; i < s.size(); ++i)
        for (std::size_t j = i + 1; j < s.size(); ++j) {
            const double d = norm(box.minimum_image(s.position[i] - s.position[j]));
            worst = std::min(worst, d / (s.radius(i) + s.radius(j)));
        }
    EXPECT_GE(worst, 1.0 - 1e-9) << when << ": closest pair at " << worst << " of contact";
    for (std::size_t i = 0; i < s.size(); ++i)
        EXPECT_TRUE(box.contains(s.position[i], s.radius(i) * (1.0 - 1e-9)))
            << when << ": particle " << s.tag[i];
}

template <int D> std::uint64_t total_collisions(const EventEngine<D>& e) {
    return e.counters().pair_collisions + e.counters().wall_collisions;
}

} // namespace

TEST(Conservation, EnergyOverMillionCollisions2D) {
    auto spec = equal_gas<2>(3000, 0.45);
    auto gas = make_gas(spec);
    const double e0 = kinetic_energy(gas.particles);
    EventEngine<2> e(gas.particles, gas.box, EventParams{});
    StopLimits lim;
    lim.pair_collisions = 1'000'000;
    EXPECT_EQ(e.run(lim), StopReason::collisions);
    EXPECT_EQ(e.counters().pair_collisions, 1'000'000u);
    const auto s = e.snapshot();
    const double e1 = kinetic_energy(s);
    EXPECT_NEAR(e1, e0, 1e-10 * e0);
    // the engine's running total agrees with the recomputed one
    EXPECT_NEAR(e.kinetic_energy(), e1, 1e-10 * e0);
    EXPECT_EQ(e.counters().energy_lost, 0.0);
    // and the momentum stays zero
    const Vec<2> P = total_momentum(s);
    EXPECT_LT(norm(P), 1e-12 * momentum_scale(s));
}

template <int D> void momentum_case(bool mixture) {
    GasSpec<D> spec;
    spec.eta = D == 2 ? 0.4 : 0.3;
    if (mixture)
        spec.species = {SpeciesSpec{300, 0.5, 1.0, -1.0}, SpeciesSpec{200, 0.35, 4.0, -1.0}};
    else
        spec.species = {SpeciesSpec{500, 0.5, 1.0, -1.0}};
    spec.seed = 17;
    auto gas = make_gas(spec);
    // give the whole system a drift so that conservation of a non-zero P is tested
    Vec<D> drift{};
    drift[0] = 0.3;
    drift[D - 1] = -0.2;
    for (auto& v : gas.particles.velocity) v += drift;
    const Vec<D> P0 = total_momentum(gas.particles);
    const double e0 = kinetic_energy(gas.particles);
    EventEngine<D> e(gas.particles, gas.box, EventParams{});
    StopLimits lim;
    lim.pair_collisions = 200'000;
    e.run(lim);
    const auto s = e.snapshot();
    const Vec<D> P1 = total_momentum(s);
    const double scale = momentum_scale(s);
    for (int a = 0; a < D; ++a) EXPECT_NEAR(P1[a], P0[a], 1e-12 * scale) << "axis " << a;
    EXPECT_NEAR(kinetic_energy(s), e0, 1e-11 * e0);
}

TEST(Conservation, MomentumPeriodic2D) {
    momentum_case<2>(false);
}
TEST(Conservation, MomentumPeriodic3D) {
    momentum_case<3>(false);
}
TEST(Conservation, MomentumPeriodicMixture2D) {
    momentum_case<2>(true);
}
TEST(Conservation, MomentumPeriodicMixture3D) {
    momentum_case<3>(true);
}

template <int D> void walled_momentum_case() {
    // walls: the momentum change of the gas is exactly what the walls gave it,
    // +wall_impulse on the low wall (pushes +) and -wall_impulse on the high wall
    auto spec = equal_gas<D>(400, D == 2 ? 0.3 : 0.2, false, 5);
    auto gas = make_gas(spec);
    const Vec<D> P0 = total_momentum(gas.particles);
    const double e0 = kinetic_energy(gas.particles);
    EventEngine<D> e(gas.particles, gas.box, EventParams{});
    StopLimits lim;
    lim.pair_collisions = 100'000;
    e.run(lim);
    const auto s = e.snapshot();
    const Vec<D> P1 = total_momentum(s);
    const auto& c = e.counters();
    EXPECT_GT(c.wall_collisions, 1000u);
    double impulse_scale = 0.0;
    for (int a = 0; a < D; ++a) impulse_scale += c.wall_impulse[a][0] + c.wall_impulse[a][1];
    for (int a = 0; a < D; ++a)
        EXPECT_NEAR(P1[a] - P0[a], c.wall_impulse[a][0] - c.wall_impulse[a][1],
                    1e-12 * impulse_scale);
    EXPECT_NEAR(kinetic_energy(s), e0, 1e-11 * e0);
    expect_no_overlap_brute(s, gas.box, "end of walled run");
}

TEST(Conservation, WallImpulseBalancesMomentum2D) {
    walled_momentum_case<2>();
}
TEST(Conservation, WallImpulseBalancesMomentum3D) {
    walled_momentum_case<3>();
}

template <int D> void dense_no_overlap_case(const GasSpec<D>& spec, std::uint64_t collisions) {
    auto gas = make_gas(spec);
    EventParams params;
    params.check_overlaps = true; // throws RunError after any collision that leaves an overlap
    EventEngine<D> e(gas.particles, gas.box, params);
    const double e0 = e.kinetic_energy();
    for (int k = 1; k <= 5; ++k) {
        StopLimits lim;
        lim.pair_collisions = collisions * k / 5;
        EXPECT_NO_THROW(e.run(lim)) << "stage " << k;
        EXPECT_NO_THROW(e.check_no_overlap()) << "stage " << k;
        EXPECT_NO_THROW(e.check_no_overlap(1e-12)) << "stage " << k;
    }
    EXPECT_EQ(e.counters().pair_collisions, collisions);
    const auto s = e.snapshot();
    expect_no_overlap_brute(s, gas.box, "end of dense run");
    EXPECT_NEAR(kinetic_energy(s), e0, 1e-10 * e0);
    EXPECT_GT(total_collisions(e), 0u);
}

TEST(NoOverlap, DenseDisks2D) {
    dense_no_overlap_case<2>(equal_gas<2>(900, 0.70, true, 3), 400'000);
}
TEST(NoOverlap, DenseDisksWalled2D) {
    dense_no_overlap_case<2>(equal_gas<2>(900, 0.62, false, 4), 300'000);
}
TEST(NoOverlap, DenseSpheres3D) {
    dense_no_overlap_case<3>(equal_gas<3>(500, 0.50, true, 5), 300'000);
}
TEST(NoOverlap, DenseSpheresWalled3D) {
    dense_no_overlap_case<3>(equal_gas<3>(500, 0.45, false, 6), 200'000);
}
TEST(NoOverlap, BinaryMixture2D) {
    GasSpec<2> spec;
    spec.species = {SpeciesSpec{400, 0.5, 1.0, -1.0}, SpeciesSpec{400, 0.35, 0.5, -1.0}};
    spec.eta = 0.6;
    spec.seed = 8;
    dense_no_overlap_case<2>(spec, 300'000);
}

TEST(NoOverlap, GasAmongFixedObstacles2D) {
    // 10% of the disks are immovable posts: energy is conserved and nothing overlaps
    auto spec = equal_gas<2>(1000, 0.45, true, 9);
    auto gas = make_gas(spec);
    gas.particles.species_table.push_back(Species{"post", 0.5, INFINITY});
    for (std::size_t i = 0; i < gas.particles.size(); i += 10) gas.particles.species[i] = 1;
    const double e0 = kinetic_energy(gas.particles);
    EventParams params;
    params.check_overlaps = true;
    EventEngine<2> e(gas.particles, gas.box, params);
    StopLimits lim;
    lim.pair_collisions = 200'000;
    EXPECT_NO_THROW(e.run(lim));
    const auto s = e.snapshot();
    const auto initial_index = gas.particles.index_of_tags();
    for (std::size_t i = 0; i < s.size(); ++i) {
        if (s.species[i] != 1) continue;
        EXPECT_EQ(norm2(s.velocity[i]), 0.0);
        const auto j = initial_index[s.tag[i]];
        EXPECT_NEAR(norm(gas.box.minimum_image(s.position[i] - gas.particles.position[j])), 0.0,
                    1e-12);
    }
    EXPECT_NEAR(kinetic_energy(s), e0, 1e-10 * e0);
    expect_no_overlap_brute(s, gas.box, "end of run among posts");
}

// ---- unusual geometries ---------------------------------------------------------------

template <int D>
ParticleStore<D> random_disks(const Box<D>& box, std::size_t n, double radius, std::uint64_t seed) {
    std::vector<Vec<D>> pos;
    std::vector<double> radii;
    PlacementRequest<D> req;
    req.count = n;
    req.radius = radius;
    for (int a = 0; a < D; ++a) {
        const double inset = box.periodic(a) ? 0.0 : radius;
        req.lo[a] = box.lo(a) + inset;
        req.hi[a] = box.hi(a) - inset;
    }
    req.what = "test";
    place_randomly<D>(pos, radii, box, req, seed);
    ParticleStore<D> p;
    p.species_table = {Species{"A", radius, 1.0}};
    p.resize(n);
    VelocitySpec vs;
    for (std::size_t i = 0; i < n; ++i) {
        p.position[i] = pos[i];
        box.wrap(p.position[i]);
        p.tag[i] = static_cast<std::uint32_t>(i);
        p.species[i] = 0;
        p.velocity[i] = draw_velocity<D>(vs, 1.0, seed, p.tag[i]);
    }
    return p;
}

template <int D>
void geometry_case(const Box<D>& box, std::size_t n, std::uint64_t collisions, std::uint64_t seed) {
    auto p = random_disks<D>(box, n, 0.5, seed);
    const double e0 = kinetic_energy(p);
    const Vec<D> P0 = total_momentum(p);
    EventParams params;
    params.check_overlaps = true;
    EventEngine<D> e(p, box, params);
    StopLimits lim;
    lim.pair_collisions = collisions;
    EXPECT_NO_THROW(e.run(lim));
    EXPECT_EQ(e.counters().pair_collisions, collisions);
    EXPECT_NO_THROW(e.check_no_overlap());
    const auto s = e.snapshot();
    expect_no_overlap_brute(s, box, "end of run");
    EXPECT_NEAR(kinetic_energy(s), e0, 1e-10 * e0);
    // momentum along periodic axes is conserved; along walled axes the walls account for it
    const Vec<D> P1 = total_momentum(s);
    for (int a = 0; a < D; ++a) {
        const double wall = e.counters().wall_impulse[a][0] - e.counters().wall_impulse[a][1];
        if (box.periodic(a)) {
            EXPECT_EQ(wall, 0.0);
        }
        EXPECT_NEAR(P1[a] - P0[a], wall,
                    1e-10 * momentum_scale(s) * (1.0 + e.counters().wall_collisions));
    }
}

// Periodic axes only 2.5 and 3.5 diameters long: one or two cells, neighbour skin cut
// down so that the minimum image stays unique; particles meet their own images' neighbours.
TEST(Geometry, ThinPeriodicStrip2D) {
    geometry_case<2>(Box<2>(Vec<2>{{2.5, 60.0}}, {true, true}), 70, 100'000, 1);
    geometry_case<2>(Box<2>(Vec<2>{{3.5, 40.0}}, {true, true}), 70, 100'000, 2);
}
TEST(Geometry, ThinPeriodicSlab3D) {
    geometry_case<3>(Box<3>(Vec<3>{{2.5, 2.5, 30.0}}, {true, true, true}), 60, 100'000, 3);
    geometry_case<3>(Box<3>(Vec<3>{{2.2, 8.0, 8.0}}, {true, true, true}), 60, 100'000, 4);
}
// Channel: periodic along x, walls along y (and a 3D duct)
TEST(Geometry, Channel2D) {
    geometry_case<2>(Box<2>(Vec<2>{{40.0, 6.0}}, {true, false}), 120, 200'000, 5);
}
TEST(Geometry, Duct3D) {
    geometry_case<3>(Box<3>(Vec<3>{{20.0, 4.0, 3.0}}, {true, false, false}), 80, 200'000, 6);
}
// Walls very close together: a single file of disks between walls 1.4 diameters apart
TEST(Geometry, SingleFile2D) {
    geometry_case<2>(Box<2>(Vec<2>{{60.0, 1.4}}, {true, false}), 30, 50'000, 7);
}

TEST(NoOverlap, LargeSizeRatioMixture2D) {
    // radii 2.5 and 0.3: a big disk has dozens of small neighbours, which outgrows the
    // neighbour lists sized at the start (they must grow) and stresses the cell list
    GasSpec<2> spec;
    spec.species = {SpeciesSpec{20, 2.5, 10.0, -1.0}, SpeciesSpec{1500, 0.3, 1.0, -1.0}};
    spec.eta = 0.5;
    spec.placement = Placement::random;
    spec.seed = 10;
    dense_no_overlap_case<2>(spec, 300'000);
}
TEST(NoOverlap, LargeSizeRatioMixture3D) {
    GasSpec<3> spec;
    spec.species = {SpeciesSpec{8, 1.5, 10.0, -1.0}, SpeciesSpec{1500, 0.3, 1.0, -1.0}};
    spec.eta = 0.3;
    spec.placement = Placement::random;
    spec.seed = 11;
    dense_no_overlap_case<3>(spec, 100'000);
}
