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

// Transport coefficients of one-component hard disks and spheres (diameter sigma, mass
// m, temperature T, number density n), as in ../shared/PHYSICS.md and Python's
// pedesis.analyze.enskog_transport. Dilute (Chapman-Enskog): 3D with the converged Sonine
// factors, D0 = 1.018954 (3 / 8) / (n sigma^2) sqrt(T / (pi m)),
// eta0 = 1.016034 (5 / 16) sqrt(m T / pi) / sigma^2,
// lambda0 = 1.025218 (75 / 64) sqrt(T / (pi m)) / sigma^2; 2D first Sonine,
// D0 = sqrt(T / (pi m)) / (2 n sigma), eta0 = sqrt(m T / pi) / (2 sigma),
// lambda0 = 2 sqrt(T / (pi m)) / sigma. Enskog: D_E = D0 / chi;
// 3D (y = 4 phi chi) eta_E = (eta0 / chi)(1 + 0.8 y + 0.7615 y^2),
// lambda_E = (lambda0 / chi)(1 + 1.2 y + 0.7575 y^2), kappa_E = (4/9) n^2 sigma^4 chi
// sqrt(pi m T); 2D eta_E = eta0 [1/chi + 2 phi + (1 + 8/pi) phi^2 chi],
// lambda_E = lambda0 [1/chi + 3 phi + (9/4 + 4/pi) phi^2 chi],
// kappa_E = (1/2) n^2 sigma^3 chi sqrt(pi m T). k_B = 1.
struct TransportCoefficients {
    double diffusion, shear_viscosity, bulk_viscosity, thermal_conductivity;
};

inline TransportCoefficients enskog_transport(int dim, double n, double sigma, double m, double T) {
    const double pi = std::numbers::pi, root_pi = std::sqrt(pi);
    const double phi = packing_fraction(dim, n, sigma), chi = contact_value(dim, phi);
    const double speed = std::sqrt(T / m), sd = std::pow(sigma, dim);
    const double d_unit = sigma * speed / (n * sd);
    const double eta_unit = std::sqrt(m * T) / std::pow(sigma, dim - 1);
    const double lambda_unit = speed / std::pow(sigma, dim - 1);
    TransportCoefficients c{};
    if (dim == 2) {
        const double eta0 = eta_unit / (2.0 * root_pi), lambda0 = 2.0 * lambda_unit / root_pi;
        c.diffusion = d_unit / (2.0 * root_pi) / chi;
        c.shear_viscosity = eta0 * (1.0 / chi + 2.0 * phi + (1.0 + 8.0 / pi) * phi * phi * chi);
        c.thermal_conductivity =
            lambda0 * (1.0 / chi + 3.0 * phi + (2.25 + 4.0 / pi) * phi * phi * chi);
        c.bulk_viscosity = 0.5 * root_pi * (n * sd) * (n * sd) * chi * eta_unit;
    } else {
        const double y = 4.0 * phi * chi;
        const double eta0 = 1.016034 * 5.0 / (16.0 * root_pi) * eta_unit;
        const double lambda0 = 1.025218 * 75.0 / (64.0 * root_pi) * lambda_unit;
        c.diffusion = 1.018954 * 3.0 / (8.0 * root_pi) * d_unit / chi;
        c.shear_viscosity = eta0 / chi * (1.0 + 0.8 * y + 0.7615 * y * y);
        c.thermal_conductivity = lambda0 / chi * (1.0 + 1.2 * y + 0.7575 * y * y);
        c.bulk_viscosity = 4.0 / 9.0 * root_pi * (n * sd) * (n * sd) * chi * eta_unit;
    }
    return c;
}

// The diffusion coefficient of an infinite system from that of a cubic periodic box of
// edge L (Yeh & Hummer, J. Phys. Chem. B 108, 15873 (2004)): D + 2.837297 T / (6 pi eta L).
inline double yeh_hummer(double d_box, double T, double shear_viscosity, double L) {
    return d_box + 2.837297 * T / (6.0 * std::numbers::pi * shear_viscosity * L);
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
