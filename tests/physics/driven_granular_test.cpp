// A granular gas driven by white noise ([event] driving = "white_noise"; van Noije &
// Ernst, Granular Matter 1, 57 (1998)) reaches the stationary temperature where the
// injected power balances the collisional loss.
//
// The balance per particle: the kicks inject (m D / 2) s nu, s the velocity variance
// per component and kick (driving_strength), nu each particle's kick rate
// (driving_rate). A collision of restitution e takes (1 - e^2) (m/4) (g.n)^2, and for
// Maxwellian velocities the collision-weighted mean of (g.n)^2 is 4 T / m, so each
// collision takes (1 - e^2) T; a particle has omega / 2 collisions per unit time of its
// own (omega the Enskog collision frequency, each collision shared by two), so the loss
// is (omega / 2)(1 - e^2) T. With omega = omega_1 sqrt(T) (omega_1 at T = 1):
//     T^(3/2) = m D s nu / ((1 - e^2) omega_1).
// Corrections: the velocity distribution's a2 (~0.01 for white-noise-driven disks at e =
// 0.9, van Noije & Ernst) changes the loss by ~0.2%; velocity correlations and the
// contact value's error at area fraction 0.1 by ~1%. Tolerance 5%.
// The run: N = 500 disks, area fraction 0.1, e = 0.9, nu = 1, s = 0.05 (T ~ 1), relaxed
// for 60 time units (the energy relaxes at (3/2)(1 - e^2) omega ~ 0.15 per unit time), then
// sampled for 300: the mean's standard error is ~0.5%.
#include "pedesis/event/event_engine.hpp"
#include "pedesis/observe/theory.hpp"
#include "support/gas_builder.hpp"

#include <gtest/gtest.h>

#include <cmath>

using namespace pedesis;
using namespace pedesis::test;

TEST(DrivenGranularGas, ReachesTheTemperatureWhereInjectionBalancesTheLoss) {
    constexpr int D = 2;
    const std::size_t n = 500;
    const double e_rest = 0.9, nu = 1.0, s = 0.05;
    auto spec = equal_gas<D>(n, 0.1, true, 5);
    spec.placement = Placement::random;
    const auto gas = make_gas(spec);
    EventParams params;
    params.restitution = e_rest;
    params.driving_rate = nu;
    params.driving_strength = s;
    params.seed = 4;
    EventEngine<D> e(gas.particles, gas.box, params);
    StopLimits lim;
    lim.time = 60.0;
    e.run(lim);
    const double inj0 = e.driving().injected_energy, t0 = e.time();
    const double lost0 = e.counters().energy_lost, k0 = e.kinetic_energy();
    const std::uint64_t c0 = e.counters().pair_collisions;
    double kinetic = 0.0;
    const int samples = 600;
    for (int k = 1; k <= samples; ++k) {
        lim.time = t0 + 0.5 * k;
        e.run(lim);
        kinetic += e.kinetic_energy();
    }
    // the momentum is kept (zero): f = D (N - 1)
    const double T = 2.0 * kinetic / samples / (D * (static_cast<double>(n) - 1.0));
    const double rho = static_cast<double>(n) / gas.box.volume();
    const double omega1 = theory::enskog_collision_frequency(D, rho, 1.0, 1.0, 1.0);
    const double T_theory = std::pow(D * s * nu / ((1.0 - e_rest * e_rest) * omega1), 2.0 / 3.0);
    const double dt = e.time() - t0;
    const double power = (e.driving().injected_energy - inj0) / dt / static_cast<double>(n);
    const double omega =
        2.0 * static_cast<double>(e.counters().pair_collisions - c0) / dt / static_cast<double>(n);
    std::printf("[driven] T = %.4f, theory %.4f (ratio %.4f); injected power per particle %.5f "
                "(expected %.5f); collision frequency %.4f (Enskog %.4f)\n",
                T, T_theory, T / T_theory, power, 0.5 * D * s * nu, omega, omega1 * std::sqrt(T));
    EXPECT_NEAR(T / T_theory, 1.0, 0.05);
    // (each pair kick's energy has a standard deviation ~6 times its mean, 2 s T-weighted
    // cross terms: over 75000 kicks the mean power scatters by ~2.5%)
    EXPECT_NEAR(power / (0.5 * D * s * nu), 1.0, 0.08);
    // the books balance: injected - lost = the change of the kinetic energy, to rounding
    const double injected = e.driving().injected_energy - inj0;
    const double lost = e.counters().energy_lost - lost0;
    EXPECT_NEAR(injected - lost, e.kinetic_energy() - k0, 1e-9 * injected);
    EXPECT_NEAR(omega / (omega1 * std::sqrt(T)), 1.0, 0.05);
}
