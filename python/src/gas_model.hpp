#pragma once
// The hard-particle engines (event and stepped) as the Python module drives them: a gas
// built from a run config (a TOML file or text, with every check `pedesis run` makes),
// advanced until a time, a collision count or a number of steps, and measured. Nothing
// here knows Python.
#include "pedesis/core/species.hpp"
#include "pedesis/core/sym_tensor.hpp"
#include "pedesis/run/trigger.hpp"
#include "pedesis/setup/run_config.hpp"

#include <cstdint>
#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <vector>

namespace pedesis::python {

struct GasLimits {
    std::optional<double> time;                    // absolute simulated time
    std::optional<double> collisions_per_particle; // pair collisions since t = 0, per particle
    std::optional<std::uint64_t> steps;            // steps from now (stepped engine only)
};

class GasModel {
  public:
    virtual ~GasModel() = default;
    virtual int dim() const = 0;
    virtual std::string dynamics() const = 0;
    virtual std::size_t size() const = 0;
    // Advances through the one run loop (run/simulation.hpp), without a run directory,
    // until the first limit is met or a caught signal (core/interrupt.hpp) stops it.
    // Returns the reason, by the names summary.json's stopped_by uses: "time",
    // "collisions_per_particle", "steps", "no more events", "energy_fraction", "grown".
    virtual std::string run(const GasLimits& limits) = 0;
    // Copies in tag order (the event engine moves particles lazily: its own arrays hold
    // each particle at its last event, so there is nothing to view).
    virtual std::vector<double> positions() const = 0;  // N x dim at time()
    virtual std::vector<double> velocities() const = 0; // N x dim
    virtual std::vector<std::uint16_t> types() const = 0;
    virtual std::vector<double> box() const = 0;
    virtual std::vector<bool> periodic() const = 0; // per axis; false: walls
    virtual const std::vector<Species>& species() const = 0;
    virtual double time() const = 0;
    virtual std::uint64_t steps() const = 0; // 0 for the event engine
    virtual std::uint64_t pair_collisions() const = 0;
    virtual std::uint64_t wall_collisions() const = 0;
    virtual double kinetic_energy() const = 0;
    // 2 K / f in the centre-of-mass frame, f the degrees of freedom (observe/thermo.hpp)
    virtual double temperature() const = 0;
    virtual double degrees_of_freedom() const = 0;
    // The pressure tensor since the previous call (or since t = 0), as log.csv's
    // pressure_xx ... (observe/pressure.hpp): the walls' momentum on a walled axis's
    // diagonal, the virial elsewhere, the kinetic part the mean of both ends' K_ab.
    virtual SymTensor pressure_tensor() = 0;

    // Something a script does each time `trigger` fires inside run() (a recording of
    // frames), in every later run(); the trigger's grid is anchored at t = 0 / step 0.
    void add_operation(Trigger trigger, std::function<void()> act) {
        operations_.push_back({trigger, std::move(act)});
    }

  protected:
    struct Operation {
        Trigger trigger;
        std::function<void()> act;
    };
    std::vector<Operation> operations_;
};

std::unique_ptr<GasModel> make_gas(const RunConfig& config);

} // namespace pedesis::python
