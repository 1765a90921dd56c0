#pragma once
// Nose-Hoover chains (the `nose_hoover` integrator; Martyna, Klein & Tuckerman, J. Chem.
// Phys. 97, 2635, 1992): the particles' thermal velocities feel a friction -v_1 v, and
// v_1, the first of M thermostat velocities, is driven by the kinetic energy's excess,
// each further one by the one before it:
//   Q_1 dv_1/dt = 2 K - f T - Q_1 v_1 v_2,
//   Q_j dv_j/dt = Q_{j-1} v_{j-1}^2 - T - Q_j v_j v_{j+1}   (v_{M+1} = 0),
//   dxi_j/dt = v_j,   Q_1 = f T tau^2,  Q_j = T tau^2   (j > 1),
// with tau the period of the thermostat's oscillation (LAMMPS' Tdamp; its masses too).
// The chain's half-steps around the Verlet step (nvt_thermostat.hpp) are the Trotter
// factorisation of Martyna, Tuckerman, Tobias & Klein (Mol. Phys. 87, 1117, 1996; their
// NHCP routine with one sub-step, as LAMMPS' default tloop = 1): down the chain, the
// particles' scaling exp(-v_1 h), up the chain, each velocity update between two
// scalings by its successor. The dynamics is deterministic and samples the canonical
// ensemble (given ergodicity, which the chain is there to help), and
//   H = K + U + sum_j Q_j v_j^2 / 2 + f T xi_1 + T sum_{j>1} xi_j
// is conserved up to the integrator's error: bath_energy() is H - K - U.
#include "pedesis/soft/nvt_thermostat.hpp"

#include <cmath>
#include <cstdint>
#include <string>
#include <vector>

namespace pedesis {

template <int D> class NoseHooverIntegrator final : public NvtThermostat<D> {
  public:
    NoseHooverIntegrator(double T, double tau, int chain)
        : NvtThermostat<D>("nose_hoover", T, tau, false), xi_(check_chain(chain), 0.0),
          v_(xi_.size(), 0.0) {}
    std::string name() const override { return "nose_hoover"; }
    std::size_t chain() const { return xi_.size(); }

    double bath_energy() const override {
        double e = 0.0;
        for (std::size_t j = 0; j < xi_.size(); ++j)
            e += 0.5 * mass(j) * v_[j] * v_[j] + (j == 0 ? freedom_ : 1.0) * this->T_ * xi_[j];
        return e;
    }
    // f, then the chain's positions and velocities
    std::vector<double> saved_state() const override {
        std::vector<double> out{freedom_};
        out.insert(out.end(), xi_.begin(), xi_.end());
        out.insert(out.end(), v_.begin(), v_.end());
        return out;
    }
    void restore_state(const std::vector<double>& saved) override {
        const std::size_t m = xi_.size();
        if (saved.size() != 1 + 2 * m)
            throw InputError("the checkpoint's Nose-Hoover chain has " +
                             std::to_string(saved.empty() ? 0 : (saved.size() - 1) / 2) +
                             " thermostats, and the config's chain = " + std::to_string(m) +
                             ": a run continues with its own chain");
        for (double x : saved)
            if (!std::isfinite(x))
                throw InputError("the nose_hoover thermostat's state is corrupt");
        freedom_ = saved[0];
        xi_.assign(saved.begin() + 1, saved.begin() + 1 + static_cast<std::ptrdiff_t>(m));
        v_.assign(saved.begin() + 1 + static_cast<std::ptrdiff_t>(m), saved.end());
    }

  protected:
    double rescale_factor(const ThermalKinetics<D>& k, double h, std::uint64_t, int) override {
        freedom_ = k.freedom;
        if (!(k.freedom >= 1.0)) return 1.0;
        const std::size_t m = xi_.size();
        const double h2 = 0.5 * h, h4 = 0.25 * h;
        double twice_kinetic = 2.0 * k.energy;
        // the force on thermostat j: the excess of what drives it over its temperature
        auto force = [&](std::size_t j) {
            const double drive = j == 0 ? twice_kinetic : mass(j - 1) * v_[j - 1] * v_[j - 1];
            return (drive - (j == 0 ? freedom_ : 1.0) * this->T_) / mass(j);
        };
        auto update = [&](std::size_t j) {
            if (j + 1 == m) {
                v_[j] += h2 * force(j);
                return;
            }
            const double scale = std::exp(-h4 * v_[j + 1]);
            v_[j] = (v_[j] * scale + h2 * force(j)) * scale;
        };
        for (std::size_t j = m; j-- > 0;) update(j);
        const double alpha = std::exp(-h * v_[0]);
        twice_kinetic *= alpha * alpha;
        for (std::size_t j = 0; j < m; ++j) xi_[j] += h * v_[j];
        for (std::size_t j = 0; j < m; ++j) update(j);
        return alpha;
    }

  private:
    static std::size_t check_chain(int chain) {
        if (chain < 1) throw InputError("nose_hoover: chain must be a whole number >= 1");
        return static_cast<std::size_t>(chain);
    }
    double mass(std::size_t j) const {
        return (j == 0 ? freedom_ : 1.0) * this->T_ * this->tau_ * this->tau_;
    }

    std::vector<double> xi_, v_; // the chain's positions and velocities
    double freedom_ = 0.0;       // f at the last half-step (for Q_1 and H)
};

} // namespace pedesis
