#pragma once
// The soft / active engine's run (dynamics = brownian, langevin or nve): builds (or
// restores) the state and the evolver with the config's plug-ins and measures its log
// columns and summary; the Simulation drives it.
#include "pedesis/run/run_options.hpp"
#include "pedesis/run/simulation.hpp"
#include "pedesis/setup/run_config.hpp"

#include <ostream>

namespace pedesis {

template <int D>
EngineSetup<D> soft_engine_setup(const RunConfig& config, const RunOptions& options,
                                 std::ostream& console);

} // namespace pedesis
