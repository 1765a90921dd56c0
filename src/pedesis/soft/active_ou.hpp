#pragma once
// Active Ornstein-Uhlenbeck particles (AOUPs): each particle carries an active velocity
// p_i, an Ornstein-Uhlenbeck process per axis,
//   tau dp = -p dt + sqrt(2 D_a) dW,
// and feels the active force gamma p_i, gamma the friction of its position integrator
// (brownian: r moves by p dt on top of the rest; langevin: the terminal velocity is p).
// Free AOUPs have <dr^2> = 2 d D_t t + 2 d D_a [t - tau (1 - e^{-t/tau})] and a
// stationary <p^2> = d D_a / tau (../shared/PHYSICS.md).
//
// p lives in the state (SoftState::active_velocity), so that it travels with its particle
// through storage sorts and into checkpoints. It starts from its stationary distribution
// (a Gaussian of variance D_a / tau per axis) and advances once per step, exactly:
//   p(t + dt) = p e^{-dt/tau} + sqrt(D_a / tau (1 - e^{-2 dt/tau})) xi,
// before the step's forces (the integrator ActiveOuStep does it, registered beside the
// force). The normals are Philox keyed by (seed, active_velocity, tag, counter): the start
// at step k draws counter k, the advance of step k counter k + 1, so no two draws share a
// key and the trajectory depends neither on thread count nor on storage order.
#include "pedesis/core/error.hpp"
#include "pedesis/core/rng.hpp"
#include "pedesis/soft/active_virial.hpp"
#include "pedesis/soft/batch_normals.hpp"
#include "pedesis/soft/evolver.hpp"
#include "pedesis/soft/per_species.hpp"
#include "pedesis/soft/plugins.hpp"

#include <cmath>
#include <memory>
#include <string>
#include <vector>

