#pragma once
// The soft/active engine as the Python module drives it: a System of either dimension
// (chosen when its particles are read) and Evolvers over it, behind interfaces without
// templates, so that the bindings stay one piece of code for 2D and 3D. Nothing here
// knows Python; the run loop takes a plain callback for what the bindings do between
// steps (the user's callback).
#include "pedesis/core/species.hpp"
#include "pedesis/soft/plugin_spec.hpp"

#include <cstdint>
#include <filesystem>
#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <vector>

namespace pedesis::python {

class SystemModel {
  public:
    virtual ~SystemModel() = default;
    virtual int dim() const = 0;
    virtual std::size_t size() const = 0;
    // Storage of the particle arrays, in tag order whenever Python can see them.
    virtual double* positions() = 0;  // N x dim
    virtual double* velocities() = 0; // N x dim
    virtual double* directors() = 0;  // N x dim
    virtual double* forces() = 0;     // N x dim
    virtual double* torques() = 0;    // N x 1 (2D) or N x 3
    virtual std::int32_t* images() = 0;
    virtual std::uint32_t* tags() = 0;
    virtual std::uint16_t* types() = 0;
    virtual std::vector<double> box() const = 0;
    virtual std::vector<bool> periodic() const = 0; // per axis; false: a wall
    virtual const std::vector<Species>& species() const = 0;
    virtual double time() const = 0;
    virtual std::uint64_t step() const = 0;
    virtual double polar_order() const = 0;
    virtual double kinetic_energy() const = 0;
    virtual void write_vtp(const std::filesystem::path& path) const = 0;
    virtual void write_json(const std::filesystem::path& path) const = 0;
    // Throws RunError naming the first particle with a non-finite position or director,
    // or a position outside the box on a periodic axis (what a user's write can break).
    virtual void check_arrays(const std::string& context) const = 0;
};

// Reads a start as `pedesis run`'s [initial] file does (io/particle_file.hpp): the ABP
// tutorial's JSON (pedesis init random, or the tutorial's random_init), or frame `frame`
// of a GSD or extended XYZ file (unset: the last): box, positions, directors, types,
// radii; `dim` 0 takes the dimension from the file.
std::unique_ptr<SystemModel> read_system(const std::filesystem::path& path, int dim,
                                         std::uint64_t seed,
                                         std::optional<std::int64_t> frame = std::nullopt);

struct RunHooks {
    std::uint64_t every = 0;                    // steps between calls of between_steps
    std::function<void(std::uint64_t)> between; // called with the step, storage in tag order
};

class EvolverModel {
  public:
    virtual ~EvolverModel() = default;
    virtual void add(const PluginSpec& spec) = 0;
    // Advances `steps` steps of dt through the one run loop (run/simulation.hpp), without a
    // run directory; a caught signal (core/interrupt.hpp) ends it early at a step boundary.
    // Leaves the storage in tag order on return, also when a hook throws.
    virtual void run(std::uint64_t steps, double dt, const RunHooks& hooks) = 0;
    virtual std::uint64_t list_builds() const = 0;
    virtual double list_cutoff() const = 0;
    virtual double potential_energy() = 0;
    virtual std::vector<std::string> terms() const = 0;
};

std::unique_ptr<EvolverModel> make_evolver(SystemModel& system, double rcut, double pad,
                                           std::uint64_t seed, std::uint64_t sort_every);

} // namespace pedesis::python
