#pragma once
// Drives an event-driven run from a config: builds (or restores) the engine, and
// writes the run directory: log.csv, trajectory.xyz, snapshots/, speed_histogram.csv,
// checkpoint.bin, summary.json. Engines know nothing of files; this is where they meet.
#include "pedesis/io/run_config.hpp"
#include "pedesis/run/run_options.hpp"

#include <filesystem>
#include <optional>
#include <ostream>
#include <string>

namespace pedesis {

void run_event_simulation(const RunConfig& config, const RunOptions& options,
                          std::ostream& console);

} // namespace pedesis
