// Conservation laws of the stepped engine. Every pair collision conserves energy and
// momentum exactly (the event engine's elastic rule) and every wall bounce conserves
// energy and hands the wall a known momentum, so the only per-step error is rounding:
// about 1e-16 relative per event. Over the ~1e5 events of these runs a random walk of
// such errors stays near 1e-14; the tolerance is 1e-12.
//
// - periodic box: kinetic energy and total momentum constant;
// - walled box (a mixture of masses and radii): energy constant, and the change of total
//   momentum equals minus what the walls received, axis by axis (the momentum accounting
//   that gives the pressure);
// - no centre ever ends a step closer to a wall than its radius;
// - overlaps left at the end of a step come only from grazing collisions missed within a
//   step (stepped_engine.hpp): a pair whose relative displacement in the step is
//   x sigma penetrates at most sigma x^2 / 8 along a chord it crosses entirely; with
//   every particle moving at most max_move radii per step, x <= max_move, so no overlap
//   may exceed sigma max_move^2 / 8.
#include "pedesis/spatial/cell_list.hpp"
#include "pedesis/stepped/stepped_engine.hpp"
#include "pedesis/stepped/time_step.hpp"
#include "support/gas_builder.hpp"

#include <gtest/gtest.h>

#include <cstdio>

using namespace pedesis;
using namespace pedesis::test;

namespace {

// Deepest overlap, as a fraction of the contact distance.
template <int D> double deepest_overlap(const ParticleStore<D>& p, const Box<D>& box) {
    double rmax = 0.0;
    for (const auto& s : p.species_table) rmax = std::max(rmax, s.radius);
    CellList<D> cells(box, 2.0 * rmax);
    cells.build(p.position);
    double worst = 0.0;
    for (std::uint32_t i = 0; i < p.size(); ++i)
        cells.for_each_near(p.position[i], [&](std::uint32_t j) {
            if (j <= i) return;
            const double sigma = p.radius(i) + p.radius(j);
            const double d = norm(box.minimum_image(p.position[i] - p.position[j]));
            worst = std::max(worst, (sigma - d) / sigma);
        });
    return worst;
}

template <int D> void conserves(const GasSpec<D>& spec, int steps) {
    auto gas = make_gas(spec);
    SteppedParams params;
    params.dt = suggested_time_step(gas.particles, params.max_move, 100.0 * gas.particles.size());
    SteppedEngine<D> e(gas.particles, gas.box, params);
    const double K0 = e.kinetic_energy();
    const Vec<D> P0 = total_momentum(e.particles());
    const double scale = momentum_scale(e.particles());
    double worst_overlap = 0.0, worst_wall = 0.0;
    for (int k = 0; k < steps; ++k) {
        e.step();
        const auto& p = e.particles();
        worst_overlap = std::max(worst_overlap, deepest_overlap(p, gas.box));
        for (std::size_t i = 0; i < p.size(); ++i)
            for (int a = 0; a < D; ++a) {
                if (gas.box.periodic(a)) continue;
                const double inside = gas.box.hi(a) - p.radius(i) - std::abs(p.position[i][a]);
                worst_wall = std::min(worst_wall, inside);
            }
    }
    const auto& c = e.counters();
    Vec<D> P = total_momentum(e.particles()), given{};
    for (int a = 0; a < D; ++a) given[a] = c.wall_impulse[a][0] - c.wall_impulse[a][1];
    double wall_total = 0.0;
    for (int a = 0; a < D; ++a) wall_total += c.wall_impulse[a][0] + c.wall_impulse[a][1];
    std::printf("D %d %s: %llu pair and %llu wall collisions in %d steps; energy error %.2e, "
                "momentum error %.2e; deepest overlap %.2e sigma, %llu late collisions\n",
                D, spec.periodic ? "periodic" : "walled",
                static_cast<unsigned long long>(c.pair_collisions),
                static_cast<unsigned long long>(c.wall_collisions), steps,
                std::abs(e.kinetic_energy() - K0) / K0, norm(P - P0 - given) / scale, worst_overlap,
                static_cast<unsigned long long>(e.stats().late_collisions));
    ASSERT_GT(c.pair_collisions, 20000u) << "too few collisions to test anything";
    EXPECT_LT(std::abs(e.kinetic_energy() - K0), 1e-12 * K0);
    EXPECT_LT(norm(P - P0 - given), 1e-12 * scale);
    if (!spec.periodic) {
        EXPECT_GT(wall_total, 0.0);
    }
    EXPECT_GE(worst_wall, -1e-12 * gas.box.length(0)) << "a centre ended past a wall";
    EXPECT_LE(worst_overlap, params.max_move * params.max_move / 8.0);
}

} // namespace

TEST(SteppedConservation, PeriodicDenseGas2D) {
    auto spec = equal_gas<2>(1000, 0.35, true, 5);
    conserves(spec, 600);
}

TEST(SteppedConservation, WalledMixture2D) {
    GasSpec<2> spec;
    spec.species = {SpeciesSpec{600, 0.5, 1.0, -1.0}, SpeciesSpec{200, 0.8, 4.0, -1.0}};
    spec.eta = 0.3;
    spec.periodic = false;
    spec.seed = 8;
    conserves(spec, 800);
}

TEST(SteppedConservation, WalledMixture3D) {
    GasSpec<3> spec;
    spec.species = {SpeciesSpec{800, 0.5, 1.0, -1.0}, SpeciesSpec{200, 0.7, 3.0, -1.0}};
    spec.eta = 0.25;
    spec.periodic = false;
    spec.seed = 9;
    conserves(spec, 400);
}
