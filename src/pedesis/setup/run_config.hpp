#pragma once
// The contents of a run's TOML config, validated. Every key is documented in
// docs/config.md; unknown keys are errors.
#include "pedesis/core/precision.hpp"
#include "pedesis/event/moving_wall.hpp"
#include "pedesis/setup/barostat_config.hpp"
#include "pedesis/setup/transport_config.hpp"
#include "pedesis/soft/fire_params.hpp"
#include "pedesis/soft/plugin_spec.hpp"

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

namespace pedesis {

struct SpeciesConfig {
    std::string name;
    std::optional<std::size_t> count; // may come from the initial-configuration file
    std::string count_where;          // "file:line:col: key '...count'", for messages
    std::string location;             // "file:line:col" of its [[species]] table
    double radius = 0.5;
    double mass = 1.0;
    // placement (defaults from [initial])
    std::string positions; // random | square | hexagonal | sc | fcc | point
    std::optional<std::vector<double>> region_lo, region_hi;
    std::optional<std::vector<double>> point; // positions = "point": every particle here (count 1)
    // velocities (defaults from [initial])
    std::string velocities; // zero | equal_speed | uniform | normal | maxwell_boltzmann | given
    double speed = 1.0, sigma = 1.0, temperature = 1.0;
    std::optional<std::vector<double>> velocity; // velocities = "given"
};

struct RunConfig {
    std::string file; // where it came from, for messages
    int dimension = 2;
    std::string dynamics = "event"; // event | stepped | brownian | langevin | nve | minimize
    // the soft/active engines; event and stepped are the hard-particle engines
    bool soft() const { return dynamics != "event" && dynamics != "stepped"; }
    // A script (the Python module) gives the stop conditions: a hard-particle config
    // needs no [run] then.
    bool scripted = false;
    std::uint64_t seed = 1;

    std::vector<double> box_lengths; // soft engines: may be empty (box from the initial file)
    std::vector<bool> periodic;
    std::string boundary_where; // "file:line:col: key 'box.boundary'" if given, for messages
    std::string lengths_where;  // of box.length or box.lengths, for messages
    // [box] shear_rate: Lees-Edwards shear along x, gradient along y (0: none)
    double shear_rate = 0.0;
    std::string shear_where; // of box.shear_rate, for messages

    std::vector<SpeciesConfig> species;
    SpeciesConfig species_defaults; // from [initial], for species a soft run takes from its file

    // a start: the tutorial's JSON, a GSD or an extended XYZ file (io/particle_file.hpp)
    std::optional<std::string> initial_file;
    std::optional<std::int64_t> initial_frame; // of a GSD or XYZ file; unset: the last
    bool zero_momentum = true;
    double min_distance = 0.0;

    // [event]
    double restitution = 1.0;
    double wall_restitution = 1.0;
    double tc = 0.0;
    double skin = -1.0;
    bool check_overlaps = false;
    double growth_rate = 0.0; // Lubachevsky-Stillinger growth (see EventParams)
    double growth_packing_fraction = 0.0;
    double growth_max_pressure = 1e3;
    // [event] thermostat = "rescale": temperature and interval (0: no thermostat)
    double thermostat_temperature = 0.0;
    double thermostat_interval = 0.0;
    std::string thermostat_where; // of event.thermostat, for messages
    // [event] gravity (also [stepped] gravity; empty: none), thermostat = "andersen" and
    // driving = "white_noise" (setup/hard_driving_config.hpp; the meanings: EventParams)
    std::vector<double> gravity;
    double andersen_rate = 0.0, andersen_temperature = 0.0;
    double driving_rate = 0.0, driving_strength = 0.0;
    // [event.moving_wall] (setup/moving_wall_config.hpp): the axis of the face that moves
    // (-1: none), whether it is the upper face, and how it moves
    int moving_wall_axis = -1;
    bool moving_wall_upper = false;
    WallMotion moving_wall{};

    // [stepped] (dynamics = stepped): the time step is `dt` below, the other keys of [run]
    // and [output] are the event engine's, and [run] steps is a stop condition too
    double max_move = 0.5; // largest move in one step, in radii
    std::string dt_where;  // "file:line:col: key 'stepped.dt'", for messages
    std::optional<std::uint64_t> stop_steps;

    // [run] (at least one stop condition)
    std::optional<double> stop_time;
    std::optional<double> stop_collisions_per_particle;
    std::optional<double> stop_energy_fraction;
    bool stop_when_grown = false; // [run] grown = true: stop when growth ends

    // [output]
    double log_interval = 1.0;
    double snapshot_interval = 0.0; // 0: first and last frame only
    std::vector<std::string> formats = {"gsd"};
    // [log] quantities: the columns of log.csv, in order (empty: all the engine measures)
    std::vector<std::string> log_quantities;
    std::string log_quantities_where; // for messages
    int histogram_bins = 50;
    std::optional<double> histogram_start; // unset: histogram of the final state only
    double checkpoint_interval = 0.0;      // 0: only at the end
    double checkpoint_seconds = 0.0;       // [output], every engine: wall clock (0: none)
    bool progress = true;

    // soft / active engines (dynamics = brownian, langevin or nve)
    std::vector<PluginSpec> forces, torques, integrators;
    double list_r_cut = 0.0; // 0: the largest interaction range
    double list_skin = 0.5;
    std::uint64_t sort_every = 500;        // steps between space-filling-curve sorts (0: never)
    std::string device = "cpu";            // soft engines: "cpu" or "gpu" (gpu/gpu_stepper.hpp)
    std::string device_where;              // of [run] device if given, for messages
    Precision precision = Precision::full; // the pair rows' (core/precision.hpp)
    std::string precision_where;           // of precision if given, for messages
    std::uint64_t steps = 0;
    double dt = 0.0; // also the time step of the stepped engine
    std::uint64_t log_every = 100;
    std::uint64_t snapshot_every = 0;   // 0: first and last frame only
    std::uint64_t checkpoint_every = 0; // 0: only at the end

    TransportConfig transport; // [transport]
    FireParams minimize;       // [minimize] of dynamics = "minimize" (FIRE)
    BarostatConfig barostat;   // [barostat]
};

// Whether `name` can name a species: 1 to 64 of A-Z a-z 0-9 _ - . + (it names log
// columns, and types in every output format).
bool valid_species_name(const std::string& name);

RunConfig load_run_config(const std::string& path, bool scripted = false);
// The same from TOML text (the Python module's configs); messages name `name` as the
// file, and a relative [initial] file is taken from the working directory.
RunConfig parse_run_config(const std::string& text, const std::string& name, bool scripted);

} // namespace pedesis
