#pragma once
// The rotational Brownian step of a director n in 3D, shared by the CPU integrator
// (soft/brownian.hpp) and the GPU kernel (gpu/device_system.cu).
//
// The angular displacement w = dt tau / gamma + k xi (xi three standard normals) turns n
// about the axis of its part normal to n, w_perp, by the angle |w_perp| (Rodrigues:
// n' = n cos|w_perp| + (w_perp x n) sin|w_perp| / |w_perp|): a rotation, which keeps |n|
// = 1 and moves n along the great circle. The earlier step, n += w x n then
// renormalised, turned n by atan|w_perp| instead and decorrelated it about 5 D_r dt too
// slowly.
//
// The noise amplitude k is sqrt(2 D_r dt) times sphere_kick_scale: with a = D_r dt, the
// angle |k xi_perp| then has E[theta^2] = 4a - (4/3) a^2 and E[theta^4] = 32 a^2 + O(a^3),
// the moments the heat kernel on the sphere asks of a step to second order: every
// Legendre mode decays as exp(-l (l + 1) a) up to O(a^3) per step (<n.n0> = e^{-2a},
// <P2> = e^{-6a}), where the unscaled angle gives e^{-2a} + (2/3) a^2 for the first. The
// torque's part is Euler's, first order, as the translational step.
#include "pedesis/core/host_device.hpp"
#include "pedesis/core/sincos.hpp"

#include <cmath>

namespace pedesis {

// The factor on sqrt(2 D_r dt) for a noise amplitude `kick` = sqrt(2 D_r dt):
// sqrt(1 - D_r dt / 3). Past D_r dt = 1.5, where one step all but forgets the director
// anyway, it stays at sqrt(1/2).
PEDESIS_HD inline double sphere_kick_scale(double kick) {
    const double a = 0.5 * kick * kick;
    return std::sqrt(1.0 - (a < 1.5 ? a : 1.5) / 3.0);
}

// Turns the unit vector n (n[0..2]) by the angular displacement w, as above.
template <class V> PEDESIS_HD inline void rotate_on_sphere(const double w[3], V& n) {
    const double along = w[0] * n[0] + w[1] * n[1] + w[2] * n[2];
    const double p0 = w[0] - along * n[0], p1 = w[1] - along * n[1], p2 = w[2] - along * n[2];
    const double angle = std::sqrt(p0 * p0 + p1 * p1 + p2 * p2);
    if (angle == 0.0) return; // (a NaN goes on through, for the run's checks to find)
    double s, c;
    if (angle <= 0.7853981633974483) // pi/4: the polynomials; libm the rare rest
        detail::sincos_kernel(angle, s, c);
    else {
        s = std::sin(angle);
        c = std::cos(angle);
    }
    const double f = s / angle;
    const double x0 = p1 * n[2] - p2 * n[1];
    const double x1 = p2 * n[0] - p0 * n[2];
    const double x2 = p0 * n[1] - p1 * n[0];
    const double m0 = c * n[0] + f * x0, m1 = c * n[1] + f * x1, m2 = c * n[2] + f * x2;
    // one Newton step back to |n| = 1 against the rounding of many steps
    const double fix = 1.5 - 0.5 * (m0 * m0 + m1 * m1 + m2 * m2);
    n[0] = m0 * fix;
    n[1] = m1 * fix;
    n[2] = m2 * fix;
}

} // namespace pedesis
