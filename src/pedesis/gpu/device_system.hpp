#pragma once
// The state of a soft/active system on an NVIDIA GPU and the kernels of one step: the
// CUDA twin of soft/evolver.hpp's step, driven by gpu/gpu_stepper.hpp. The particles
// live on the device between frames; they are sorted along a space-filling curve of
// cells at every neighbour-list build (which is how the cell list is made), so that a
// particle's neighbours lie close in memory. C++17: implemented in device_system.cu,
// or in device_unavailable.cpp in a build without CUDA.
#include "pedesis/gpu/gpu_model.hpp"

#include <cstddef>
#include <cstdint>
#include <memory>
#include <string>

namespace pedesis::gpu {

// Whether this build has the CUDA path.
bool cuda_built();
// Empty when a CUDA device can run the engine; else why not, in a sentence.
std::string unavailable_reason();
// The device the engine runs on ("NVIDIA H100 80GB HBM3, compute capability 9.0, ...").
std::string device_description();

// Host arrays of n particles in one storage order: dim doubles per particle for vectors
// (torques: 1 in 2D, 3 in 3D), dim ints per image.
struct HostArrays {
    double* position = nullptr;
    double* velocity = nullptr;
    double* director = nullptr;
    double* force = nullptr;
    double* torque = nullptr;
    std::int32_t* image = nullptr;
    std::uint32_t* tag = nullptr;
    std::uint16_t* species = nullptr;
};

// What a pre- or post-step found.
struct StepStatus {
    bool bad_move = false;     // a move was not finite or longer than max_move
    std::uint32_t bad_tag = 0; // the lowest tag of such a move
};

class DeviceSystem {
  public:
    explicit DeviceSystem(const Model& model);
    ~DeviceSystem();
    DeviceSystem(const DeviceSystem&) = delete;
    DeviceSystem& operator=(const DeviceSystem&) = delete;

    // The whole state, in any storage order. `reference`: the positions of the last list
    // build (a checkpoint's), from which the list is built now, as the CPU engine's
    // restore does; null: the list is built at the next force computation.
    void upload(const HostArrays& a, const double* reference);
    // The state in the device's storage order (tags travel with the particles).
    void download(const HostArrays& a) const;
    // The positions of the last build, in the device's storage order (empty: none yet).
    bool download_reference(double* reference) const;

    void set_coefficients(const StepCoefficients& c);

    // The step, as Evolver::evolve: pre-step (langevin, nve), forces (a list build first
    // if a particle moved more than half the skin since the last), post-step with the
    // periodic wrap. Each returns at once but for the status it reports.
    StepStatus prestep(std::uint32_t step);
    // Returns whether the list was rebuilt.
    bool compute_forces();
    StepStatus poststep(std::uint32_t step);

    // Energy and virial of the pair force at the current positions, from a cell list of
    // their own (the stepping list and its order are left as they are).
    Totals totals();

    std::size_t device_bytes() const;

  private:
    struct Impl;
    std::unique_ptr<Impl> impl_;
};

} // namespace pedesis::gpu
