#pragma once
// The time-stepped hard-particle engine's run (dynamics = stepped): builds (or restores)
// the engine and measures the event engine's log columns plus step, v_rms, mean_speed
// and the notebook's running pressure, so that plots and movies work for both; the
// Simulation drives it.
#include "pedesis/run/run_options.hpp"
#include "pedesis/run/simulation.hpp"
#include "pedesis/setup/run_config.hpp"

#include <ostream>

namespace pedesis {

template <int D>
EngineSetup<D> stepped_engine_setup(const RunConfig& config, const RunOptions& options,
                                    std::ostream& console);

} // namespace pedesis
