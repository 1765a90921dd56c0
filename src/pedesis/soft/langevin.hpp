#pragma once
// Underdamped Langevin dynamics (the `langevin` engine),
//   dr = v dt,  m dv = F dt - gamma v dt + sqrt(2 gamma T) dW,
// integrated with the BAOAB splitting of Leimkuhler & Matthews:
//   pre-step:  B  v += (dt/2) F/m
//              A  r += (dt/2) v
//              O  v  = c1 v + sqrt((1 - c1^2) T/m) xi,   c1 = exp(-gamma dt/m)
//              A  r += (dt/2) v
//   post-step: B  v += (dt/2) F/m   (F of the new positions)
// The O step solves the Ornstein-Uhlenbeck part exactly, so free particles have exactly
// the Maxwell-Boltzmann velocity distribution for any dt, and BAOAB's configurational
// sampling error is O(dt^2) with a small constant. The noise of particle i at step s is
// drawn from Philox keyed by (seed, thermostat, tag, s): the trajectory does not depend
// on thread count or storage order. xi is a standard normal, or with uniform_noise a
// uniform variate of the same variance (batch_normals.hpp). A particle of infinite mass
// is a fixed obstacle.
// Under Lees-Edwards shear the velocities are peculiar, B and A are SLLOD's exact flows
// (sllod.hpp), and O, the thermostat, acts on the peculiar velocity.
#include "pedesis/core/chunk_shares.hpp"
#include "pedesis/core/error.hpp"
#include "pedesis/core/rng.hpp"
#include "pedesis/soft/batch_normals.hpp"
#include "pedesis/soft/blow_up.hpp"
#include "pedesis/soft/per_species.hpp"
#include "pedesis/soft/plugins.hpp"
#include "pedesis/soft/sllod.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <string>
#include <vector>

namespace pedesis {

namespace detail {

// BAOAB coefficients of one step, per species, so that the particle loop only indexes
// small tables.
struct LangevinCoefficients {
    std::vector<double> kick;       // dt / (2 m)
    std::vector<double> half_drift; // dt / 2, or 0 for an infinite mass
    std::vector<double> damp;       // c1 = exp(-gamma dt / m)
    std::vector<double> noise;      // sqrt((1 - c1^2) T / m)
    bool noisy = false;

