#pragma once
// How long ago two overlapping particles in uniform motion first touched: the quadratic
// formula of seed 002. Going back a time tau, the separation is dr - dv tau, and contact
// means |dr - dv tau| = sigma:
//     dv^2 tau^2 - 2 b tau + (r^2 - sigma^2) = 0,   b = dr . dv.
// With r < sigma the roots have opposite signs; the positive one is the moment the pair
// entered the overlap. Seed 002 assumes an approaching pair (b < 0), but the same root
// holds for a pair that is already separating again at the end of the step (b > 0):
// it too collided during the step, more than halfway through its overlap.
#include "pedesis/core/vec.hpp"

#include <cmath>

namespace pedesis {

// dr = r_i - r_j and dv = v_i - v_j now, contact distance sigma, |dr| < sigma.
// Returns tau >= 0, or a negative number when the pair does not move relative to itself
// (dv = 0: an overlap that was never entered).
template <int D>
inline double contact_rewind_time(const Vec<D>& dr, const Vec<D>& dv, double sigma) {
    const double v2 = norm2(dv);
    if (v2 == 0.0) return -1.0;
    const double b = dot(dr, dv);
    const double depth = sigma * sigma - norm2(dr); // > 0 inside the overlap
    const double root = std::sqrt(b * b + v2 * depth);
    // the two algebraically equal forms, each free of cancellation for its sign of b
    return b >= 0.0 ? (b + root) / v2 : depth / (root - b);
}

} // namespace pedesis
