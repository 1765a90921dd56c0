#pragma once
// Exact collision times for particles in free flight. All functions return the
// time from "now" until the event, or +infinity when there is none.
#include "pedesis/core/vec.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace pedesis {

inline constexpr double never = std::numeric_limits<double>::infinity();

// Pair at separation dr (r_i - r_j, minimum image) with relative velocity dv,
// contact distance sigma. Only approaching pairs collide. The root is written as
// c / (-b + sqrt(disc)) to avoid cancellation; a pair that already overlaps by a
// rounding error and approaches collides at once (returns 0).
template <int D>
inline double pair_collision_time(const Vec<D>& dr, const Vec<D>& dv, double sigma) {
    const double b = dot(dr, dv);
    if (b >= 0.0) return never;
    const double dv2 = norm2(dv);
    const double c = norm2(dr) - sigma * sigma;
    const double disc = b * b - dv2 * c;
    if (disc <= 0.0) return never;
    const double t = c / (-b + std::sqrt(disc));
    return t > 0.0 ? t : 0.0;
}

// As above, but returns `never` without a square root when the collision cannot
// come before `bound`: for c >= 0 the time is at least c / (-2b).
template <int D>
inline double pair_collision_time_before(const Vec<D>& dr, const Vec<D>& dv, double sigma,
                                         double bound) {
    const double b = dot(dr, dv);
    if (b >= 0.0) return never;
    const double c = norm2(dr) - sigma * sigma;
    if (c > -2.0 * b * bound) return never;
    const double disc = b * b - norm2(dv) * c;
    if (disc <= 0.0) return never;
    const double t = c / (-b + std::sqrt(disc));
    return t > 0.0 ? t : 0.0;
}

// Pair whose contact distance grows: sigma now, sigma_rate = d sigma / dt >= 0
// (Lubachevsky-Stillinger). The gap closes when |dr + dv t| = sigma + sigma_rate t, a
// quadratic a t^2 + 2 b t + c = 0 with a = dv^2 - rate^2, which has a root even for
// receding pairs once the growth outruns them (a < 0). An overlap by a rounding error
// counts as contact.
template <int D>
inline double growing_pair_collision_time(const Vec<D>& dr, const Vec<D>& dv, double sigma,
                                          double sigma_rate) {
    const double b = dot(dr, dv) - sigma * sigma_rate;
    const double a = norm2(dv) - sigma_rate * sigma_rate;
    const double c = std::max(norm2(dr) - sigma * sigma, 0.0);
    if (b < 0.0) {
        const double disc = b * b - a * c;
        if (disc <= 0.0) return never;
        return c / (-b + std::sqrt(disc));
    }
    if (a >= 0.0) return never;
    return (-b - std::sqrt(b * b - a * c)) / a;
}

// Particle at coordinate x with velocity v between walls at lo and hi, radius rad.
inline double wall_collision_time(double x, double v, double lo, double hi, double rad) {
    double t;
    if (v > 0.0)
        t = (hi - rad - x) / v;
    else if (v < 0.0)
        t = (lo + rad - x) / v;
    else
        return never;
    return t > 0.0 ? t : 0.0;
}

// As wall_collision_time for a radius growing at rad_rate: both walls may come
// first. Sets `upper` to whether the wall hit is the one at hi.
inline double growing_wall_collision_time(double x, double v, double lo, double hi, double rad,
                                          double rad_rate, bool& upper) {
    double t_hi = never, t_lo = never;
    if (v + rad_rate > 0.0) t_hi = std::max((hi - rad - x) / (v + rad_rate), 0.0);
    if (v - rad_rate < 0.0) t_lo = std::max((lo + rad - x) / (v - rad_rate), 0.0);
    upper = t_hi < t_lo;
    return upper ? t_hi : t_lo;
}

// Time at which a particle displaced d from its neighbour-list centre, moving with
// v, reaches distance `radius` from the centre (the larger root).
template <int D> inline double shell_exit_time(const Vec<D>& d, const Vec<D>& v, double radius) {
    const double a = norm2(v);
    if (a == 0.0) return never;
    const double b = dot(d, v);
    const double c = norm2(d) - radius * radius;
    if (c >= 0.0) return 0.0;
    const double disc = b * b - a * c;
    return (-b + std::sqrt(disc)) / a;
}

} // namespace pedesis
