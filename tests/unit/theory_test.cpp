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
