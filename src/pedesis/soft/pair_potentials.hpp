#pragma once
// Pair evaluators: tiny structs with their parameters and two functions: eval gives,
// for a pair at squared distance r2 with radii summing to rsum, whether it interacts,
// the force divided by r and the energy; force_over_r gives the force alone, without a
// branch, for pairs already known to lie in range (the pair loop's vectorisable part). The pair
// loop (pair_force.hpp) is written once for all of them; adding a potential is one struct here and
// one line in the registry.
#include "pedesis/core/host_device.hpp"

#include <cmath>
#include <type_traits>
#include <utility>

namespace pedesis {

// The evaluators are shared with the CUDA kernels (src/pedesis/gpu/): what a kernel calls
// is PEDESIS_HD, and the header stays C++17.

// The real type of T: T itself for a scalar, the element type of a SIMD vector. The
// evaluators' parameters are doubles and enter the arithmetic converted to it, so that
// the mixed-precision rows (soft/pair_rows_mixed.hpp) compute in float throughout; for
// double the conversions are nothing and the bits are those of the plain expressions.
template <class T, class = void> struct real_of { using type = T; };
template <class T> struct real_of<T, std::void_t<decltype(std::declval<T>()[0])>> {
    using type = std::decay_t<decltype(std::declval<T>()[0])>;
};
template <class T> using real_of_t = typename real_of<T>::type;

// Lennard-Jones F/r = 24 eps (2 (s/r)^12 - (s/r)^6) / r^2, shared by wca and lj. One
// division per pair (s^2 / r^2, then products): divisions are the slowest operation of
// the pair loop. 24 eps / r^2 comes from (s/r)^2 beside (s/r)^4, so that four operations,
// not seven, follow the division on the SIMD kernels' critical path (in.lj 1.05x).
// T is double, or a vector of doubles or floats in the CPU's SIMD kernels
// (soft/pair_rows.hpp, soft/pair_rows_mixed.hpp).
template <class T> PEDESIS_HD_INLINE T lj_force_over_r(double epsilon, double s, T r2) {
    using R = real_of_t<T>;
    const double s2 = s * s;
    const T x2 = R(s2) / r2;
    const T x4 = x2 * x2;
    const T scale = R(24.0 * epsilon / s2) * x2; // 24 eps / r^2, beside x4
    const T x6 = x4 * x2;
    return (R(2.0) * x6 - R(1.0)) * (scale * x6);
}

// Harmonic repulsion of the ABP tutorial: F = k (a - r) r_hat for r <= a,
// U = k (a - r)^2 / 2. With a <= 0 the range is the contact distance r_i + r_j.
struct HarmonicPair {
    double k = 10.0;
    double a = -1.0;

    bool operator==(const HarmonicPair& o) const { return k == o.k && a == o.a; }
    PEDESIS_HD double range(double rsum) const { return a > 0.0 ? a : rsum; }
    double max_range(double max_rsum) const { return range(max_rsum); }
    // none: its force is bounded (k a at most), so harmonic particles may overlap, by
    // any amount and at any density, without a blow-up (what a blow-up's message
    // measures overlaps and the density against: soft/blow_up_cause.hpp)
    double core(double) const { return 0.0; }
    // F/r for a pair inside the range (the pair loop filters by range first)
    PEDESIS_HD double force_over_r(double r2, double rsum) const {
        return force_over_r_at(std::sqrt(r2), rsum);
    }
    // the same from the distance r (T: double or a SIMD vector of them)
    template <class T> PEDESIS_HD_INLINE T force_over_r_at(T r, double rsum) const {
        using R = real_of_t<T>;
        return R(k) * (R(range(rsum)) - r) / r;
    }
    PEDESIS_HD bool eval(double r2, double rsum, double& f_over_r, double& energy) const {
        const double R = range(rsum);
        if (r2 >= R * R) return false;
        const double overlap = R - std::sqrt(r2);
        f_over_r = force_over_r(r2, rsum);
        energy = 0.5 * k * overlap * overlap;
        return true;
    }
};

// Weeks-Chandler-Andersen: Lennard-Jones cut at its minimum 2^(1/6) sigma and shifted
// to zero there, purely repulsive. With sigma <= 0, sigma = r_i + r_j.
struct WcaPair {
    double epsilon = 1.0;
    double sigma = -1.0;

