#pragma once
// Reference results from kinetic theory and liquid-state theory (see docs/validation.md).
// Units: k_B = 1; sigma is a diameter.
#include <algorithm>
#include <cmath>
#include <numbers>
#include <vector>

namespace pedesis::theory {

// Packing fraction of n particles of diameter sigma per unit volume (area in 2D).
inline double packing_fraction(int dim, double number_density, double sigma) {
    return dim == 2 ? number_density * std::numbers::pi * sigma * sigma / 4.0
                    : number_density * std::numbers::pi * sigma * sigma * sigma / 6.0;
}

// Compressibility factor Z = P / (rho T): Henderson (2D), Carnahan-Starling (3D).
inline double compressibility_factor(int dim, double eta) {
    if (dim == 2) return (1.0 + eta * eta / 8.0) / ((1.0 - eta) * (1.0 - eta));
    return (1.0 + eta + eta * eta - eta * eta * eta) / std::pow(1.0 - eta, 3);
}

// Contact value of the pair correlation function g(sigma), consistent with the above.
inline double contact_value(int dim, double eta) {
    if (dim == 2) return (1.0 - 7.0 * eta / 16.0) / ((1.0 - eta) * (1.0 - eta));
    return (1.0 - eta / 2.0) / std::pow(1.0 - eta, 3);
}

// Enskog collision frequency per particle, equal masses m.
inline double enskog_collision_frequency(int dim, double number_density, double sigma, double T,
                                         double m) {
    const double eta = packing_fraction(dim, number_density, sigma);
    const double g = contact_value(dim, eta);
    const double pref = dim == 2 ? 2.0 * std::sqrt(std::numbers::pi) * sigma
                                 : 4.0 * std::sqrt(std::numbers::pi) * sigma * sigma;
    return pref * number_density * g * std::sqrt(T / m);
}

// Haff's law for homogeneous cooling with restitution xi; omega0 is the collision
// frequency per particle at T0.
inline double haff_temperature(int dim, double t, double T0, double omega0, double xi) {
    const double t0 = 2.0 * dim / ((1.0 - xi * xi) * omega0);
    const double s = 1.0 + t / t0;
    return T0 / (s * s);
}

// Equilibrium speed distribution (Rayleigh in 2D, Maxwell in 3D) of particles of
// mass m at temperature T: density and cumulative distribution.
inline double speed_pdf(int dim, double v, double T, double m) {
    const double a = m / T;
    if (v < 0.0) return 0.0;
    if (dim == 2) return a * v * std::exp(-0.5 * a * v * v);
    return 4.0 * std::numbers::pi * v * v * std::pow(a / (2.0 * std::numbers::pi), 1.5) *
           std::exp(-0.5 * a * v * v);
}

inline double speed_cdf(int dim, double v, double T, double m) {
    if (v <= 0.0) return 0.0;
    const double s = std::sqrt(T / m);
    const double x = v / s;
    if (dim == 2) return 1.0 - std::exp(-0.5 * x * x);
    return std::erf(x / std::sqrt(2.0)) -
           std::sqrt(2.0 / std::numbers::pi) * x * std::exp(-0.5 * x * x);
}

// Kolmogorov-Smirnov distance between a sample (sorted in place) and a CDF.
template <class Cdf> double ks_distance(std::vector<double>& sample, Cdf&& cdf) {
    std::sort(sample.begin(), sample.end());
    const double n = static_cast<double>(sample.size());
    double d = 0.0;
    for (std::size_t k = 0; k < sample.size(); ++k) {
        const double F = cdf(sample[k]);
        d = std::max(d,
                     std::max(F - static_cast<double>(k) / n, static_cast<double>(k + 1) / n - F));
    }
    return d;
}

// Critical KS distance for sample size n at significance alpha (asymptotic form,
// c(alpha) = sqrt(-ln(alpha/2)/2)).
inline double ks_critical(std::size_t n, double alpha) {
    return std::sqrt(-0.5 * std::log(alpha / 2.0)) / std::sqrt(static_cast<double>(n));
}

} // namespace pedesis::theory
