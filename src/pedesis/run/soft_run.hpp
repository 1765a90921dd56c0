#pragma once
// The soft / active engine's run (dynamics = brownian, langevin or nve): builds (or
// restores) the state and the evolver with the config's plug-ins and measures its log
// columns and summary; the Simulation drives it.
#include "pedesis/core/interrupt.hpp"
#include "pedesis/run/run_options.hpp"
#include "pedesis/run/simulation.hpp"
#include "pedesis/setup/run_config.hpp"
#include "pedesis/soft/evolver.hpp"

#include <limits>
#include <ostream>

namespace pedesis {

// The clock of a soft run: t = t0 + (step - step0) dt, a multiple of dt rather than a
// running sum (t = 10 after 1000 steps of 0.01).
struct SoftClock {
    double t0 = 0.0;
    std::uint64_t step0 = 0;
    double dt = 0.0;
};

// Steps until `until_step`, until `until_time` (a time within rounding of the clock is
// reached) or until a caught signal (core/interrupt.hpp): how `pedesis run` and the
// Python module's Evolver.run step alike.
template <int D>
void evolve_until(SoftState<D>& s, Evolver<D>& evolver, const SoftClock& clock,
                  std::uint64_t until_step,
                  double until_time = std::numeric_limits<double>::infinity()) {
    while (s.step < until_step && s.time < until_time - 1e-9 * clock.dt && !evolver.interrupted()) {
        evolver.evolve(clock.dt);
        s.time = clock.t0 + static_cast<double>(s.step - clock.step0) * clock.dt;
    }
}

template <int D>
EngineSetup<D> soft_engine_setup(const RunConfig& config, const RunOptions& options,
                                 std::ostream& console);

} // namespace pedesis
