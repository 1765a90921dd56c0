#pragma once
// Overdamped integrators of the ABP tutorial, Euler-Maruyama:
//   brownian:          r += dt F / gamma + sqrt(2 T dt / gamma) xi
//   brownian_rotation: theta += dt tau / gamma + sqrt(2 T dt / gamma) xi  (2D),
//                      n turned by w = dt tau / gamma + sqrt(2 D_r dt) s xi about the
//                      axis of w's part normal to n, by its length (3D; the noise scaled
//                      by s = sqrt(1 - D_r dt / 3) for second order: core/sphere_rotation.hpp)
// with D = T / gamma. The noise of particle i at step s is drawn from Philox keyed by
// (seed, stream, tag, s): the trajectory does not depend on thread count or storage order.
// xi is a standard normal; brownian's, with uniform_noise, a uniform variate of the same
// variance (batch_normals.hpp).
// Under Lees-Edwards shear at rate g (core/box.hpp) the particles also stream with the
// flow: r += dt F / gamma + g y dt e_x + noise, y of the step's start; the velocity kept
// (move / dt) is the peculiar one, without the streaming.
#include "pedesis/core/error.hpp"
#include "pedesis/core/rng.hpp"
#include "pedesis/core/sphere_rotation.hpp"
#include "pedesis/soft/batch_normals.hpp"
#include "pedesis/soft/blow_up.hpp"
#include "pedesis/soft/per_species.hpp"
#include "pedesis/soft/plugins.hpp"
#include "pedesis/soft/polar_align.hpp"

#include <cmath>
#include <limits>
#include <numbers>