namespace pedesis {

template <int D> class ActiveOU final : public ForceTerm<D> {
  public:
    using Integrators = std::vector<std::unique_ptr<Integrator<D>>>;

    // `integrators`: the evolver's, where the friction of each species is read (they may
    // be registered after this force, as a config lists them).
    ActiveOU(PerSpecies tau, PerSpecies active_diffusion, std::uint64_t seed,
             const Integrators& integrators)
        : tau_(std::move(tau)), da_(std::move(active_diffusion)), seed_(seed),
          integrators_(integrators) {
        for (double t : tau_.values())
            if (!(t > 0.0 && std::isfinite(t)))
                throw InputError("active_ou: tau must be a positive finite number");
        for (double d : da_.values())
            if (!(d >= 0.0 && std::isfinite(d)))
                throw InputError("active_ou: D_a must be a finite number >= 0");
    }
    std::string name() const override { return "active_ou"; }

    // Draws every particle's p from the stationary distribution, unless the state has
    // them (a restored checkpoint, or an earlier call).
    void start(SoftState<D>& s) const {
        if (s.active_velocity.size() == s.size() && !s.active_velocity.empty()) return;
        const std::size_t ns = s.p.species_table.size();
        spread_.resize(ns);
        for (std::size_t k = 0; k < ns; ++k) spread_[k] = std::sqrt(da_.at(k, ns) / tau_.at(k, ns));
        s.active_velocity.assign(s.size(), Vec<D>{});
        draw(s, static_cast<std::uint32_t>(s.step), [&](std::int64_t i, const double* z) {
            const double a = spread_[s.p.species[i]];
            for (int c = 0; c < D; ++c) s.active_velocity[i][c] = a * z[c];
        });
    }

    // One step of the exact Ornstein-Uhlenbeck update.
    void advance(SoftState<D>& s, double dt) const {
        start(s);
        const std::size_t ns = s.p.species_table.size();
        damp_.resize(ns);
        kick_.resize(ns);
        for (std::size_t k = 0; k < ns; ++k) {
            const double tau = tau_.at(k, ns), x = dt / tau;
            damp_[k] = std::exp(-x);
            // 1 - e^{-2x} by expm1: for dt << tau the plain difference loses digits
            kick_[k] = std::sqrt(-std::expm1(-2.0 * x) * da_.at(k, ns) / tau);
        }
        draw(s, static_cast<std::uint32_t>(s.step + 1), [&](std::int64_t i, const double* z) {
            const std::uint16_t k = s.p.species[i];
            Vec<D>& p = s.active_velocity[i];
            for (int c = 0; c < D; ++c) p[c] = damp_[k] * p[c] + kick_[k] * z[c];
        });
    }

    void add_forces(SoftState<D>& s, const NeighborList<D>&) const override {
        start(s);
        const double* gamma = frictions(s).data();
        const std::uint16_t* sp = s.p.species.data();
        const Vec<D>* p = s.active_velocity.data();
        const auto n = static_cast<std::int64_t>(s.owned());
        parallel_for_each_index(n, s.thread_shares,
                                [&](std::int64_t i) { s.force[i] += gamma[sp[i]] * p[i]; });
    }

    double swim_pressure(const SoftState<D>& s, const std::vector<Vec<D>>& start) const override {
        if (s.active_velocity.size() != s.size()) return 0.0; // (none drawn yet)
        const std::vector<double>& gamma = frictions(s);
        return active_virial(s, start, [&](std::size_t i, const Vec<D>& d) {
            return gamma[s.p.species[i]] * dot(s.active_velocity[i], d);
        });
    }

    void add_active_forces(const SoftState<D>& s, std::vector<Vec<D>>& out) const override {
        if (s.active_velocity.size() != s.size()) return;
        const std::vector<double>& gamma = frictions(s);
        if (out.empty()) out.assign(s.owned(), Vec<D>{});
        for (std::size_t i = 0; i < s.owned(); ++i)
            out[i] += gamma[s.p.species[i]] * s.active_velocity[i];
    }

    // gamma of each species: the friction of the first integrator that has one for it.
    const std::vector<double>& frictions(const SoftState<D>& s) const {
        const std::size_t ns = s.p.species_table.size();
        gamma_.assign(ns, std::nan(""));
        for (std::size_t k = 0; k < ns; ++k) {
            for (const auto& i : integrators_) {
                gamma_[k] = i->friction(k, ns);
                if (std::isfinite(gamma_[k])) break;
            }
            if (!std::isfinite(gamma_[k]))
                throw InputError("active_ou: its active force is gamma p, gamma the friction of "
                                 "the position integrator, and this run has none with a "
                                 "friction: move the particles with brownian or langevin");
        }
        return gamma_;
    }

  private:
    // f(i, z) for every particle, z its D standard normals of counter `counter`.
    template <class F> void draw(SoftState<D>& s, std::uint32_t counter, F&& f) const {
        const auto n = static_cast<std::int64_t>(s.size());
        detail::parallel_for_each_batch(n, s.thread_shares, [&](std::int64_t first, int m) {
            double z[detail::noise_batch * D];
            detail::batch_normals<D>(seed_, RngStream::active_velocity, s.p.tag.data() + first,
                                     counter, m, z);
            for (int k = 0; k < m; ++k) f(first + k, z + k * D);
        });
    }

    PerSpecies tau_, da_;
    std::uint64_t seed_;
    const Integrators& integrators_;
    // per-species tables, reused every step
    mutable std::vector<double> spread_, damp_, kick_, gamma_;
};

// The step of p, before the forces of each step: an integrator that moves no position,
// registered with the force (add_active_ou).
template <int D> class ActiveOuStep final : public Integrator<D> {
  public:
    explicit ActiveOuStep(const ActiveOU<D>& force) : force_(force) {}
    std::string name() const override { return "active_ou"; }
    void prestep(SoftState<D>& s, double dt, double) override { force_.advance(s, dt); }

  private:
    const ActiveOU<D>& force_;
};

// Registers active_ou with `e`: the force and the step of its active velocities.
template <int D>
void add_active_ou(Evolver<D>& e, PerSpecies tau, PerSpecies active_diffusion, std::uint64_t seed) {
    auto force = std::make_unique<ActiveOU<D>>(std::move(tau), std::move(active_diffusion), seed,
                                               e.integrators());
    const ActiveOU<D>& ou = *force;
    e.add_force(std::move(force));
    e.add_integrator(std::make_unique<ActiveOuStep<D>>(ou));
}

} // namespace pedesis
