#pragma once
// A step of the soft engine made elsewhere than on the host's arrays: the CUDA twin
// (gpu/gpu_stepper.hpp) implements it, and an Evolver given one (Evolver::set_device)
// hands it every step, force computation and total. The state's host arrays are then a
// copy, brought up to date by download() before anything reads them.
#include "pedesis/soft/plugins.hpp"

#include <cstdint>
#include <string>
#include <vector>

namespace pedesis {

template <int D> class DeviceStepper {
  public:
    virtual ~DeviceStepper() = default;
    // Where it runs, for the run's first lines ("GPU: NVIDIA H100 ...").
    virtual std::string description() const = 0;
    // One step of the state's step counter: pre-steps, forces, post-steps, wrap. Returns
    // the neighbour-list builds it made (0 or 1). A blow-up throws RunError.
    virtual std::uint64_t step(double dt, double max_move) = 0;
    // Forces and torques at the current positions; returns the builds made.
    virtual std::uint64_t compute_forces() = 0;
    virtual PairTotals pair_totals() = 0;
    // The host arrays take the device's state (in the device's storage order).
    virtual void download() = 0;
    // The positions of the last list build, in the order download() leaves.
    virtual std::vector<Vec<D>> list_reference() = 0;
    // Device memory held (benchmarks).
    virtual std::size_t device_bytes() const { return 0; }
};

} // namespace pedesis
