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
// sampled for 300: the mean's standard error is ~0.7%, but the kicks' randomness moves
// the power they inject by ~2.5% (T by 2/3 of that). So T is also compared with the
// balance at the measured power, at 3%. Measured: 1.033 and 1.016.
#include "support/driven_gases.hpp"

#include <gtest/gtest.h>

#include <cstdio>

using namespace pedesis::test;

TEST(DrivenGranularGas, ReachesTheTemperatureWhereInjectionBalancesTheLoss) {
    constexpr int D = 2;
    const double e_rest = 0.9, nu = 1.0, s = 0.05;
    const DrivenResult r = driven_gas<D>(500, 0.1, e_rest, nu, s, 60.0, 300.0, 5);
    const double expected_power = 0.5 * D * s * nu; // (D/2) m s nu
    std::printf("[driven] T = %.4f, theory %.4f (ratio %.4f), for the measured power %.4f (ratio "
                "%.4f); injected power per particle %.5f (expected %.5f); collision frequency / "
                "Enskog %.4f\n",
                r.T, r.T_theory, r.T / r.T_theory, r.T_balance, r.T / r.T_balance, r.power,
                expected_power, r.omega_ratio);
    EXPECT_NEAR(r.T / r.T_theory, 1.0, 0.05);
    EXPECT_NEAR(r.T / r.T_balance, 1.0, 0.03);
    // (each pair kick's energy has a standard deviation ~6 times its mean, 2 s T-weighted
    // cross terms: over 75000 kicks the mean power scatters by ~2.5%)
    EXPECT_NEAR(r.power / expected_power, 1.0, 0.08);
    EXPECT_NEAR(r.omega_ratio, 1.0, 0.05);
    // the books balance: injected - lost = the change of the kinetic energy, to rounding
    EXPECT_LT(std::abs(r.residual), 1e-9);
}
