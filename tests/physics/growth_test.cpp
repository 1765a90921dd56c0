// Lubachevsky-Stillinger growth in the event engine: exact collision times and rules
// for growing spheres against closed forms, the approach to random close packing with
// its free-volume pressure divergence, and a compression to a target packing fraction
// that leaves an equilibrium fluid on the Carnahan-Starling equation of state.
#include "pedesis/event/event_engine.hpp"
#include "pedesis/observe/theory.hpp"
#include "support/gas_builder.hpp"
#include "support/growing_gas.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <vector>

using namespace pedesis;
using namespace pedesis::test;

namespace {

ParticleStore<3> spheres(const std::vector<Vec<3>>& r, const std::vector<Vec<3>>& v) {
    ParticleStore<3> p;
    p.species_table = {Species{"A", 0.5, 1.0}};
    p.resize(r.size());
    for (std::size_t i = 0; i < r.size(); ++i) {
        p.position[i] = r[i];
        p.velocity[i] = v[i];
        p.tag[i] = static_cast<std::uint32_t>(i);
        p.species[i] = 0;
    }
    return p;
}

Box<3> walled_cube(double L) {
    return Box<3>(Vec<3>::filled(L), std::array<bool, 3>{false, false, false});
}

} // namespace

// Two unit-diameter spheres 4 apart close at speed 2 while the contact distance grows
// as 1 + 0.5 t: they touch at t = 3 / 2.5 = 1.2, 1.6 apart. The closing speed relative
// to the growing surfaces, -2.5, is reversed: J = 2.5, velocities -1.5 and +1.5, virial
// J * 1.6 = 4. The thermostat then scales the kinetic energy back to its start (|v| = 1).
TEST(ExactGrowth, HeadOnPair) {
    EventParams params;
    params.growth_rate = 0.5;
    EventEngine<3> e(spheres({Vec<3>{-2.0, 0.0, 0.0}, Vec<3>{2.0, 0.0, 0.0}},
                             {Vec<3>{1.0, 0.0, 0.0}, Vec<3>{-1.0, 0.0, 0.0}}),
                     walled_cube(20.0), params);
    StopLimits lim;
    lim.pair_collisions = 1;
    EXPECT_EQ(e.run(lim), StopReason::collisions);
    EXPECT_NEAR(e.time(), 1.2, 1e-13);
    EXPECT_NEAR(virial_trace(e.counters()), 4.0, 1e-12);
    const auto s = e.snapshot();
    EXPECT_NEAR(s.species_table[0].radius, 0.8, 1e-13);
    EXPECT_NEAR(s.position[0][0], -0.8, 1e-12);
    EXPECT_NEAR(s.position[1][0], 0.8, 1e-12);
    EXPECT_NEAR(s.velocity[0][0], -1.0, 1e-12);
    EXPECT_NEAR(s.velocity[1][0], 1.0, 1e-12);
    EXPECT_NEAR(e.packing_fraction(), 2.0 * 4.0 / 3.0 * M_PI * std::pow(0.8, 3) / 8000.0, 1e-15);
    EXPECT_EQ(e.counters().wall_collisions, 0u);
}

// A sphere of radius 0.5 growing at 0.25 per unit time, at x = 2 moving at +1 toward
// the wall at 5: contact when 2 + t = 4.5 - 0.25 t, t = 2, at x = 4. The wall reverses
// the closing speed 1.25 relative to the moving surface: v = -1.25 - 0.25 = -1.5, and
// the thermostat brings it back to speed 1.
TEST(ExactGrowth, WallContact) {
    EventParams params;
    params.growth_rate = 0.5;
    EventEngine<3> e(spheres({Vec<3>{2.0, 0.0, 0.0}}, {Vec<3>{1.0, 0.0, 0.0}}), walled_cube(10.0),
                     params);
    StopLimits lim;
    lim.time = 1.999;
    e.run(lim);
    EXPECT_EQ(e.counters().wall_collisions, 0u);
    lim.time = 2.01;
    e.run(lim);
    EXPECT_EQ(e.counters().wall_collisions, 1u);
    EXPECT_NEAR(e.counters().wall_impulse[0][1], 2.5, 1e-12); // m (1 - (-1.5))
    const auto s = e.snapshot();
    EXPECT_NEAR(s.velocity[0][0], -1.0, 1e-12);
    EXPECT_NEAR(s.position[0][0], 4.0 - 0.01, 1e-12);
}