namespace pedesis {

namespace detail {

inline void check_overdamped(const PerSpecies& T, const PerSpecies& gamma, const char* who) {
    for (double t : T.values())
        if (!(t >= 0.0 && std::isfinite(t)))
            throw InputError(std::string(who) + ": T must be a finite number >= 0");
    for (double g : gamma.values())
        if (!(g > 0.0 && std::isfinite(g)))
            throw InputError(std::string(who) + ": gamma must be a positive finite number");
}

// Per-species Euler-Maruyama coefficients for one step: drift dt / gamma and noise
// amplitude sqrt(2 T dt / gamma).
struct OverdampedCoefficients {
    std::vector<double> drift, kick;
    bool noisy = false;
    void update(const PerSpecies& T, const PerSpecies& gamma, std::size_t n_species, double dt) {
        drift.resize(n_species);
        kick.resize(n_species);
        noisy = false;
        for (std::size_t s = 0; s < n_species; ++s) {
            const double g = gamma.at(s, n_species);
            drift[s] = dt / g;
            kick[s] = std::sqrt(2.0 * T.at(s, n_species) * dt / g);
            noisy = noisy || kick[s] > 0.0;
        }
    }
};
} // namespace detail

template <int D> class BrownianIntegrator final : public Integrator<D> {
  public:
    BrownianIntegrator(PerSpecies T, PerSpecies gamma, std::uint64_t seed,
                       detail::NoiseShape noise = detail::NoiseShape::gaussian)
        : T_(std::move(T)), gamma_(std::move(gamma)), seed_(seed), noise_(noise) {
        detail::check_overdamped(T_, gamma_, "brownian");
    }
    std::string name() const override { return "brownian"; }
    bool overdamped_positions() const override { return true; }
    double bath_temperature(std::size_t s, std::size_t count) const override {
        return T_.at(s, count);
    }
    double friction(std::size_t s, std::size_t count) const override { return gamma_.at(s, count); }
    const PerSpecies& temperature() const { return T_; }
    const PerSpecies& gamma() const { return gamma_; }
    std::uint64_t seed() const { return seed_; }
    detail::NoiseShape noise_shape() const { return noise_; }
    // From the next step on (the coefficients are made from T every step).
    void set_temperature(PerSpecies T) {
        detail::check_overdamped(T, gamma_, "brownian");
        T_ = std::move(T);
    }

    void poststep(SoftState<D>& s, double dt, double max_move) override {
        c_.update(T_, gamma_, s.p.species_table.size(), dt);
        const double* drift = c_.drift.data();
        const double* kick = c_.kick.data();
        const bool noisy = c_.noisy;
        const std::uint16_t* sp = s.p.species.data();
        const auto n = static_cast<std::int64_t>(s.owned());
        const auto step = static_cast<std::uint32_t>(s.step);
        const double max2 = max_move * max_move;
        const double stream = s.box.shear_rate() * dt; // 0 without shear
        detail::FirstBadMove<D> bad;
        detail::parallel_for_each_batch(n, s.thread_shares, [&](std::int64_t first, int m) {
            // (locals, not the captured references: the stores below cannot change them, so
            // the compiler loads them once, not once a particle)
            const Vec<D>* const force = s.force.data();
            Vec<D>* const position = s.p.position.data();
            Vec<D>* const velocity = s.p.velocity.data();
            const double inv_dt = 1.0 / dt, limit2 = max2;
            detail::FirstBadMove<D> batch_bad;
            double z[detail::noise_batch * D];
            if (noisy)
                detail::batch_noise<D>(noise_, seed_, RngStream::thermostat, s.p.tag.data() + first,
                                       step, m, z);
            else // (unread; filled so that no compiler takes it for uninitialised)
                std::fill_n(z, m * D, 0.0);
            if (stream > 0.0) {
                for (int k = 0; k < m; ++k) {
                    const std::int64_t i = first + k;
                    Vec<D> move = drift[sp[i]] * force[i];
                    if (noisy)
                        for (int a = 0; a < D; ++a) move[a] += kick[sp[i]] * z[k * D + a];
                    velocity[i] = move * inv_dt;
                    move[0] += stream * position[i][1];
                    if (!(norm2(move) <= limit2)) batch_bad.note(i, move);
                    position[i] += move;
                }
                batch_bad.merge_into(bad);
                return;
            }
            for (int k = 0; k < m; ++k) {
                const std::int64_t i = first + k;
                Vec<D> move = drift[sp[i]] * force[i];
                if (noisy)
                    for (int a = 0; a < D; ++a) move[a] += kick[sp[i]] * z[k * D + a];
                if (!(norm2(move) <= limit2)) batch_bad.note(i, move);
                position[i] += move;
                velocity[i] = move * inv_dt;
            }
            batch_bad.merge_into(bad);
        });
        if (bad.any())
            detail::throw_bad_move(s, static_cast<std::size_t>(bad.index), bad.move, max_move,
                                   name());
    }

  private:
    PerSpecies T_, gamma_;
    std::uint64_t seed_;
    detail::NoiseShape noise_;
    detail::OverdampedCoefficients c_;
};

template <int D> class BrownianRotationIntegrator final : public Integrator<D> {
  public:
    BrownianRotationIntegrator(PerSpecies T, PerSpecies gamma, std::uint64_t seed)
        : T_(std::move(T)), gamma_(std::move(gamma)), seed_(seed) {
        detail::check_overdamped(T_, gamma_, "brownian_rotation");
    }
    std::string name() const override { return "brownian_rotation"; }
    // D_r = T / gamma of species s among n
    double rotational_diffusion(std::size_t s = 0, std::size_t n = 1) const {
        return T_.at(s, n) / gamma_.at(s, n);
    }
    const PerSpecies& temperature() const { return T_; }
    const PerSpecies& gamma() const { return gamma_; }
    std::uint64_t seed() const { return seed_; }

    void poststep(SoftState<D>& s, double dt, double) override {
        c_.update(T_, gamma_, s.p.species_table.size(), dt);
        const double* drift_of = c_.drift.data();
        const double* kick_of = c_.kick.data();
        const std::uint16_t* sp = s.p.species.data();
        const auto n = static_cast<std::int64_t>(s.owned());
        const auto step = static_cast<std::uint32_t>(s.step);
        constexpr int per = detail::normals_per_rotation<D>;
        const bool noisy = c_.noisy;
        detail::parallel_for_each_batch(n, s.thread_shares, [&](std::int64_t first, int m) {
            double z[detail::noise_batch * detail::normals_per_rotation<D>];
            if (noisy)
                detail::batch_normals<per>(seed_, RngStream::orientation, s.p.tag.data() + first,
                                           step, m, z);
            if constexpr (D == 2) {
                double angle[detail::noise_batch], sn[detail::noise_batch], cs[detail::noise_batch];
                for (int k = 0; k < m; ++k) {
                    const std::int64_t i = first + k;
                    const double kick = kick_of[sp[i]];
                    angle[k] = drift_of[sp[i]] * s.torque[i][0];
                    if (kick > 0.0) angle[k] += kick * z[k];
                }
                // the polynomials serve the small angles of a step; libm the rare rest
                for (int k = 0; k < m; ++k) detail::sincos_kernel(angle[k], sn[k], cs[k]);
                for (int k = 0; k < m; ++k)
                    if (!(std::abs(angle[k]) <= 0.25 * std::numbers::pi)) {
                        sn[k] = std::sin(angle[k]);
                        cs[k] = std::cos(angle[k]);
                    }
                for (int k = 0; k < m; ++k) {
                    Vec<D>& d = s.director[first + k];
                    d = Vec<D>{{cs[k] * d[0] - sn[k] * d[1], sn[k] * d[0] + cs[k] * d[1]}};
                }
            } else {
                for (int k = 0; k < m; ++k) {
                    const std::int64_t i = first + k;
                    const double kick = kick_of[sp[i]];
                    double w[3]; // angular displacement
                    for (int a = 0; a < 3; ++a) w[a] = drift_of[sp[i]] * s.torque[i][a];
                    if (kick > 0.0) {
                        const double amplitude = kick * sphere_kick_scale(kick);
                        for (int a = 0; a < 3; ++a) w[a] += amplitude * z[k * per + a];
                    }
                    rotate_on_sphere(w, s.director[i]);
                }
            }
        });
    }

  private:
    PerSpecies T_, gamma_;
    std::uint64_t seed_;
    detail::OverdampedCoefficients c_;
};

} // namespace pedesis
