#pragma once
// Constant pressure for the inertial soft engine ([barostat]): the Martyna-Tobias-Klein
// equations (J. Chem. Phys. 101, 4177 (1994)) for an orthorhombic box whose axes follow
// one strain rate (isotropic) or each its own (anisotropic), with particle momenta p
// peculiar to the box's affine flow:
//   dr_a/dt = p_a/m + nu_a r_a,   dp_a/dt = F_a - (nu_a + sum_b nu_b / N_f) p_a,
//   dL_a/dt = nu_a L_a,           W dnu_g/dt = sum_{a in g} [V (P_aa - P) + 2K / N_f],
// P_aa = (sum m v_a^2 + W_aa) / V with W_aa the pair virial (with the terms' tail
// corrections), N_f = D N the particles' degrees of freedom, g a group of axes (all axes
// isotropic, one axis each anisotropic) and W = N_f T tau^2 the barostat's mass. Without
// a thermostat (nve) they conserve H = K + U + P V + sum_g W nu_g^2 / 2 (constant
// enthalpy); with langevin's friction and noise on p, whose stationary law exp(-H/T) the
// equations' phase-space compressibility (-d ln V / dt) leaves in place, the (N, P, T)
// ensemble. The step is the symmetric Trotter splitting of Tuckerman et al. (J. Phys. A
// 39, 5629 (2006)) that LAMMPS' fix npt uses:
//   nu half-kick, p scaled by exp(-(dt/2)(nu_a + sum nu / N_f)), B half-kick,
//   r and L scaled by exp(nu_a dt/2), drift (nve: r += dt v; langevin: A O A), scaled again,
//   forces, B half-kick, p scaled, nu half-kick (with the new positions' virial).
// The virial is one pair pass per step (Evolver::pair_totals), which a step without the
// barostat does not pay.
#include "pedesis/core/chunk_shares.hpp"
#include "pedesis/core/error.hpp"
#include "pedesis/core/rng.hpp"
#include "pedesis/core/sym_tensor.hpp"
#include "pedesis/setup/barostat_config.hpp"
#include "pedesis/soft/batch_normals.hpp"
#include "pedesis/soft/blow_up.hpp"
#include "pedesis/soft/langevin.hpp"
#include "pedesis/soft/plugin_registry.hpp"
#include "pedesis/soft/plugins.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <functional>
#include <limits>
#include <memory>
#include <optional>
#include <string>
#include <vector>