// Fast compression of a dilute fluid jams near random close packing. Skoge, Donev,
// Stillinger and Torquato (PRE 74, 041127, 2006) find jamming densities 0.63-0.645 for
// growth rates 1e-1 to 1e-3 (diameter per unit time at kT/m = 1); at 0.03 we expect
// 0.63-0.64. Near jamming the pressure follows the free-volume law Z = 3 / (1 - phi/phi_J)
// (Salsburg and Wood): every window with Z > 100 must point at the same phi_J to 0.003,
// the spread a run of this size (2000 spheres) gives between seeds being about 0.002.
TEST(GrowthJamming, FastCompressionStopsNearRandomClosePacking) {
    auto e = growing_gas(2000, 0.15, 5, 0.03, 0.0);
    std::vector<double> phi_j;
    StopLimits lim;
    StopReason why = StopReason::time;
    double last_z = 0.0;
    for (int k = 1; k < 100000 && why != StopReason::grown; ++k) {
        lim.time = 0.05 * k;
        why = e.run(lim);
        const double z = e.growth().last_pressure;
        if (z > 100.0 && z != last_z) phi_j.push_back(e.packing_fraction() / (1.0 - 3.0 / z));
        last_z = z;
    }
    ASSERT_EQ(why, StopReason::grown);
    EXPECT_EQ(e.growth().ended, GrowthEnd::pressure);
    const double phi = e.packing_fraction();
    EXPECT_GT(phi, 0.625);
    EXPECT_LT(phi, 0.650);
    e.check_no_overlap(1e-9);

    ASSERT_GE(phi_j.size(), 3u);
    for (double pj : phi_j) {
        EXPECT_NEAR(pj, phi_j.back(), 0.003);
        EXPECT_GT(pj, phi);
    }
}

// Growth to a set packing fraction ends there exactly, at the temperature it started
// with; the fluid it leaves, given 5 time units to relax, has the Carnahan-Starling
// pressure. At eta = 0.45, Z = 9.385 (simulations agree within 0.5%); 1500 spheres over
// 20 time units (~4e5 collisions) give Z to about 0.5%, so 1.5% leaves room for the
// relaxation of the compressed structure.
TEST(GrowthTarget, StopsAtThePackingFractionAsAnEquilibriumFluid) {
    auto e = growing_gas(1500, 0.2, 9, 0.1, 0.45);
    const double k0 = e.kinetic_energy();
    StopLimits lim;
    lim.time = 100.0;
    ASSERT_EQ(e.run(lim), StopReason::grown);
    EXPECT_EQ(e.growth().ended, GrowthEnd::packing_fraction);
    EXPECT_NEAR(e.packing_fraction(), 0.45, 1e-9);
    EXPECT_NEAR(e.kinetic_energy(), k0, 1e-9 * k0);
    EXPECT_NEAR(e.snapshot().species_table[0].radius, 0.5 * std::cbrt(0.45 / 0.2), 1e-9);

    lim.time = e.time() + 5.0;
    EXPECT_EQ(e.run(lim), StopReason::time);
    const double t0 = e.time(), w0 = virial_trace(e.counters());
    lim.time = t0 + 20.0;
    e.run(lim);
    EXPECT_NEAR(e.kinetic_energy(), k0, 1e-9 * k0); // elastic now: energy conserved
    const double z = 1.0 + (virial_trace(e.counters()) - w0) / (2.0 * k0 * (e.time() - t0));
    const double z_cs = theory::compressibility_factor(3, 0.45);
    EXPECT_NEAR(z / z_cs, 1.0, 0.015) << "Z = " << z << ", Carnahan-Starling " << z_cs;
}
