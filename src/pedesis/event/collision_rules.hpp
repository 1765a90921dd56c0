#pragma once
// Momentum exchange of smooth hard particles along the line of centres, with a
// normal restitution coefficient xi. Inverse masses let one partner be immovable.
#include "pedesis/core/vec.hpp"

namespace pedesis {

struct PairImpulse {
    double impulse;       // J >= 0, momentum given to particle i along n
    double energy_change; // <= 0
};

// n: unit vector from j to i at contact; vi, vj updated in place.
template <int D>
inline PairImpulse collide_pair(Vec<D>& vi, Vec<D>& vj, const Vec<D>& n, double inv_mi,
                                double inv_mj, double xi) {
    const double inv_sum = inv_mi + inv_mj;
    if (inv_sum == 0.0) return {0.0, 0.0};
    const double mu = 1.0 / inv_sum;
    const double g = dot(vi - vj, n); // < 0 when approaching
    const double J = -(1.0 + xi) * mu * g;
    vi += (J * inv_mi) * n;
    vj -= (J * inv_mj) * n;
    return {J, -0.5 * (1.0 - xi * xi) * mu * g * g};
}

// As collide_pair for surfaces that move apart at surface_speed (growing particles,
// Lubachevsky-Stillinger): the gap's closing speed g - surface_speed is reversed and
// scaled by xi, so the energy may rise.
template <int D>
inline PairImpulse collide_growing_pair(Vec<D>& vi, Vec<D>& vj, const Vec<D>& n, double inv_mi,
                                        double inv_mj, double xi, double surface_speed) {
    const double mu = 1.0 / (inv_mi + inv_mj);
    const double g = dot(vi - vj, n);
    const double J = -(1.0 + xi) * mu * (g - surface_speed);
    vi += (J * inv_mi) * n;
    vj -= (J * inv_mj) * n;
    return {J, J * g + 0.5 * J * J / mu};
}

// Reflects the normal velocity component off a wall: v -> -xi v. Returns the
// momentum given to the wall, m (1 + xi) |v|.
inline double collide_wall(double& v, double mass, double xi) {
    const double transferred = mass * (1.0 + xi) * (v > 0 ? v : -v);
    v = -xi * v;
    return transferred;
}

// As collide_wall for a particle whose surface moves toward the wall at surface_speed
// in the direction of `outward` (+1 for the wall at hi, -1 at lo) on top of v. Returns
// the momentum given to the wall.
inline double collide_growing_wall(double& v, double mass, double xi, double surface_speed,
                                   double outward) {
    const double before = v;
    const double closing = v + outward * surface_speed; // along the wall's outward axis
    v = -xi * closing - outward * surface_speed;
    const double transferred = mass * (before - v);
    return transferred > 0 ? transferred : -transferred;
}

} // namespace pedesis
