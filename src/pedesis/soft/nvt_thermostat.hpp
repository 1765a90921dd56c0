#pragma once
// What the NVT thermostats of the soft engine share (`bussi`, bussi.hpp; `nose_hoover`,
// nose_hoover.hpp): velocity Verlet for the particles with a thermostat half-step of
// dt/2 before it and one after it, the Trotter splitting
//   exp(iL_T dt/2) exp(iL_VV dt) exp(iL_T dt/2)
// of Martyna, Tuckerman, Tobias & Klein (Mol. Phys. 87, 1117, 1996), which keeps the step
// time-reversible. A half-step rescales every thermal velocity by one factor, which the
// thermostat finds from the thermal kinetic energy K and the degrees of freedom f.
//
// K and f are those of the log's temperature (observe/thermo.hpp): along the axes whose
// momentum the dynamics conserves (set_conserved_momentum), velocities are measured in
// the centre-of-mass frame and f = d N_mobile - c; the rescale v -> V + alpha (v - V)
// keeps the total momentum. Particles of infinite mass are left alone.
//
// The sums run serially in storage order: the same numbers for every thread count (and a
// checkpoint keeps the order). They cost a pass over the particles per half-step, and
// the rescale another, small beside the forces. Under a domain decomposition the sums
// are added up over the processes (set_communicator), and every process draws the same
// random numbers and keeps the same bath variables.
#include "pedesis/core/chunk_shares.hpp"
#include "pedesis/core/communicator.hpp"
#include "pedesis/core/error.hpp"
#include "pedesis/soft/plugins.hpp"
#include "pedesis/soft/velocity_verlet.hpp"

#include <array>
#include <cmath>
#include <cstdint>
#include <span>
#include <string>
#include <vector>

namespace pedesis {

// The thermal kinetic energy of the owned particles and what it was measured with.
template <int D> struct ThermalKinetics {
    double energy = 0.0;  // K = sum m (v - V)^2 / 2
    double freedom = 0.0; // f = d N_mobile - c (0 without mobile particles)
    Vec<D> centre{};      // V: the centre-of-mass velocity along conserved axes, else 0
};

// From the owned particles; with `comm`, of every process's (collective).
template <int D>
ThermalKinetics<D> measure_thermal(const SoftState<D>& s, const std::array<bool, D>& conserved,
                                   Communicator* comm = nullptr) {
    // K, M, N_mobile, P
    std::array<double, 3 + D> sums{};
    const std::size_t n = s.owned();
    for (std::size_t i = 0; i < n; ++i) {
        const double m = s.p.mass(i);
        if (std::isinf(m)) continue;
        sums[0] += 0.5 * m * norm2(s.p.velocity[i]);
        sums[1] += m;
        sums[2] += 1.0;
        for (int a = 0; a < D; ++a) sums[3 + a] += m * s.p.velocity[i][a];
    }
    if (comm) comm->sum(std::span<double>(sums));
    const double kinetic = sums[0], mass = sums[1], mobile = sums[2];
    Vec<D> momentum{};
    for (int a = 0; a < D; ++a) momentum[a] = sums[3 + a];
    ThermalKinetics<D> k;
    k.energy = kinetic;
    int c = 0;
    for (int a = 0; a < D; ++a)
        if (conserved[a] && mass > 0.0) {
            ++c;
            k.centre[a] = momentum[a] / mass;
            k.energy -= 0.5 * momentum[a] * k.centre[a];
        }
    k.energy = std::max(k.energy, 0.0); // (rounding, when every particle moves alike)
    k.freedom = mobile > 0.0 ? D * mobile - c : 0.0;
    return k;
}

template <int D> class NvtThermostat : public Integrator<D> {
  public:
    NvtThermostat(const std::string& name, double T, double tau, bool zero_T_allowed)
        : T_(T), tau_(tau), verlet_(name) {
        if (!(std::isfinite(T) && (zero_T_allowed ? T >= 0.0 : T > 0.0)))
            throw InputError(name + ": T must be a finite number " +
                             (zero_T_allowed ? ">= 0" : "> 0"));
        if (!(tau > 0.0 && std::isfinite(tau)))
            throw InputError(name + ": tau must be a positive finite number");
    }
    bool needs_initial_forces() const override { return true; }
    double bath_temperature(std::size_t, std::size_t) const override { return T_; }
    void set_conserved_momentum(const std::array<bool, D>& axes) override { conserved_ = axes; }
    void set_communicator(Communicator* comm) override { comm_ = comm; }
    double temperature() const { return T_; }
    double tau() const { return tau_; }

    void prestep(SoftState<D>& s, double dt, double max_move) override {
        half_step(s, 0.5 * dt, 0);
        verlet_.prestep(s, dt, max_move);
    }
    void poststep(SoftState<D>& s, double dt, double max_move) override {
        verlet_.poststep(s, dt, max_move);
        half_step(s, 0.5 * dt, 1);
    }

  protected:
    // The factor by which the thermal velocities are scaled over a half-step of length h
    // (`half`: 0 before the Verlet step, 1 after it), updating the bath's variables.
    virtual double rescale_factor(const ThermalKinetics<D>& k, double h, std::uint64_t step,
                                  int half) = 0;

    const double T_, tau_;

  private:
    void half_step(SoftState<D>& s, double h, int half) {
        const ThermalKinetics<D> k = measure_thermal<D>(s, conserved_, comm_);
        const double alpha = rescale_factor(k, h, s.step, half);
        if (alpha == 1.0) return;
        const Vec<D> centre = k.centre;
        const std::uint16_t* sp = s.p.species.data();
        const std::vector<Species>& table = s.p.species_table;
        Vec<D>* vel = s.p.velocity.data();
        parallel_for_each_index(static_cast<std::int64_t>(s.owned()), s.thread_shares,
                                [&](std::int64_t i) {
                                    if (!std::isinf(table[sp[i]].mass))
                                        vel[i] = centre + alpha * (vel[i] - centre);
                                });
    }

    std::array<bool, D> conserved_{};
    Communicator* comm_ = nullptr;
    VelocityVerletIntegrator<D> verlet_;
};

} // namespace pedesis
