#pragma once
// The running integrals behind the Helfand (Einstein) moments of hard particles, from
// which shear and bulk viscosity and heat conduction follow (run/transport_*):
//
//   G_ab(t) = V ∫ P_ab dt = ∫ Σ_i m v_a v_b dt + Σ_collisions r_ij,a Δp_i,b
//   H_a(t)  = ∫ J_q,a dt  = ∫ Σ_i v_i,a e_i dt  + Σ_collisions r_ij,a ΔE_i
//
// with e_i = m_i v_i² / 2, r_ij = r_i − r_j the contact vector (minimum image) and Δp_i,
// ΔE_i what particle i gained. The collisional parts use the contact vector, never
// unwrapped positions: Σ_i x_i p_i of unwrapped positions jumps whenever a particle
// crosses the box (the periodic-boundary trap). The collision virial Σ J n_a r_ij,b of
// EventCounters is G's collisional part; the rest is here. Between collisions the
// velocities are constant, so the kinetic integrals are exact sums of rectangles.
#include "pedesis/core/sym_tensor.hpp"
#include "pedesis/core/vec.hpp"

namespace pedesis {

template <int D> struct FluxMoments {
    double t = 0.0;               // the time the integrals reach
    SymTensor kinetic{};          // Σ m v_a v_b now
    SymTensor kinetic_integral{}; // ∫ Σ m v_a v_b dt up to t
    Vec<D> heat{};                // Σ v_i e_i now
    Vec<D> heat_integral{};       // ∫ Σ v_i e_i dt up to t
    Vec<D> heat_collisional{};    // Σ over collisions r_ij ΔE_i

    // Carries the integrals from t to `now` (velocities unchanged in between).
    void advance(double now) {
        const double dt = now - t;
        for (int c = 0; c < 6; ++c) kinetic_integral[c] += kinetic[c] * dt;
        heat_integral += heat * dt;
        t = now;
    }
    // Under Lees-Edwards shear at `rate` (the event engine), `kinetic` sums peculiar
    // velocities c = v - rate y e_x, and in free flight dc_x/dt = -rate c_y: so
    // d/dt Σ m c_x c_y = -rate Σ m c_y², d/dt Σ m c_x c_z = -rate Σ m c_y c_z,
    // d/dt Σ m c_x² = -2 rate Σ m c_x c_y, the rest constant. The integrals are exact
    // polynomials in dt. (The heat sums are not kept under shear.)
    void advance_sheared(double now, double rate) {
        const double dt = now - t, g = rate;
        const double xx = kinetic[0], yy = kinetic[1], xy = kinetic[3], yz = kinetic[5];
        for (int c = 0; c < 6; ++c) kinetic_integral[c] += kinetic[c] * dt;
        kinetic_integral[0] += -g * xy * dt * dt + g * g * yy * dt * dt * dt / 3.0;
        kinetic_integral[3] += -0.5 * g * yy * dt * dt;
        kinetic_integral[4] += -0.5 * g * yz * dt * dt;
        kinetic[0] = xx - 2.0 * g * xy * dt + g * g * yy * dt * dt;
        kinetic[3] = xy - g * yy * dt;
        kinetic[4] -= g * yz * dt;
        t = now;
    }
    // A particle of mass m with velocity v enters (sign +1) or leaves (−1) the sums.
    void count(double m, const Vec<D>& v, double sign) {
        add_sym_outer<D>(kinetic, v, v, sign * m);
        heat += v * (sign * 0.5 * m * norm2(v));
    }
    // A collision at the current t: i's velocity went from vi0 to vi, j's from vj0 to vj.
    void collision(double mi, const Vec<D>& vi0, const Vec<D>& vi, double mj, const Vec<D>& vj0,
                   const Vec<D>& vj, const Vec<D>& r_ij) {
        count(mi, vi0, -1.0);
        count(mj, vj0, -1.0);
        count(mi, vi, 1.0);
        count(mj, vj, 1.0);
        heat_collisional += r_ij * (0.5 * mi * (norm2(vi) - norm2(vi0)));
    }
};

} // namespace pedesis
