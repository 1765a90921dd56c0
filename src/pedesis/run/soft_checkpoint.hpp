#pragma once
// Checkpoints of a soft-engine run. Everything that decides the next step is saved
// exactly: the state in storage order (with forces and image counts), the positions of
// the last neighbour-list build (rebuilding from them gives the same rows, hence the
// same summation order) and the driver's own bookkeeping, so a restart continues bit for
// bit.
#include "pedesis/observe/shear_flow.hpp"
#include "pedesis/run/transport_measurement.hpp"
#include "pedesis/setup/run_config.hpp"
#include "pedesis/soft/evolver.hpp"
#include "pedesis/soft/soft_state.hpp"

#include <filesystem>
#include <optional>
#include <vector>

namespace pedesis {

// What the run driver keeps besides the state.
template <int D> struct SoftRunBook {
    std::vector<Vec<D>> start; // unwrapped positions at step 0, by tag (MSD, swim pressure)
    std::uint64_t frames = 0;
    std::uint64_t samples = 0; // logged rows that enter the run averages
    double sum_pressure = 0.0, sum_polar_order = 0.0;
    double sum_temperature = 0.0; // inertial runs (langevin, nve)
    ShearRecord shear;            // under Lees-Edwards shear
    // [transport]'s measurement so far (none without the table)
    std::optional<TransportMeasurement<D>> transport;
};

template <int D>
void save_soft_checkpoint(const std::filesystem::path& path, const SoftState<D>& s,
                          const Evolver<D>& evolver, const SoftRunBook<D>& book);

// Restores state and book, and the evolver's neighbour list; checks that the config
// describes the same system (dimension, species, box).
template <int D>
void load_soft_checkpoint(const std::filesystem::path& path, const RunConfig& c, SoftState<D>& s,
                          Evolver<D>& evolver, SoftRunBook<D>& book);

} // namespace pedesis
