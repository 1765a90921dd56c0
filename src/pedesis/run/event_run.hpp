#pragma once
// The event-driven engine's run: builds (or restores) the engine from a config and
// measures what its run directory holds (log columns, speed histogram, summary); the
// Simulation drives it.
#include "pedesis/run/run_options.hpp"
#include "pedesis/run/simulation.hpp"
#include "pedesis/setup/run_config.hpp"

#include <ostream>

namespace pedesis {

template <int D>
EngineSetup<D> event_engine_setup(const RunConfig& config, const RunOptions& options,
                                  std::ostream& console);

} // namespace pedesis
