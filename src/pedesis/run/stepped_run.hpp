#pragma once
// Drives a time-stepped hard-particle run (dynamics = stepped) from a config: builds (or
// restores) the engine, steps it, and writes the run directory of the event engine
// (log.csv with the same columns plus step, v_rms, mean_speed and the running pressure,
// trajectory.xyz, snapshots/, speed_histogram.csv, checkpoint.bin, summary.json), so
// that plots and movies work for both.
#include "pedesis/io/run_config.hpp"
#include "pedesis/run/event_run.hpp" // RunOptions

#include <ostream>

namespace pedesis {

void run_stepped_simulation(const RunConfig& config, const RunOptions& options,
                            std::ostream& console);

} // namespace pedesis
