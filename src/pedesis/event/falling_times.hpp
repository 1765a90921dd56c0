#pragma once
// Event times of particles in uniform gravity (parabolic flights). Two particles fall
// alike, so a pair's relative motion stays linear and pair times are prediction.hpp's;
// what changes is a particle's distance to a wall and to its neighbour-list centre.
// Each function returns the time from "now" until the event, or +infinity.
#include "pedesis/core/vec.hpp"
#include "pedesis/event/prediction.hpp"

#include <cmath>

namespace pedesis {

// When a gap s(t) = s + w t + a t^2 / 2 (to a wall: s the distance of the centre from its
// contact plane, w its rate of change, a the acceleration along the gap) first closes
// while closing. Roots come from the stable pair q = -(w + sgn(w) sqrt(w^2 - 2 a s)) / 2,
// t = q / (a / 2) or s / q, so that a small root is never the difference of two large
// numbers. A particle at contact or past it by rounding (s <= 0) collides now if it
// approaches, and otherwise when it comes back to the plane: a particle that rests or
// bounces on a floor can then never tunnel through it.
inline double falling_gap_time(double s, double w, double a) {
    if (s <= 0.0) {
        if (w < 0.0 || (w == 0.0 && a < 0.0)) return 0.0;
        return a < 0.0 ? -2.0 * w / a : never;
    }
    if (a == 0.0) return w < 0.0 ? -s / w : never;
    const double disc = w * w - 2.0 * a * s;
    if (a > 0.0) {
        // pulled away from the wall: only an approach fast enough reaches it (smaller root)
        if (w >= 0.0 || disc < 0.0) return never;
        return 2.0 * s / (-w + std::sqrt(disc));
    }
    // pulled towards it (disc > w^2): the one positive root
    if (w >= 0.0) return (w + std::sqrt(disc)) / -a;
    return 2.0 * s / (-w + std::sqrt(disc));
}

// A particle at coordinate x, velocity v and acceleration g along an axis walled at lo
// and hi, radius rad: the time it meets either wall; `upper` tells which.
inline double falling_wall_time(double x, double v, double g, double lo, double hi, double rad,
                                bool& upper) {
    const double t_lo = falling_gap_time(x - (lo + rad), v, g);
    const double t_hi = falling_gap_time((hi - rad) - x, -v, -g);
    upper = t_hi < t_lo;
    return upper ? t_hi : t_lo;
}

// A lower bound on when a particle displaced d from its list centre, with velocity v and
// acceleration g, reaches distance `radius` from it: the bound |d| + |v| t + |g| t^2 / 2
// reaches it first (the exact time is a root of a quartic). The lists stay exact since
// the particle is relisted no later than it could leave.
template <int D>
inline double falling_shell_exit_time(const Vec<D>& d, const Vec<D>& v, const Vec<D>& g,
                                      double radius) {
    const double room = radius - norm(d);
    if (!(room > 0.0)) return 0.0;
    const double speed = norm(v), accel = norm(g);
    if (speed == 0.0 && accel == 0.0) return never;
    return 2.0 * room / (speed + std::sqrt(speed * speed + 2.0 * accel * room));
}

} // namespace pedesis
