#pragma once
// The soft engine's step on an NVIDIA GPU (`[run] device = "gpu"`, `--device gpu`): reads
// the evolver's plug-ins into the device model, uploads the state and steps it there
// (gpu/device_system.hpp). Plug-in parameters are read again every step, so steering
// (temperature, alpha, J) works as on the CPU.
#include "pedesis/gpu/gpu_model.hpp"
#include "pedesis/soft/device_stepper.hpp"
#include "pedesis/soft/evolver.hpp"

#include <memory>
#include <string>
#include <vector>

namespace pedesis {

// Empty when `device = "gpu"` can run here; else why not (no CUDA in this build, no
// device), in a sentence for an InputError.
std::string gpu_unavailable_reason();

// Whether the device path runs this evolver's terms; else InputError naming what it does
// not run and the box it cannot hold. `reference`: the positions of a checkpoint's last
// list build (empty: none). Throws InputError when no GPU is usable.
template <int D>
std::unique_ptr<DeviceStepper<D>> make_gpu_stepper(SoftState<D>& state, Evolver<D>& evolver,
                                                   const std::vector<Vec<D>>& reference);

// The device model of the evolver's terms and state (what make_gpu_stepper uploads),
// made without a device, so that any machine checks that a config can run on the GPU:
// InputError for a term the device path does not run or a box it cannot hold.
template <int D> gpu::Model gpu_model(const SoftState<D>& state, Evolver<D>& evolver);
// The per-species coefficients of one step of length dt, from the integrators' and
// forces' current parameters (the CPU integrators' own tables).
template <int D>
gpu::StepCoefficients gpu_coefficients(const SoftState<D>& state, const Evolver<D>& evolver,
                                       double dt, double max_move);

} // namespace pedesis