    void update(const PerSpecies& T, const PerSpecies& gamma, const std::vector<Species>& table,
                double dt) {
        const std::size_t n = table.size();
        kick.resize(n);
        half_drift.resize(n);
        damp.resize(n);
        noise.resize(n);
        noisy = false;
        for (std::size_t k = 0; k < n; ++k) {
            const double inv_m = table[k].inverse_mass();
            const double x = gamma.at(k, n) * dt * inv_m;
            kick[k] = 0.5 * dt * inv_m;
            half_drift[k] = std::isinf(table[k].mass) ? 0.0 : 0.5 * dt;
            damp[k] = std::exp(-x);
            // 1 - c1^2 by expm1: for gamma dt / m ~ 1e-8 the plain difference loses half
            // its digits
            noise[k] = std::sqrt(-std::expm1(-2.0 * x) * T.at(k, n) * inv_m);
            noisy = noisy || noise[k] > 0.0;
        }
    }
};

// BAOAB's A O A for one particle of species k: v becomes the O step's velocity; returns
// the move. z: its D normals, or null without noise. (Also the barostat's, barostat.hpp.)
template <int D>
inline Vec<D> langevin_aoa(Vec<D>& v, const LangevinCoefficients& c, std::uint16_t k,
                           const double* z) {
    Vec<D> move = c.half_drift[k] * v;
    v *= c.damp[k];
    if (z)
        for (int a = 0; a < D; ++a) v[a] += c.noise[k] * z[a];
    move += c.half_drift[k] * v;
    return move;
}

} // namespace detail

template <int D> class LangevinIntegrator final : public Integrator<D> {
  public:
    LangevinIntegrator(PerSpecies T, PerSpecies gamma, std::uint64_t seed,
                       detail::NoiseShape noise = detail::NoiseShape::gaussian)
        : T_(std::move(T)), gamma_(std::move(gamma)), seed_(seed), noise_(noise) {
        for (double t : T_.values())
            if (!(t >= 0.0 && std::isfinite(t)))
                throw InputError("langevin: T must be a finite number >= 0");
        for (double g : gamma_.values())
            if (!(g > 0.0 && std::isfinite(g)))
                throw InputError("langevin: gamma must be a positive finite number");
    }
    std::string name() const override { return "langevin"; }
    double bath_temperature(std::size_t s, std::size_t count) const override {
        return T_.at(s, count);
    }
    double friction(std::size_t s, std::size_t count) const override { return gamma_.at(s, count); }
    // the first B half-kick reads the forces of the positions the step starts from
    bool needs_initial_forces() const override { return true; }
    const PerSpecies& temperature() const { return T_; }
    const PerSpecies& gamma() const { return gamma_; }
    std::uint64_t seed() const { return seed_; }
    detail::NoiseShape noise_shape() const { return noise_; }
    // From the next step on (the coefficients are made from T every step).
    void set_temperature(PerSpecies T) {
        for (double t : T.values())
            if (!(t >= 0.0 && std::isfinite(t)))
                throw InputError("langevin: T must be a finite number >= 0");
        T_ = std::move(T);
    }

    void prestep(SoftState<D>& s, double dt, double max_move) override {
        c_.update(T_, gamma_, s.p.species_table, dt);
        const double* kick = c_.kick.data();
        const double* half_drift = c_.half_drift.data();
        const double* damp = c_.damp.data();
        const double* noise = c_.noise.data();
        const bool noisy = c_.noisy;
        const std::uint16_t* sp = s.p.species.data();
        const std::uint32_t* tag = s.p.tag.data();
        const Vec<D>* force = s.force.data();
        Vec<D>* pos = s.p.position.data();
        Vec<D>* vel = s.p.velocity.data();
        const auto n = static_cast<std::int64_t>(s.owned());
        const auto step = static_cast<std::uint32_t>(s.step);
        const double max2 = max_move * max_move;
        const bool sheared = s.box.sheared();
        const double g = s.box.shear_rate(), g_h = 0.5 * dt * g;
        // The move of the lowest bad index is kept for the message: after the O step the
        // velocities no longer tell what it was.
        detail::FirstBadMove<D> bad;
        // Batches of particles: their normals are drawn together (batch_normals), the
        // same numbers as one particle at a time, several at once.
        detail::parallel_for_each_batch(n, s.thread_shares, [&](std::int64_t first, int m) {
            detail::FirstBadMove<D> batch_bad;
            double z[detail::noise_batch * D];
            if (noisy)
                detail::batch_noise<D>(noise_, seed_, RngStream::thermostat, tag + first, step, m,
                                       z);
            if (sheared) {
                for (int q = 0; q < m; ++q) {
                    const std::int64_t i = first + q;
                    const std::uint16_t k = sp[i];
                    Vec<D> v = detail::sllod_kick_one(vel[i], force[i], kick[k], g_h);
                    Vec<D> move = detail::sllod_drift_one(v, pos[i][1], half_drift[k], g);
                    v *= damp[k];
                    if (noisy)
                        for (int a = 0; a < D; ++a) v[a] += noise[k] * z[q * D + a];
                    move += detail::sllod_drift_one(v, pos[i][1] + move[1], half_drift[k], g);
                    if (!(norm2(move) <= max2)) batch_bad.note(i, move);
                    pos[i] += move;
                    vel[i] = v;
                }
                batch_bad.merge_into(bad);
                return;
            }
            for (int q = 0; q < m; ++q) {
                const std::int64_t i = first + q;
                const std::uint16_t k = sp[i];
                Vec<D> v = vel[i] + kick[k] * force[i];
                const Vec<D> move = detail::langevin_aoa(v, c_, k, noisy ? z + q * D : nullptr);
                if (!(norm2(move) <= max2)) batch_bad.note(i, move);
                pos[i] += move;
                vel[i] = v;
            }
            batch_bad.merge_into(bad);
        });
        if (bad.any())
            detail::throw_bad_move(s, static_cast<std::size_t>(bad.index), bad.move, max_move,
                                   name());
    }

    void poststep(SoftState<D>& s, double dt, double) override {
        // one entry per species: cheap, and the post-step then relies on no pre-step state
        c_.update(T_, gamma_, s.p.species_table, dt);
        const double* kick = c_.kick.data();
        const std::uint16_t* sp = s.p.species.data();
        const Vec<D>* force = s.force.data();
        Vec<D>* vel = s.p.velocity.data();
        const auto n = static_cast<std::int64_t>(s.owned());
        if (s.box.sheared()) {
            detail::sllod_kick(s, c_.kick, dt);
            return;
        }
        parallel_for_each_index(n, s.thread_shares,
                                [&](std::int64_t i) { vel[i] += kick[sp[i]] * force[i]; });
    }

  private:
    PerSpecies T_, gamma_;
    std::uint64_t seed_;
    detail::NoiseShape noise_;
    detail::LangevinCoefficients c_;
};

} // namespace pedesis
