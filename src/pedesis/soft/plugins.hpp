#pragma once
// The plug-in interfaces of the soft/active engine (the design of the ABP tutorial:
// forces, torques and integrators registered with an evolver). A virtual call happens
// once per term per step, never per pair or per particle.
#include "pedesis/core/sym_tensor.hpp"
#include "pedesis/soft/soft_state.hpp"
#include "pedesis/spatial/neighbor_list.hpp"

#include <array>
#include <limits>
#include <optional>
#include <string>
#include <vector>

namespace pedesis {

class Communicator;

// Totals that only logging needs: computed on request, serially, so that they are
// reproducible and cost nothing on ordinary steps.
struct PairTotals {
    double energy = 0.0;       // potential energy of the conservative forces
    double virial = 0.0;       // sum over pairs of r_ij . F_ij
    SymTensor virial_tensor{}; // sum over pairs of r_ij,a F_ij,b (trace: virial)
};

template <int D> class ForceTerm {
  public:
    virtual ~ForceTerm() = default;
    virtual std::string name() const = 0;
    // Largest pair distance the term needs (0 for one-body terms).
    virtual double range(const SoftState<D>&) const { return 0.0; }
    // The distance inside which the force between species a and b grows without bound (a
    // Lennard-Jones sigma; 0 for terms without such a core, harmonic among them): what a
    // blow-up's message measures overlaps and the density against
    // (soft/blow_up_cause.hpp).
    virtual double core(const SoftState<D>&, std::size_t /*a*/, std::size_t /*b*/) const {
        return 0.0;
    }
    // The same for a one-body term (a wall): the particle that starts deepest inside the
    // term's core, said as a blow-up's message says it ("particle 7 began 0.3 from a
    // wall, inside its sigma (1)"), with its fix; empty if none starts there.
    virtual std::string start_overlap(const SoftState<D>&) const { return {}; }
    virtual void add_forces(SoftState<D>& s, const NeighborList<D>& nl) const = 0;
    // The precision its pair rows compute in for this state (s.pair_precision where they
    // can: soft/pair_rows_mixed.hpp); none for a term without pair rows.
    virtual std::optional<Precision> rows_precision(const SoftState<D>&) const {
        return std::nullopt;
    }
    virtual void add_totals(const SoftState<D>&, const NeighborList<D>&, PairTotals&) const {}
    // The pair part of the heat flux ([transport]'s thermal conductivity): adds each pair's
    // energy u_ij, half to each particle, to energy[i], and (1/2) r_ij (F_ij . (v_i + v_j))
    // to `flux` (Irving-Kirkwood; r_ij = r_i - r_j, F_ij the force on i), and in the same
    // pass what add_totals adds to the virial tensor. false for a term whose energy is not
    // shared by pairs (walls, fields, active forces): the heat flux of a system with one is
    // not measured.
    virtual bool add_heat_flux(const SoftState<D>&, const NeighborList<D>&,
                               std::vector<double>& /*energy*/, Vec<D>& /*flux*/,
                               SymTensor& /*virial_tensor*/) const {
        return false;
    }
    // The energy and virial beyond the cutoff of a homogeneous fluid of counts[s]
    // particles of species s in `volume` (LJ's tail correction, with g(r) = 1 there): 0
    // for a term that asks for none.
    virtual PairTotals tail(const std::vector<Species>& /*table*/,
                            const std::vector<double>& /*counts*/, double /*volume*/) const {
        return {};
    }
    // The term's share of the pressure that is not a pair virial: the swim pressure of an
    // active force, from the unwrapped displacements since `start` (indexed by tag).
    virtual double swim_pressure(const SoftState<D>&, const std::vector<Vec<D>>& /*start*/) const {
        return 0.0;
    }
    // The active force along the director on species s (of `count`), which makes the swim
    // pressure: 0 for a passive term. (A run shared among processes sums the swim
    // pressure from it, soft_observables.hpp.)
    virtual double swim_force(std::size_t /*s*/, std::size_t /*count*/) const { return 0.0; }
    // Active forces that are not a species' constant along the director (active_ou's
    // gamma p_i), for the swim pressure's tensor and sums: adds the term's force on each
    // owned particle i to out[i], making `out` owned() zero vectors first if it is empty.
    // A term without such forces leaves `out` as it is (empty when no term has any, which
    // the sums then skip at no cost).
    virtual void add_active_forces(const SoftState<D>&, std::vector<Vec<D>>& /*out*/) const {}

    // Log columns of the term's own (a wall's pressure, a field's energy), by their names
    // in the quantity catalogue (observe/quantities.hpp), and their values at the current
    // state, appended to `out` in that order. Each value must be a sum over the owned
    // particles (i < s.owned()), divided by a constant if need be: a run shared among
    // processes adds the processes' values up.
    virtual std::vector<std::string> log_columns(const SoftState<D>&) const { return {}; }
    virtual void log_values(const SoftState<D>&, std::vector<double>& /*out*/) const {}
};

template <int D> class TorqueTerm {
  public:
    virtual ~TorqueTerm() = default;
    virtual std::string name() const = 0;
    virtual double range(const SoftState<D>&) const { return 0.0; }
    virtual void add_torques(SoftState<D>& s, const NeighborList<D>& nl) const = 0;
};

// Integrators act before (pre-step) and after (post-step) forces are computed, as in the
// tutorial: overdamped schemes only need the post-step, velocity Verlet needs both.
// `max_move` is the largest displacement per step that is not a blow-up (the skin); an
// integrator that moves a particle further (or to NaN) throws RunError naming it.
template <int D> class Integrator {
  public:
    virtual ~Integrator() = default;
    virtual std::string name() const = 0;
    // True if the pre-step reads the forces of the current positions (velocity Verlet):
    // the evolver then computes them once before the first step.
    virtual bool needs_initial_forces() const { return false; }
    virtual void prestep(SoftState<D>&, double /*dt*/, double /*max_move*/) {}
    virtual void poststep(SoftState<D>&, double /*dt*/, double /*max_move*/) {}

    // What the logs need of the integrator's physics, so that no run code looks at its
    // name. An overdamped position integrator has no inertia: the kinetic part of the
    // pressure is then n T of its bath, and velocities are not thermal.
    virtual bool overdamped_positions() const { return false; }
    // The temperature of the bath it couples species s to (of `count` species), or NaN
    // for none (energy-conserving, or rotations only).
    virtual double bath_temperature(std::size_t /*s*/, std::size_t /*count*/) const {
        return std::numeric_limits<double>::quiet_NaN();
    }
    // The friction coefficient gamma with which it moves species s's positions (the drag
    // -gamma v, or the mobility 1 / gamma), or NaN for none: what turns an active velocity
    // into an active force (active_ou).
    virtual double friction(std::size_t /*s*/, std::size_t /*count*/) const {
        return std::numeric_limits<double>::quiet_NaN();
    }

    // The NVT thermostats' (bussi, nose_hoover) needs beyond the step. The energy their
    // bath holds, which K + U plus it keeps constant up to the integrator's error (the
    // log's conserved_energy), or NaN for an integrator without one.
    virtual double bath_energy() const { return std::numeric_limits<double>::quiet_NaN(); }
    // What a restart needs beyond the particles to go on bit for bit (the thermostat's
    // variables), and its restoring: InputError for numbers that cannot be its state.
    virtual std::vector<double> saved_state() const { return {}; }
    virtual void restore_state(const std::vector<double>& /*saved*/) {}
    // The axes along which the dynamics conserves momentum (observe/thermo.hpp), so that
    // a thermostat counts degrees of freedom and measures the temperature as the log does
    // (none unless told).
    virtual void set_conserved_momentum(const std::array<bool, D>& /*axes*/) {}
    // Under a domain decomposition, the processes whose particles together make the
    // system (null on one process): a thermostat sums its kinetic energy over them, in
    // every pre- and post-step (collective then).
    virtual void set_communicator(Communicator* /*comm*/) {}
};

} // namespace pedesis
