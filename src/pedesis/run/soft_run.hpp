#pragma once
// Drives a soft / active run (dynamics = brownian, langevin or nve) from a config: builds
// (or restores) the state and the evolver with the config's plug-ins, steps it, and
// writes the run directory: log.csv, snapshots/ (VTP, JSON, text table), trajectory.gsd,
// trajectory.xyz, checkpoint.bin, summary.json.
#include "pedesis/io/run_config.hpp"
#include "pedesis/run/event_run.hpp"

#include <ostream>

namespace pedesis {

void run_soft_simulation(const RunConfig& config, const RunOptions& options, std::ostream& console);

} // namespace pedesis
