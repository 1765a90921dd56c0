#pragma once
// Pair evaluators: tiny structs with their parameters and one function giving, for a
// pair at squared distance r2 with radii summing to rsum, the force divided by r and
// the energy. The pair loop (pair_loop.hpp) is written once for all of them; adding a
// potential is one struct here and one line in the registry.
#include <cmath>

namespace pedesis {

// Harmonic repulsion of the ABP tutorial: F = k (a - r) r_hat for r <= a,
// U = k (a - r)^2 / 2. With a <= 0 the range is the contact distance r_i + r_j.
struct HarmonicPair {
    double k = 10.0;
    double a = -1.0;

    double range(double rsum) const { return a > 0.0 ? a : rsum; }
    double max_range(double max_rsum) const { return range(max_rsum); }
    bool eval(double r2, double rsum, double& f_over_r, double& energy) const {
        const double R = range(rsum);
        if (r2 >= R * R) return false;
        const double r = std::sqrt(r2);
        const double overlap = R - r;
        f_over_r = k * overlap / r;
        energy = 0.5 * k * overlap * overlap;
        return true;
    }
};

// Weeks-Chandler-Andersen: Lennard-Jones cut at its minimum 2^(1/6) sigma and shifted
// to zero there, purely repulsive. With sigma <= 0, sigma = r_i + r_j.
struct WcaPair {
    double epsilon = 1.0;
    double sigma = -1.0;

    double sig(double rsum) const { return sigma > 0.0 ? sigma : rsum; }
    double max_range(double max_rsum) const { return std::pow(2.0, 1.0 / 6.0) * sig(max_rsum); }
    bool eval(double r2, double rsum, double& f_over_r, double& energy) const {
        const double s = sig(rsum);
        const double s2 = s * s;
        if (r2 >= std::pow(2.0, 1.0 / 3.0) * s2) return false;
        const double x2 = s2 / r2;
        const double x6 = x2 * x2 * x2;
        f_over_r = 24.0 * epsilon * (2.0 * x6 * x6 - x6) / r2;
        energy = 4.0 * epsilon * (x6 * x6 - x6) + epsilon;
        return true;
    }
};

} // namespace pedesis
