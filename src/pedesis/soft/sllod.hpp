#pragma once
// The SLLOD equations of Lees-Edwards shear at rate g (core/box.hpp), for the inertial
// integrators (velocity_verlet.hpp, langevin.hpp): with the velocities v peculiar (relative
// to the streaming velocity g y along x),
//   dr/dt = v + g y e_x,   dv/dt = F/m - g v_y e_x.
// Each integrator keeps its splitting; its parts are the exact flows of these pieces:
//   kick  (forces fixed): v_y moves linearly, so over h
//         v_y' = v_y + h F_y/m,   v_x' = v_x + h F_x/m - g h (v_y + v_y') / 2;
//   drift (velocities fixed): y moves linearly, so over h
//         y' = y + h v_y,         x' = x + h v_x + g h (y + y') / 2.
// A thermostat's friction and noise act on the peculiar velocity.
#include "pedesis/core/chunk_shares.hpp"
#include "pedesis/soft/batch_normals.hpp"
#include "pedesis/soft/blow_up.hpp"
#include "pedesis/soft/soft_state.hpp"

#include <cstdint>
#include <limits>
#include <string>
#include <vector>

namespace pedesis::detail {

// The kick over h: kick = h / m (0 for an infinite mass, which then keeps its velocity),
// g_h = g h.
template <int D> inline Vec<D> sllod_kick_one(Vec<D> v, const Vec<D>& f, double kick, double g_h) {
    const double vy = v[1];
    v += kick * f;
    if (kick > 0.0) v[0] -= g_h * 0.5 * (vy + v[1]);
    return v;
}

// The drift over h of a particle at height y: the displacement (h = 0: none, the fixed
// obstacle of an infinite mass).
template <int D> inline Vec<D> sllod_drift_one(const Vec<D>& v, double y, double h, double g) {
    Vec<D> m = h * v;
    m[0] += g * h * (y + 0.5 * m[1]);
    return m;
}

// Velocity Verlet's pre-step under shear: a kick of dt/2 and a drift of dt, per species
// kick = dt / (2 m) and drift = dt (both 0 for an infinite mass); every displacement,
// streaming included, within max_move.
template <int D>
void sllod_kick_drift(SoftState<D>& s, const std::vector<double>& kick,
                      const std::vector<double>& drift, double dt, double max_move,
                      const std::string& who) {
    const double g = s.box.shear_rate(), g_h = 0.5 * dt * g;
    const std::uint16_t* sp = s.p.species.data();
    const Vec<D>* force = s.force.data();
    Vec<D>* pos = s.p.position.data();
    Vec<D>* vel = s.p.velocity.data();
    const auto n = static_cast<std::int64_t>(s.owned());
    const double max2 = max_move * max_move;
    FirstBadMove<D> bad;
    parallel_for_each_batch(n, s.thread_shares, [&](std::int64_t first, int m) {
        FirstBadMove<D> batch_bad;
        for (std::int64_t i = first; i < first + m; ++i) {
            vel[i] = sllod_kick_one(vel[i], force[i], kick[sp[i]], g_h);
            const Vec<D> move = sllod_drift_one(vel[i], pos[i][1], drift[sp[i]], g);
            if (!(norm2(move) <= max2)) batch_bad.note(i, move);
            pos[i] += move;
        }
        batch_bad.merge_into(bad);
    });
    if (bad.any()) throw_bad_move(s, static_cast<std::size_t>(bad.index), bad.move, max_move, who);
}

// The closing kick of dt/2 (kick = dt / (2 m) per species).
template <int D> void sllod_kick(SoftState<D>& s, const std::vector<double>& kick, double dt) {
    const double g_h = 0.5 * dt * s.box.shear_rate();
    const std::uint16_t* sp = s.p.species.data();
    const Vec<D>* force = s.force.data();
    Vec<D>* vel = s.p.velocity.data();
    parallel_for_each_index(
        static_cast<std::int64_t>(s.owned()), s.thread_shares,
        [&](std::int64_t i) { vel[i] = sllod_kick_one(vel[i], force[i], kick[sp[i]], g_h); });
}

} // namespace pedesis::detail
