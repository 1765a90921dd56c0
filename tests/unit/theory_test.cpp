// The reference formulas the physics tests are held to (observe/theory.hpp), checked
// against PHYSICS.md and against each other: speed pdf/cdf consistency and
// normalisation, Z = 1 + 2^(d-1) eta g(sigma), low-density virial expansions, Haff's
// law's initial slope, and the KS distance on exact quantiles.
#include "pedesis/observe/theory.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <vector>

using namespace pedesis;

namespace {

// Simpson's rule on [a, b] with n (even) intervals
template <class F> double simpson(F&& f, double a, double b, int n) {
    const double h = (b - a) / n;
    double s = f(a) + f(b);
    for (int k = 1; k < n; ++k) s += (k % 2 ? 4.0 : 2.0) * f(a + k * h);
    return s * h / 3.0;
}

} // namespace

TEST(Theory, SpeedCdfIsIntegralOfPdf) {
    for (int d : {2, 3}) {
        for (double T : {0.5, 1.0, 3.0}) {
            for (double m : {1.0, 4.0}) {
                const double scale = std::sqrt(T / m);
                EXPECT_NEAR(simpson([&](double v) { return theory::speed_pdf(d, v, T, m); }, 0.0,
                                    12.0 * scale, 4000),
                            1.0, 1e-10);
                for (double x : {0.3, 1.0, 1.7, 3.0}) {
                    const double v = x * scale;
                    EXPECT_NEAR(theory::speed_cdf(d, v, T, m),
                                simpson([&](double u) { return theory::speed_pdf(d, u, T, m); },
                                        0.0, v, 2000),
                                1e-10)
                        << "d " << d << " T " << T << " m " << m << " v " << v;
                }
                // mean square speed d T / m
                EXPECT_NEAR(simpson([&](double v) { return v * v * theory::speed_pdf(d, v, T, m); },
                                    0.0, 12.0 * scale, 4000),
                            d * T / m, 1e-9 * d * T / m);
            }
        }
        EXPECT_EQ(theory::speed_cdf(d, 0.0, 1.0, 1.0), 0.0);
        EXPECT_EQ(theory::speed_pdf(d, -1.0, 1.0, 1.0), 0.0);
    }
    // PHYSICS.md forms, written out
    const double v = 1.3, T = 0.8, m = 2.0;
    EXPECT_NEAR(theory::speed_pdf(2, v, T, m), m * v / T * std::exp(-m * v * v / (2 * T)), 1e-15);
    EXPECT_NEAR(theory::speed_pdf(3, v, T, m),
                4 * std::numbers::pi * v * v * std::pow(m / (2 * std::numbers::pi * T), 1.5) *
                    std::exp(-m * v * v / (2 * T)),
                1e-15);
}

TEST(Theory, CompressibilityFactorsAndContactValues) {
    for (double eta : {0.0, 0.05, 0.2, 0.4, 0.6}) {
        // PHYSICS.md
        EXPECT_NEAR(theory::compressibility_factor(2, eta),
                    (1 + eta * eta / 8) / ((1 - eta) * (1 - eta)), 1e-14);
        EXPECT_NEAR(theory::compressibility_factor(3, eta),
                    (1 + eta + eta * eta - eta * eta * eta) / std::pow(1 - eta, 3), 1e-13);
        // virial route at contact: Z = 1 + 2 eta g (2D), 1 + 4 eta g (3D)
        EXPECT_NEAR(theory::compressibility_factor(2, eta),
                    1 + 2 * eta * theory::contact_value(2, eta), 1e-13);
        EXPECT_NEAR(theory::compressibility_factor(3, eta),
                    1 + 4 * eta * theory::contact_value(3, eta), 1e-13);
    }
    // second virial coefficients: Z = 1 + 2 eta + ... (disks), 1 + 4 eta + 10 eta^2 (spheres)
    const double h = 1e-4;
    EXPECT_NEAR((theory::compressibility_factor(2, h) - 1) / h, 2.0, 1e-3);
    EXPECT_NEAR((theory::compressibility_factor(3, h) - 1 - 4 * h) / (h * h), 10.0, 1e-2);
    // packing fraction
    EXPECT_NEAR(theory::packing_fraction(2, 1.0, 1.0), std::numbers::pi / 4, 1e-15);
    EXPECT_NEAR(theory::packing_fraction(3, 1.0, 2.0), std::numbers::pi * 8 / 6, 1e-14);
}

TEST(Theory, EnskogFrequencyAndHaff) {
    const double n = 0.1, sigma = 1.0, T = 2.0, m = 1.5;
    const double eta2 = theory::packing_fraction(2, n, sigma),
                 eta3 = theory::packing_fraction(3, n, sigma);
    EXPECT_NEAR(theory::enskog_collision_frequency(2, n, sigma, T, m),
                2 * std::sqrt(std::numbers::pi) * n * sigma * theory::contact_value(2, eta2) *
                    std::sqrt(T / m),
                1e-14);
    EXPECT_NEAR(theory::enskog_collision_frequency(3, n, sigma, T, m),
                4 * std::sqrt(std::numbers::pi) * n * sigma * sigma *
                    theory::contact_value(3, eta3) * std::sqrt(T / m),
                1e-14);
    // Haff: T(0) = T0; initial slope dT/dt = -(1 - xi^2) omega0 T0 / d, i.e. each
    // collision (N omega / 2 per unit time) removes (1 - xi^2) T on average
    for (int d : {2, 3}) {
        const double T0 = 1.7, w0 = 0.9, xi = 0.8, dt = 1e-6;
        EXPECT_DOUBLE_EQ(theory::haff_temperature(d, 0.0, T0, w0, xi), T0);
        const double slope = (theory::haff_temperature(d, dt, T0, w0, xi) - T0) / dt;
        EXPECT_NEAR(slope, -(1 - xi * xi) * w0 * T0 / d, 1e-5);
        // at t = t0 the temperature is a quarter
        const double t0 = 2.0 * d / ((1 - xi * xi) * w0);
        EXPECT_NEAR(theory::haff_temperature(d, t0, T0, w0, xi), T0 / 4, 1e-14);
    }
}