namespace pedesis {

template <int D> class MtkIntegrator final : public Integrator<D> {
  public:
    // The pair virial tensor, tail corrections included, at the state's present positions.
    using VirialOf = std::function<SymTensor()>;
    // langevin's parameters (none: nve, constant enthalpy)
    struct Bath {
        PerSpecies T, gamma;
        std::uint64_t seed = 0;
        detail::NoiseShape noise = detail::NoiseShape::gaussian;
    };

    // `volume`: the box's at the start (what conserved_energy counts before the first step).
    MtkIntegrator(double pressure, double tau, bool anisotropic, std::optional<Bath> bath,
                  VirialOf virial, double volume = 0.0)
        : pressure_(pressure), tau_(tau), anisotropic_(anisotropic), bath_(std::move(bath)),
          virial_of_(std::move(virial)), volume_(volume) {
        if (!(pressure > 0.0 && std::isfinite(pressure)))
            throw InputError("barostat: pressure must be a positive finite number");
        if (!(tau > 0.0 && std::isfinite(tau)))
            throw InputError("barostat: tau must be a positive finite time");
    }

    std::string name() const override { return bath_ ? "langevin" : "nve"; }
    bool needs_initial_forces() const override { return true; }
    double bath_temperature(std::size_t s, std::size_t count) const override {
        return bath_ ? bath_->T.at(s, count) : Integrator<D>::bath_temperature(s, count);
    }
    double friction(std::size_t s, std::size_t count) const override {
        return bath_ ? bath_->gamma.at(s, count) : Integrator<D>::friction(s, count);
    }

    double pressure() const { return pressure_; }
    bool anisotropic() const { return anisotropic_; }
    const std::array<double, D>& strain_rate() const { return rate_; }
    // W, fixed at the first step (0 before)
    double mass() const { return mass_; }
    // What the barostat adds to the conserved quantity: P V + sum_g W nu_g^2 / 2.
    double energy_of(double volume) const {
        double kinetic = 0.0;
        for (int a = 0; a < (anisotropic_ ? D : 1); ++a)
            kinetic += 0.5 * mass_ * rate_[a] * rate_[a];
        return pressure_ * volume + kinetic;
    }

    void prestep(SoftState<D>& s, double dt, double max_move) override {
        if (!(mass_ > 0.0)) start(s);
        kick_rate(s, 0.5 * dt);
        scale_velocities(s, 0.5 * dt);
        kick(s, dt);
        affine(s, 0.5 * dt);
        if (bath_)
            drift_langevin(s, max_move);
        else
            drift(s, max_move);
        affine(s, 0.5 * dt);
    }

    void poststep(SoftState<D>& s, double dt, double) override {
        kick(s, dt);
        scale_velocities(s, 0.5 * dt);
        virial_ = virial_of_();
        kick_rate(s, 0.5 * dt);
    }

    // At constant enthalpy (nve) the barostat's share of the conserved quantity (the log's
    // conserved_energy adds it to K + U); with langevin's bath nothing is conserved.
    double bath_energy() const override {
        return bath_ ? std::numeric_limits<double>::quiet_NaN() : energy_of(volume_);
    }
    // What a checkpoint keeps: the strain rates, the mass, the last virial (a restart
    // continues bit for bit without a pair pass of its own), the mobile count, the volume.
    std::vector<double> saved_state() const override {
        std::vector<double> v(rate_.begin(), rate_.end());
        v.push_back(mass_);
        v.insert(v.end(), virial_.begin(), virial_.end());
        v.push_back(mobile_);
        v.push_back(volume_);
        return v;
    }
    void restore_state(const std::vector<double>& v) override {
        if (v.empty()) return; // a checkpoint without the barostat: it starts afresh
        if (v.size() != static_cast<std::size_t>(D) + 9)
            throw InputError("corrupt barostat state (" + std::to_string(v.size()) + " numbers)");
        for (const double x : v)
            if (!std::isfinite(x)) throw InputError("corrupt barostat state (not a finite number)");
        auto at = v.begin();
        std::copy(at, at + D, rate_.begin());
        at += D;
        mass_ = *at++;
        std::copy(at, at + 6, virial_.begin());
        at += 6;
        mobile_ = *at++;
        volume_ = *at;
        if (!(mass_ >= 0.0) || !(mobile_ >= 0.0) || !(volume_ >= 0.0))
            throw InputError("corrupt barostat state (a negative mass, count or volume)");
    }

  private:
    // At the first step: the degrees of freedom, the mass W = N_f T tau^2 (T of the bath,
    // or the particles' kinetic temperature at constant enthalpy) and the virial.
    void start(SoftState<D>& s) {
        const auto& table = s.p.species_table;
        mobile_ = 0.0;
        double bath_T = 0.0;
        for (std::size_t i = 0; i < s.owned(); ++i) {
            if (std::isinf(s.p.mass(i))) continue;
            mobile_ += 1.0;
            if (bath_) bath_T += bath_->T.at(s.p.species[i], table.size());
        }
        // (config errors, though only the first step sees them: exit 2)
        if (!(mobile_ > 0.0)) throw InputError("barostat: every particle is fixed (infinite mass)");
        const double freedom = D * mobile_;
        const double T = bath_ ? bath_T / mobile_ : total_twice_kinetic(s) / freedom;
        if (!(T > 0.0))
            throw InputError("barostat: its mass W = N_f T tau^2 needs a temperature, and " +
                             std::string(bath_ ? "langevin's T is 0"
                                               : "the particles are at rest: give them velocities "
                                                 "([initial] velocities)"));
        mass_ = freedom * T * tau_ * tau_;
        virial_ = virial_of_();
        volume_ = s.box.volume();
    }

    double total_twice_kinetic(const SoftState<D>& s) const {
        double k = 0.0;
        for (const double v : twice_kinetic(s)) k += v;
        return k;
    }
    // sum m v_a^2 per axis, serially in storage order (the same bits for any threads)
    std::array<double, D> twice_kinetic(const SoftState<D>& s) const {
        std::array<double, D> k{};
        for (std::size_t i = 0; i < s.owned(); ++i) {
            const double m = s.p.mass(i);
            if (std::isinf(m)) continue;
            for (int a = 0; a < D; ++a) k[a] += m * s.p.velocity[i][a] * s.p.velocity[i][a];
        }
        return k;
    }

    void kick_rate(const SoftState<D>& s, double h) {
        const std::array<double, D> k = twice_kinetic(s);
        double k_total = 0.0;
        for (int a = 0; a < D; ++a) k_total += k[a];
        const double PV = pressure_ * s.box.volume(), freedom = D * mobile_;
        std::array<double, D> force{};
        for (int a = 0; a < D; ++a)
            force[a] =
                k[a] + virial_[static_cast<std::size_t>(sym_slot(a, a))] - PV + k_total / freedom;
        if (anisotropic_) {
            for (int a = 0; a < D; ++a) rate_[a] += h * force[a] / mass_;
            return;
        }
        double sum = 0.0;
        for (int a = 0; a < D; ++a) sum += force[a];
        const double rate = rate_[0] + h * sum / mass_;
        rate_.fill(rate);
    }

    void scale_velocities(SoftState<D>& s, double h) const {
        double total = 0.0;
        for (int a = 0; a < D; ++a) total += rate_[a];
        Vec<D> f;
        for (int a = 0; a < D; ++a) f[a] = std::exp(-h * (rate_[a] + total / (D * mobile_)));
        Vec<D>* vel = s.p.velocity.data();
        parallel_for_each_index(static_cast<std::int64_t>(s.owned()), s.thread_shares,
                                [&](std::int64_t i) {
                                    for (int a = 0; a < D; ++a) vel[i][a] *= f[a];
                                });
    }

    void kick(SoftState<D>& s, double dt) {
        tabulate(s, dt);
        const double* k = c_.kick.data();
        const std::uint16_t* sp = s.p.species.data();
        const Vec<D>* force = s.force.data();
        Vec<D>* vel = s.p.velocity.data();
        parallel_for_each_index(static_cast<std::int64_t>(s.owned()), s.thread_shares,
                                [&](std::int64_t i) { vel[i] += k[sp[i]] * force[i]; });
    }

    // r_a and L_a times exp(nu_a h): the box's centre stays at the origin, so positions
    // inside stay inside.
    void affine(SoftState<D>& s, double h) {
        Vec<D> f, lengths;
        for (int a = 0; a < D; ++a) {
            if (!(std::abs(rate_[a] * h) < 0.05))
                throw RunError(
                    "barostat: at step " + std::to_string(s.step) +
                    " the box changed by more than 5% in half a step (strain rate " +
                    std::to_string(rate_[a]) +
                    "): the pressure is far from its target for this tau; start nearer the "
                    "target density, or raise tau");
            f[a] = std::exp(rate_[a] * h);
            lengths[a] = s.box.length(a) * f[a];
        }
        std::array<bool, D> periodic{};
        for (int a = 0; a < D; ++a) periodic[a] = s.box.periodic(a);
        s.box = Box<D>(lengths, periodic);
        volume_ = s.box.volume();
        Vec<D>* pos = s.p.position.data();
        parallel_for_each_index(static_cast<std::int64_t>(s.owned()), s.thread_shares,
                                [&](std::int64_t i) {
                                    for (int a = 0; a < D; ++a) pos[i][a] *= f[a];
                                });
    }

    void drift(SoftState<D>& s, double max_move) const {
        const double* half_drift = c_.half_drift.data();
        const std::uint16_t* sp = s.p.species.data();
        Vec<D>* pos = s.p.position.data();
        const Vec<D>* vel = s.p.velocity.data();
        const double max2 = max_move * max_move;
        detail::FirstBadMove<D> bad;
        detail::parallel_for_each_batch(
            static_cast<std::int64_t>(s.owned()), s.thread_shares, [&](std::int64_t first, int m) {
                detail::FirstBadMove<D> batch_bad;
                for (std::int64_t i = first; i < first + m; ++i) {
                    const Vec<D> move = (2.0 * half_drift[sp[i]]) * vel[i];
                    if (!(norm2(move) <= max2)) batch_bad.note(i, move);
                    pos[i] += move;
                }
                batch_bad.merge_into(bad);
            });
        if (bad.any())
            detail::throw_bad_move(s, static_cast<std::size_t>(bad.index), bad.move, max_move,
                                   name());
    }

    // langevin's A O A (langevin.hpp), the same noise stream
    void drift_langevin(SoftState<D>& s, double max_move) const {
        const bool noisy = c_.noisy;
        const std::uint16_t* sp = s.p.species.data();
        const std::uint32_t* tag = s.p.tag.data();
        Vec<D>* pos = s.p.position.data();
        Vec<D>* vel = s.p.velocity.data();
        const auto step = static_cast<std::uint32_t>(s.step);
        const double max2 = max_move * max_move;
        detail::FirstBadMove<D> bad;
        detail::parallel_for_each_batch(
            static_cast<std::int64_t>(s.owned()), s.thread_shares, [&](std::int64_t first, int m) {
                detail::FirstBadMove<D> batch_bad;
                double z[detail::noise_batch * D];
                if (noisy)
                    detail::batch_noise<D>(bath_->noise, bath_->seed, RngStream::thermostat,
                                           tag + first, step, m, z);
                for (int q = 0; q < m; ++q) {
                    const std::int64_t i = first + q;
                    Vec<D> v = vel[i];
                    const Vec<D> move =
                        detail::langevin_aoa(v, c_, sp[i], noisy ? z + q * D : nullptr);
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

    void tabulate(const SoftState<D>& s, double dt) {
        if (bath_) {
            c_.update(bath_->T, bath_->gamma, s.p.species_table, dt);
            return;
        }
        // nve: langevin's tables without friction or noise
        c_.update(PerSpecies(0.0), PerSpecies(1.0), s.p.species_table, dt);
    }

    double pressure_, tau_;
    bool anisotropic_;
    std::optional<Bath> bath_;
    VirialOf virial_of_;
    std::array<double, D> rate_{}; // nu_a = d ln L_a / dt
    double mass_ = 0.0;
    SymTensor virial_{};
    double mobile_ = 0.0; // particles of finite mass
    double volume_ = 0.0; // the box's, for bath_energy
    detail::LangevinCoefficients c_;
};

// The position integrator `spec` (nve or langevin) under the barostat `b`.
template <int D>
std::unique_ptr<Integrator<D>>
make_mtk_integrator(const BarostatConfig& b, const PluginSpec& spec,
                    const std::vector<Species>& table, std::uint64_t seed,
                    typename MtkIntegrator<D>::VirialOf virial, double volume) {
    std::optional<typename MtkIntegrator<D>::Bath> bath;
    if (spec.name == "langevin") {
        const auto uniform = spec.flags.find("uniform_noise");
        bath.emplace(typename MtkIntegrator<D>::Bath{
            plugin_parameter(spec, "T", table), plugin_parameter(spec, "gamma", table), seed,
            uniform != spec.flags.end() && uniform->second ? detail::NoiseShape::uniform
                                                           : detail::NoiseShape::gaussian});
    } else if (spec.name != "nve") {
        throw InputError(spec.where + ": the barostat ([barostat], " + b.where +
                         ") moves the box with the nve (constant enthalpy) or langevin "
                         "(constant temperature) integrator, not '" +
                         spec.name + "'");
    }
    return std::make_unique<MtkIntegrator<D>>(b.pressure, b.tau, b.anisotropic, std::move(bath),
                                              std::move(virial), volume);
}

} // namespace pedesis