    bool operator==(const WcaPair& o) const { return epsilon == o.epsilon && sigma == o.sigma; }
    PEDESIS_HD double sig(double rsum) const { return sigma > 0.0 ? sigma : rsum; }
    double max_range(double max_rsum) const { return std::pow(2.0, 1.0 / 6.0) * sig(max_rsum); }
    double core(double rsum) const { return sig(rsum); }
    template <class T> PEDESIS_HD_INLINE T force_over_r(T r2, double rsum) const {
        return lj_force_over_r(epsilon, sig(rsum), r2);
    }
    PEDESIS_HD bool eval(double r2, double rsum, double& f_over_r, double& energy) const {
        const double s = sig(rsum);
        const double s2 = s * s;
        if (r2 >= std::pow(2.0, 1.0 / 3.0) * s2) return false;
        const double x2 = s2 * (1.0 / r2); // the division lj_force_over_r makes too
        const double x6 = x2 * x2 * x2;
        f_over_r = lj_force_over_r(epsilon, s, r2);
        energy = 4.0 * epsilon * (x6 * x6 - x6) + epsilon;
        return true;
    }
};

// Lennard-Jones cut at `cutoff` sigma (2.5 by default, as LAMMPS' in.lj). Not shifted by
// default, as LAMMPS' lj/cut without pair_modify shift: the energy jumps by
// U(r_c) ~ -0.016 eps at the cutoff, the force is continuous enough for NVE at in.lj's
// dt. With `shift` the energy has U(r_c) subtracted, so it is continuous (HOOMD-blue's
// mode "shift"); forces are the same. With sigma <= 0, sigma = r_i + r_j. With `tail`
// the totals (energy, pressure) get the homogeneous fluid's share beyond the cutoff, as
// LAMMPS' pair_modify tail yes; the forces do not change.
struct LjPair {
    double epsilon = 1.0;
    double sigma = -1.0;
    double cutoff = 2.5;
    bool shift = false;
    bool tail = false;

    bool operator==(const LjPair& o) const {
        return epsilon == o.epsilon && sigma == o.sigma && cutoff == o.cutoff && shift == o.shift &&
               tail == o.tail;
    }
    // With tail, {the integral of U over r > r_c, that of -r U'(r)}, each over the area
    // (2D: 2 pi r dr) or volume (3D: 4 pi r^2 dr) element; {0, 0} without. With c the
    // cutoff in sigma and S the sphere's area 2 pi or 4 pi:
    //   4 eps S sigma^D [c^(D-12) / (12 - D) - c^(D-6) / (6 - D)],
    //   4 eps S sigma^D [12 c^(D-12) / (12 - D) - 6 c^(D-6) / (6 - D)].
    template <int D> std::pair<double, double> tail_integrals(double rsum) const {
        if (!tail) return {0.0, 0.0};
        constexpr double pi = 3.141592653589793;
        const double sphere = D == 2 ? 2.0 * pi : 4.0 * pi;
        const double scale = 4.0 * epsilon * sphere * std::pow(sig(rsum), D);
        const double repulsive = std::pow(cutoff, D - 12) / (12 - D);
        const double attractive = std::pow(cutoff, D - 6) / (6 - D);
        return {scale * (repulsive - attractive), scale * (12.0 * repulsive - 6.0 * attractive)};
    }
    PEDESIS_HD double sig(double rsum) const { return sigma > 0.0 ? sigma : rsum; }
    double max_range(double max_rsum) const { return cutoff * sig(max_rsum); }
    double core(double rsum) const { return sig(rsum); }
    template <class T> PEDESIS_HD_INLINE T force_over_r(T r2, double rsum) const {
        return lj_force_over_r(epsilon, sig(rsum), r2);
    }
    PEDESIS_HD bool eval(double r2, double rsum, double& f_over_r, double& energy) const {
        const double s = sig(rsum);
        const double s2 = s * s;
        if (r2 >= cutoff * cutoff * s2) return false;
        const double x2 = s2 * (1.0 / r2); // the division lj_force_over_r makes too
        const double x6 = x2 * x2 * x2;
        f_over_r = lj_force_over_r(epsilon, s, r2);
        energy = 4.0 * epsilon * (x6 * x6 - x6);
        if (shift) {
            // U(r_c) = 4 eps (rc^-12 - rc^-6) in units of sigma, whatever sigma is
            const double c6 = 1.0 / (cutoff * cutoff * cutoff * cutoff * cutoff * cutoff);
            energy -= 4.0 * epsilon * (c6 * c6 - c6);
        }
        return true;
    }
};

} // namespace pedesis