TEST(Theory, EnskogTransportMatchesThePublishedTable) {
    // ../shared/PHYSICS.md (sigma = m = T = 1, Carnahan-Starling chi): D_E, eta_E, lambda_E
    // at phi = 0.1, 0.3, 0.45, to the digits given (2e-3 relative)
    const double table[3][4] = {
        {0.1, 0.8662, 0.2232, 0.9526}, {0.3, 0.1518, 0.7311, 3.082}, {0.45, 0.05385, 2.355, 9.359}};
    for (const auto& row : table) {
        const double n = 6.0 * row[0] / std::numbers::pi;
        const auto c = theory::enskog_transport(3, n, 1.0, 1.0, 1.0);
        EXPECT_NEAR(c.diffusion, row[1], 2e-3 * row[1]) << row[0];
        EXPECT_NEAR(c.shear_viscosity, row[2], 2e-3 * row[2]) << row[0];
        EXPECT_NEAR(c.thermal_conductivity, row[3], 2e-3 * row[3]) << row[0];
    }
    // units: sigma = 2 at the same phi scales D by sigma, eta and lambda by 1/sigma^2; m = 4
    // scales D and lambda by 1/2, eta by 2
    const double n1 = 6.0 * 0.3 / std::numbers::pi;
    const auto one = theory::enskog_transport(3, n1, 1.0, 1.0, 1.0);
    const auto big = theory::enskog_transport(3, n1 / 8.0, 2.0, 1.0, 1.0);
    EXPECT_NEAR(big.diffusion, 2.0 * one.diffusion, 1e-12);
    EXPECT_NEAR(big.shear_viscosity, one.shear_viscosity / 4.0, 1e-12);
    const auto heavy = theory::enskog_transport(3, n1, 1.0, 4.0, 1.0);
    EXPECT_NEAR(heavy.thermal_conductivity, one.thermal_conductivity / 2.0, 1e-12);
    EXPECT_NEAR(heavy.bulk_viscosity, 2.0 * one.bulk_viscosity, 1e-12);
    // 3D bulk viscosity (4/9) sqrt(pi) n^2 chi; 2D: half the (8/pi) phi^2 chi eta0 term of
    // eta_E doubled, i.e. kappa_E = (16/pi) phi^2 chi eta0 with eta0 = 1/(2 sqrt(pi))
    const double chi3 = theory::contact_value(3, 0.3);
    EXPECT_NEAR(one.bulk_viscosity, 4.0 / 9.0 * std::sqrt(std::numbers::pi) * n1 * n1 * chi3,
                1e-12);
    const double phi2 = 0.3, n2 = 4.0 * phi2 / std::numbers::pi;
    const auto two = theory::enskog_transport(2, n2, 1.0, 1.0, 1.0);
    const double chi2 = theory::contact_value(2, phi2);
    EXPECT_NEAR(two.bulk_viscosity,
                16.0 / std::numbers::pi * phi2 * phi2 * chi2 / (2.0 * std::sqrt(std::numbers::pi)),
                1e-12);
    EXPECT_NEAR(two.diffusion, 1.0 / (2.0 * n2 * std::sqrt(std::numbers::pi)) / chi2, 1e-12);
    EXPECT_NEAR(theory::yeh_hummer(0.1, 1.0, 2.0, 10.0),
                0.1 + 2.837297 / (6.0 * std::numbers::pi * 20.0), 1e-15);
}

TEST(Theory, KolmogorovSmirnov) {
    // exact quantiles of the distribution: distance at most 1/n
    const std::size_t n = 1000;
    std::vector<double> q(n);
    for (std::size_t k = 0; k < n; ++k) {
        const double u = (k + 0.5) / n;
        q[k] = std::sqrt(-2.0 * std::log(1.0 - u)); // Rayleigh, T = m = 1
    }
    EXPECT_LE(theory::ks_distance(q, [](double v) { return theory::speed_cdf(2, v, 1.0, 1.0); }),
              1.0 / n + 1e-12);
    // all samples at one value: distance max(F, 1 - F) there
    std::vector<double> same(n, std::sqrt(2.0));
    const double F = 1.0 - std::exp(-1.0);
    EXPECT_NEAR(
        theory::ks_distance(same, [](double v) { return theory::speed_cdf(2, v, 1.0, 1.0); }),
        std::max(F, 1.0 - F), 1e-12);
    // critical value c(alpha) / sqrt(n): c(0.05) = 1.358, c(0.001) = 1.949
    EXPECT_NEAR(theory::ks_critical(10000, 0.05) * 100.0, 1.358, 1e-3);
    EXPECT_NEAR(theory::ks_critical(10000, 0.001) * 100.0, 1.949, 1e-3);
}
