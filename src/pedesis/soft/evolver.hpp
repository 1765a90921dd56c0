#pragma once
// The evolver of the ABP tutorial: owns the registered forces, torques and integrators
// and advances the state one step at a time:
//   neighbour-list check, integrator pre-steps, forces and torques (reset, then every
//   term), integrator post-steps, periodic wrap with image counters.
#include "pedesis/soft/blow_up_cause.hpp"
#include "pedesis/soft/device_stepper.hpp"
#include "pedesis/soft/domain_decomposition.hpp"
#include "pedesis/soft/plugins.hpp"

#include <memory>
#include <vector>

namespace pedesis {

template <int D> class Evolver {
  public:
    // The list cutoff follows the largest range of the registered terms unless r_cut is
    // given (> 0); skin is the tutorial's "pad".
    Evolver(SoftState<D>& state, double skin, double r_cut = 0.0);

    void add_force(std::unique_ptr<ForceTerm<D>> f);
    void add_torque(std::unique_ptr<TorqueTerm<D>> t);
    void add_integrator(std::unique_ptr<Integrator<D>> i);

    void evolve(double dt);

    // Shares the run with other processes (soft/domain_decomposition.hpp): the state
    // holds this process's particles and ghosts, every step exchanges ghosts, and a list
    // rebuild (decided together) redistributes the particles. Every call that steps,
    // computes forces or totals is then collective, and an error on one process (a
    // blow-up) is thrown on all, with its message. The decomposition must outlive the
    // evolver. The periodic sort then sorts each process's particles, at a shared
    // redistribution.
    void set_domain(DomainDecomposition<D>* domain);
    // Hands every step, force computation and total to a device (gpu/gpu_stepper.hpp),
    // which holds the state from now on: the host arrays are a copy that sync_host()
    // brings up to date, and the periodic sort is the device's own. Not with a domain
    // decomposition.
    void set_device(std::unique_ptr<DeviceStepper<D>> device);
    const DeviceStepper<D>* device() const { return device_.get(); }
    // Brings the state's host arrays up to date with the device (nothing without one).
    void sync_host();
    // Whether a caught signal (core/interrupt.hpp) asks the run to stop: under a domain
    // decomposition, whether one reached any process by the end of the last step, so
    // that all stop at the same step.
    bool interrupted() const;
    // The list's cutoff plus skin, from the registered terms (what ghosts must cover).
    double interaction_reach();
    void run(std::uint64_t steps, double dt) {
        for (std::uint64_t k = 0; k < steps; ++k) evolve(dt);
    }

    // Every `steps` steps (0: never) the storage is reordered for cache locality (see
    // sort_storage); outputs, which are in tag order, do not change.
    void set_sort_interval(std::uint64_t steps) { sort_interval_ = steps; }
    // That reordering now, and a fresh list (counted as a build): along the curve, then in
    // the order the force loops visit the rows. Not under a domain decomposition, whose
    // redistribution sorts each share, nor on a device, which sorts its own copy.
    void sort_storage();
    // The same before a fresh run's first step (as LAMMPS sorts at a run's set-up): its
    // list is the run's first, counted once, whether or not one was built to check the
    // input.
    void sort_storage_at_start();
    std::uint64_t sort_interval() const { return sort_interval_; }

    // Puts the storage back in tag order (index i holds tag i), as the Python module's
    // array views need, without changing the trajectory: the neighbour list follows the
    // particles instead of being rebuilt. The next sort (every sort_interval steps) gives
    // the same order as if this had never happened.
    // Returns the order applied (empty if the storage was in tag order already);
    // reorder(inverse) goes back to the storage order before the call.
    std::vector<std::uint32_t> restore_tag_order();
    void reorder(const std::vector<std::uint32_t>& order);
    bool in_tag_order() const;

    // Forces and torques at the current positions, as if a step were starting (the
    // velocity-Verlet pre-step needs them; evolve() calls this once by itself).
    void compute_forces();
    // The forces in the state are those of its positions (e.g. restored from a
    // checkpoint): the first step must not recompute them.
    void mark_forces_current() { forces_current_ = true; }
    // The positions were changed from outside (the Python module's arrays): the next step
    // recomputes the forces its pre-step needs.
    void invalidate_forces() { forces_current_ = false; }
    bool needs_initial_forces() const;

    // What a checkpoint needs to continue bit for bit: the positions of the last list
    // build (the list is rebuilt from them, giving the same rows) and the build count.
    // Under Lees-Edwards shear also the box's offset at that build.
    std::vector<Vec<D>> list_reference() const;
    double list_shear_offset() const;
    // Under a barostat also the box's lengths at that build (the list's cells and images):
    // build_lengths, empty for the present box.
    void restore_list(const std::vector<Vec<D>>& reference, std::uint64_t builds,
                      double shear_offset = 0.0, const std::vector<double>& build_lengths = {});
    // The box lengths of the last list build (the box's own before a build).
    std::vector<double> list_box_lengths() const;

    // Energy and virial of the conservative pair forces at the current positions, with
    // the terms' tail corrections (ForceTerm::tail).
    PairTotals pair_totals();
    // The heat flux J = Σ_i v_i e_i + (1/2) Σ_pairs r_ij (F_ij . (v_i + v_j)), e_i the
    // particle's kinetic energy and half its pair energies, into `flux` (`energy` is
    // scratch): false when a term has no pair energy (ForceTerm::add_heat_flux), under a
    // domain decomposition or on the GPU. Serial, on request, as pair_totals; with
    // `virial_tensor`, pair_totals().virial_tensor from the same pass.
    bool heat_flux(std::vector<double>& energy, Vec<D>& flux, SymTensor* virial_tensor = nullptr);
    const NeighborList<D>& neighbor_list();
    std::uint64_t list_builds() const { return builds_; }
    double list_cutoff() const { return r_list_cut_; }
    double skin() const { return skin_; }
    const std::vector<std::unique_ptr<ForceTerm<D>>>& forces() const { return forces_; }
    const std::vector<std::unique_ptr<TorqueTerm<D>>>& torques() const { return torques_; }
    const std::vector<std::unique_ptr<Integrator<D>>>& integrators() const { return integrators_; }

  private:
    void step(double dt); // evolve's step, without the blow-up's cause
    PairTotals pair_totals_within_cutoff();
    // The terms' shares beyond their cutoffs, for the whole system's composition.
    void add_tail_corrections(PairTotals& t);
    // for_totals: called for the log's totals (under a domain decomposition, see there)
    void ensure_list(bool for_totals = false);
    void evolve_shared(double dt);
    void build_local(); // the list from the positions in the domain's frame (local_)
    // Under a domain decomposition: throws on every process the error one of them met
    // (`error` non-empty), else returns whether any asks to stop (`stop`).
    bool agree(const std::string& error, bool stop);
    void make_list();
    void make_list(const Box<D>& box);
    // Whether the list may miss a pair within the cutoff: the list's own rule, or under a
    // box scaled since the build (a barostat) NeighborList::needs_rebuild_scaled.
    bool list_stale() const;
    bool box_changed() const;
    // Under Lees-Edwards shear: the box's offset (and its list's) slid on by rate L_y dt.
    void slide_images(double dt);
    void reorder_storage();
    void wrap_all();

    SoftState<D>& s_;
    double skin_;
    double r_cut_request_;
    double r_list_cut_ = 0.0;
    std::unique_ptr<NeighborList<D>> nl_;
    std::uint64_t builds_ = 0;
    std::uint64_t sort_interval_ = 0;
    bool forces_current_ = false;
    DomainDecomposition<D>* domain_ = nullptr;
    std::unique_ptr<DeviceStepper<D>> device_;
    bool host_current_ = true; // the host arrays hold the device's state
    bool interrupted_ = false; // collective, under a domain decomposition
    bool rebuild_for_totals_ = false;
    std::vector<Vec<D>> local_; // positions in the frame of the domain's list
    std::vector<std::unique_ptr<ForceTerm<D>>> forces_;
    std::vector<std::unique_ptr<TorqueTerm<D>>> torques_;
    std::vector<std::unique_ptr<Integrator<D>>> integrators_;
    StartFacts start_; // for a blow-up's message: measured before the first step
};

extern template class Evolver<2>;
extern template class Evolver<3>;

} // namespace pedesis
