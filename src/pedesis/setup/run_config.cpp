#include "pedesis/setup/run_config.hpp"

#include "pedesis/core/ball_volume.hpp"
#include "pedesis/core/error.hpp"
#include "pedesis/core/machine_memory.hpp"
#include "pedesis/core/stage.hpp"
#include "pedesis/io/config_table.hpp"
#include "pedesis/io/frame_writers.hpp"
#include "pedesis/observe/quantities.hpp"
#include "pedesis/setup/hard_driving_config.hpp"
#include "pedesis/setup/lattice.hpp"
#include "pedesis/setup/minimize_config.hpp"
#include "pedesis/setup/moving_wall_config.hpp"
#include "pedesis/setup/velocities.hpp"
#include "pedesis/soft/integrator_set.hpp"
#include "pedesis/soft/plugin_registry.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <limits>
#include <set>

namespace pedesis {

namespace {

void read_box(ConfigTable& t, RunConfig& c) {
    auto box = t.table("box");
    if (!box) throw InputError(c.file + ": missing [box] table");
    const auto d = static_cast<std::size_t>(c.dimension);
    if (box->has("lengths") && box->has("length"))
        throw InputError(box->where("length") + ": give either length or lengths, not both");
    if (auto ls = box->numbers("lengths", d)) {
        c.box_lengths = *ls;
        c.lengths_where = box->where("lengths");
    } else if (auto l = box->number("length")) {
        c.box_lengths.assign(d, *l);
        c.lengths_where = box->where("length");
    } else
        throw InputError(c.file + ": [box] needs length (cube) or lengths (one per axis)");
    double volume = 1.0;
    for (double l : c.box_lengths) {
        if (!(l > 0.0))
            throw InputError(box->where(box->has("lengths") ? "lengths" : "length") +
                             ": must be positive");
        volume *= l;
    }
    // a box whose volume overflows has no pressure, density or cell grid
    if (!(volume < 1e300))
        throw InputError(box->where(box->has("lengths") ? "lengths" : "length") +
                         ": the box is too large to simulate (its volume overflows)");
    if (box->has("boundary")) c.boundary_where = box->where("boundary");
    const auto b = box->strings("boundary", d).value_or(std::vector<std::string>(d, "periodic"));
    for (const auto& s : b) {
        if (s != "periodic" && s != "wall")
            throw InputError(box->where("boundary") + ": '" + s + "' is not periodic or wall");
        c.periodic.push_back(s == "periodic");
    }
    if (auto g = box->number("shear_rate")) {
        c.shear_where = box->where("shear_rate");
        if (!(std::isfinite(*g) && *g >= 0.0))
            throw InputError(c.shear_where + ": must be a finite number >= 0 (the flow runs along "
                                             "+x where y is larger)");
        if (*g > 0.0 && !(c.periodic[0] && c.periodic[1]))
            throw InputError(c.shear_where +
                             ": Lees–Edwards shear needs periodic x (the flow) "
                             "and y (the gradient) axes, and axis " +
                             (c.periodic[0] ? "y" : "x") + " is a wall");
        c.shear_rate = *g;
    }
    box->finish();
}

void read_velocity_keys(ConfigTable& t, SpeciesConfig& s, std::size_t d) {
    if (auto v = t.string("velocities")) {
        // checked at its line, as positions is (a typo used to name only the species)
        if (*v != "given") try {
                parse_velocity_kind(*v);
            } catch (const InputError& e) {
                throw InputError(t.where("velocities") + ": " + e.what());
            }
        s.velocities = *v;
    }
    if (auto v = t.number("speed")) s.speed = *v;
    if (auto v = t.number("sigma")) s.sigma = *v;
    if (auto v = t.number("temperature")) s.temperature = *v;
    if (auto v = t.numbers("velocity", d)) s.velocity = *v;
    if (s.speed < 0) throw InputError(t.where("speed") + ": must be >= 0");
    if (s.sigma < 0) throw InputError(t.where("sigma") + ": must be >= 0");
    if (s.temperature < 0) throw InputError(t.where("temperature") + ": must be >= 0");
    // m v^2 / 2 must stay a number: 1e100 leaves room for any mass a config can give
    constexpr double fastest = 1e100;
    if (s.speed > fastest) throw InputError(t.where("speed") + ": must be at most 1e100");
    if (s.sigma > fastest) throw InputError(t.where("sigma") + ": must be at most 1e100");
    if (s.temperature > fastest)
        throw InputError(t.where("temperature") + ": must be at most 1e100");
    if (s.velocity)
        for (double v : *s.velocity)
            if (std::abs(v) > fastest)
                throw InputError(t.where("velocity") +
                                 ": each component must be at most 1e100 in size (the kinetic "
                                 "energy would overflow)");
}

// A placement is checked where the config writes it, so that a typo is reported at its
// line ([initial] positions or a species' own).
void check_positions(const std::string& positions, const std::string& where, const RunConfig& c) {
    if (positions == "random" || positions == "point") return;
    if (positions == "file" && c.initial_file) return;
    const int dim = c.dimension;
    try {
        parse_lattice(positions, dim);
    } catch (const InputError&) {
        throw InputError(fmt::format(
            "{}: '{}' is not a placement: give random, point (with position = [..]), a lattice "
            "({}) or [initial] file = \"...\"",
            where, positions, dim == 2 ? "square or hexagonal in 2D" : "sc or fcc in 3D"));
    }
}

void read_species(ConfigTable& root, RunConfig& c, const SpeciesConfig& defaults) {
    auto list = root.tables("species");
    if (list.empty()) {
        // a soft run may take its species from the initial file's particle types
        if (c.soft() && c.initial_file) return;
        throw InputError(c.file + ": no [[species]] given");
    }
    const auto d = static_cast<std::size_t>(c.dimension);
    std::set<std::string> names;
    for (auto& t : list) {
        SpeciesConfig s = defaults;
        s.location = t.location();
        s.name = t.string("name").value_or(
            std::string(1, static_cast<char>('A' + c.species.size() % 26)));
        if (!valid_species_name(s.name))
            throw InputError(t.where("name") + ": species name '" + s.name +
                             "' must be 1 to 64 of the letters A-Z a-z, digits and _ - . + (it "
                             "names log columns and types in every output format)");
        if (!names.insert(s.name).second)
            throw InputError(t.where("name") + ": duplicate species name '" + s.name + "'");
        if (auto n = t.integer("count")) {
            if (*n <= 0)
                throw InputError(t.where("count") +
                                 ": must be a positive integer (N = 0 has nothing to simulate)");
            if (*n > 0xffffffffll)
                throw InputError(t.where("count") + ": " + std::to_string(*n) +
                                 " is more particles than the 4294967295 pedesis can number");
            s.count = static_cast<std::size_t>(*n);
            s.count_where = t.where("count");
        }
        s.radius = t.number("radius", 0.5);
        if (!(s.radius > 0)) throw InputError(t.where("radius") + ": must be positive");
        for (double l : c.box_lengths)
            if (!c.soft() && !(2.0 * s.radius < l))
                throw InputError(t.where("radius") + ": a particle of diameter " +
                                 fmt::format("{:g}", 2.0 * s.radius) +
                                 " does not fit in the box (edge " + fmt::format("{:g}", l) + ")");
        auto m = t.number("mass", true);
        s.mass = m.value_or(1.0);
        if (!(s.mass > 0))
            throw InputError(t.where("mass") + ": must be positive (inf makes a fixed obstacle)");
        if (auto p = t.string("positions")) {
            check_positions(*p, t.where("positions"), c);
            s.positions = *p;
        }
        if (auto r = t.table("region")) {
            s.region_lo = r->numbers("lo", d);
            s.region_hi = r->numbers("hi", d);
            if (!s.region_lo || !s.region_hi)
                throw InputError(t.where("region") + ": needs lo and hi");
            for (std::size_t a = 0; a < d; ++a)
                if (!((*s.region_lo)[a] < (*s.region_hi)[a]))
                    throw InputError(t.where("region") + ": lo must be below hi on every axis");
            r->finish();
        }
        s.point = t.numbers("position", d);
        if (s.point) s.positions = "point";
        read_velocity_keys(t, s, d);
        if (s.velocity && s.velocities != "given") s.velocities = "given";
        if (s.velocities == "given" && !s.velocity)
            throw InputError(t.where("velocities") + ": 'given' needs velocity = [..]");
        if (s.positions == "point" && !s.point)
            throw InputError(t.where("positions") + ": 'point' needs position = [..]");
        if (s.positions == "point" && s.count && *s.count != 1)
            throw InputError(t.where("count") +
                             ": a species placed at one point must have count = 1");
        if (s.positions == "point") s.count = 1;
        t.finish();
        c.species.push_back(s);
    }
}

// Any engine writes any frame format (io/frame_writers.hpp keeps the list).
std::vector<std::string> read_formats(const toml::table& doc, ConfigTable& out) {
    const toml::node* n = doc["output"]["formats"].node();
    const auto* arr = n ? n->as_array() : nullptr;
    const std::string list = frame_format_list();
    if (!arr) throw InputError(out.where("formats") + ": expected a list such as [" + list + "]");
    std::vector<std::string> formats;
    for (std::size_t k = 0; k < arr->size(); ++k) {
        auto s = (*arr)[k].value_exact<std::string>();
        if (!s || std::find(frame_formats.begin(), frame_formats.end(), *s) == frame_formats.end())
            throw InputError(out.where("formats") + ": each entry must be one of " + list);
        formats.push_back(*s);
    }
    out.strings("formats", arr->size()); // marks the key as read
    return formats;
}

std::uint64_t read_count(ConfigTable& t, const std::string& key, std::uint64_t fallback,
                         bool positive) {
    const auto v = t.integer(key);
    if (!v) return fallback;
    if (*v < 0 || (positive && *v == 0))
        throw InputError(t.where(key) +
                         (positive ? ": must be a positive integer" : ": must be an integer >= 0"));
    return static_cast<std::uint64_t>(*v);
}

// [stepped] of the time-stepped hard-particle engine.
void read_stepped_section(ConfigTable& root, RunConfig& c) {
    if (root.has("event"))
        throw InputError(root.where("event") +
                         ": [event] is for dynamics = \"event\"; the stepped engine is set up "
                         "in [stepped]");
    auto st = root.table("stepped");
    if (!st) throw InputError(c.file + ": dynamics = \"stepped\" needs a [stepped] table with dt");
    c.dt = st->required_number("dt");
    c.dt_where = st->where("dt");
    if (!(c.dt > 0)) throw InputError(c.dt_where + ": must be positive");
    c.max_move = st->number("max_move", c.max_move);
    if (!(c.max_move > 0 && c.max_move <= 1))
        throw InputError(st->where("max_move") +
                         ": must lie in (0, 1] (a fraction of the particle's radius)");
    read_gravity(*st, c);
    st->finish();
}

// [event] (or [stepped]), [run] and [output] of the hard-particle engines (times in
// simulation units).
void read_event_output(const toml::table& doc, ConfigTable& root, RunConfig& c);
void read_checkpoint_seconds(ConfigTable& out, RunConfig& c);

// [event] thermostat = "rescale", temperature and thermostat_interval (by default, the
// time in which a particle of the heaviest species at that temperature moves half the
// smallest diameter).
void read_event_thermostat(ConfigTable& ev, RunConfig& c) {
    const auto kind = ev.string("thermostat");
    if (!kind) {
        for (const char* key : {"temperature", "thermostat_interval"})
            if (ev.has(key))
                throw InputError(ev.where(key) + ": needs event.thermostat = \"rescale\"");
        return;
    }
    c.thermostat_where = ev.where("thermostat");
    if (*kind == "andersen") return read_andersen(ev, c);
    if (*kind != "rescale")
        throw InputError(c.thermostat_where + ": unknown thermostat '" + *kind +
                         "' (the event engine has \"rescale\" and \"andersen\")");
    if (!ev.has("temperature"))
        throw InputError(c.thermostat_where + ": needs event.temperature (the temperature held)");
    c.thermostat_temperature = ev.number("temperature", 0.0);
    if (!(c.thermostat_temperature > 0.0 && c.thermostat_temperature <= 1e100))
        throw InputError(ev.where("temperature") + ": must be a positive number (at most 1e100)");
    if (c.growth_rate > 0.0)
        throw InputError(c.thermostat_where +
                         ": growth (event.growth_rate) holds the kinetic energy itself; use one "
                         "or the other");
    double smallest = std::numeric_limits<double>::infinity(), heaviest = 0.0;
    for (const auto& s : c.species) {
        smallest = std::min(smallest, 2.0 * s.radius);
        if (std::isfinite(s.mass)) heaviest = std::max(heaviest, s.mass);
    }
    const double fallback = heaviest > 0.0 && std::isfinite(smallest)
                                ? 0.5 * smallest * std::sqrt(heaviest / c.thermostat_temperature)
                                : 1.0;
    c.thermostat_interval = ev.number("thermostat_interval", fallback);
    if (!(c.thermostat_interval > 0.0 && std::isfinite(c.thermostat_interval)))
        throw InputError(ev.where("thermostat_interval") + ": must be a positive finite number");
}

void read_event_sections(const toml::table& doc, ConfigTable& root, RunConfig& c) {
    const bool stepped = c.dynamics == "stepped";
    if (stepped)
        read_stepped_section(root, c);
    else if (root.has("stepped"))
        throw InputError(root.where("stepped") +
                         ": [stepped] is for dynamics = \"stepped\" (this config runs \"" +
                         c.dynamics + "\")");
    if (auto ev = stepped ? std::optional<ConfigTable>{} : root.table("event")) {
        c.restitution = ev->number("restitution", 1.0);
        c.wall_restitution = ev->number("wall_restitution", 1.0);
        if (!(c.restitution >= 0 && c.restitution <= 1))
            throw InputError(ev->where("restitution") + ": must lie in [0, 1]");
        if (!(c.wall_restitution >= 0 && c.wall_restitution <= 1))
            throw InputError(ev->where("wall_restitution") + ": must lie in [0, 1]");
        c.tc = ev->number("tc", 0.0);
        if (c.tc < 0) throw InputError(ev->where("tc") + ": must be >= 0");
        c.skin = ev->number("skin", -1.0);
        if (ev->has("skin") && !(c.skin > 0))
            throw InputError(ev->where("skin") + ": must be positive");
        c.check_overlaps = ev->boolean("check_overlaps").value_or(false);
        c.growth_rate = ev->number("growth_rate", 0.0);
        if (!(c.growth_rate >= 0))
            throw InputError(ev->where("growth_rate") + ": must be >= 0 (0: no growth)");
        c.growth_packing_fraction = ev->number("growth_packing_fraction", 0.0);
        if (ev->has("growth_packing_fraction") &&
            !(c.growth_packing_fraction > 0 && c.growth_packing_fraction < 1))
            throw InputError(ev->where("growth_packing_fraction") + ": must lie in (0, 1)");
        c.growth_max_pressure = ev->number("growth_max_pressure", c.growth_max_pressure);
        if (!(c.growth_max_pressure > 1))
            throw InputError(ev->where("growth_max_pressure") +
                             ": must exceed 1 (a reduced pressure PV/(NkT))");
        for (const char* key : {"growth_packing_fraction", "growth_max_pressure"})
            if (ev->has(key) && c.growth_rate == 0)
                throw InputError(ev->where(key) + ": needs event.growth_rate > 0");
        read_gravity(*ev, c);
        read_driving(*ev, c);
        read_moving_wall(*ev, c);
        read_event_thermostat(*ev, c);
        ev->finish();
    }

    const std::string stops = stepped ? "time, steps, collisions_per_particle"
                                      : "time, collisions_per_particle, energy_fraction, grown";
    auto run = root.table("run");
    if (!run && c.scripted) return read_event_output(doc, root, c);
    if (!run)
        throw InputError(c.file + ": missing [run] table (give at least one of " + stops + ")");
    c.stop_time = run->number("time");
    c.stop_collisions_per_particle = run->number("collisions_per_particle");
    if (stepped) {
        if (run->has("energy_fraction"))
            throw InputError(run->where("energy_fraction") +
                             ": the stepped engine is elastic, so the kinetic energy never "
                             "changes; stop on time, steps or collisions_per_particle");
        if (run->has("steps")) c.stop_steps = read_count(*run, "steps", 0, true);
    } else {
        c.stop_energy_fraction = run->number("energy_fraction");
        c.stop_when_grown = run->boolean("grown").value_or(false);
        if (c.stop_when_grown && c.growth_rate == 0)
            throw InputError(run->where("grown") + ": needs event.growth_rate > 0");
    }
    if (c.stop_time && !(*c.stop_time > 0))
        throw InputError(run->where("time") + ": must be positive");
    if (c.stop_collisions_per_particle && !(*c.stop_collisions_per_particle > 0))
        throw InputError(run->where("collisions_per_particle") + ": must be positive");
    if (c.stop_energy_fraction && !(*c.stop_energy_fraction > 0 && *c.stop_energy_fraction < 1))
        throw InputError(run->where("energy_fraction") + ": must lie in (0, 1)");
    if (!c.scripted && !c.stop_time && !c.stop_collisions_per_particle && !c.stop_energy_fraction &&
        !c.stop_steps && !c.stop_when_grown)
        throw InputError(c.file + ": [run] needs at least one of " + stops);
    run->finish();

    if (!c.gravity.empty() && c.stop_energy_fraction)
        throw InputError(run->where("energy_fraction") +
                         ": under gravity kinetic and potential energy trade; stop on run.time "
                         "or run.collisions_per_particle");
    if (c.shear_rate > 0.0) {
        if (c.growth_rate > 0.0)
            throw InputError(c.shear_where + ": growth (event.growth_rate) and Lees–Edwards shear "
                                             "cannot run together");
        if (c.stop_energy_fraction)
            throw InputError(run->where("energy_fraction") +
                             ": under shear the viscous heating feeds the energy; stop on "
                             "run.time or run.collisions_per_particle");
    }
    if (c.stop_energy_fraction && !c.stop_time && !c.stop_collisions_per_particle &&
        c.restitution == 1.0 && c.wall_restitution == 1.0)
        throw InputError(
            run->where("energy_fraction") +
            ": can never be reached with elastic collisions (event.restitution = 1 and "
            "event.wall_restitution = 1); add run.time or run.collisions_per_particle");
    read_event_output(doc, root, c);
}

void read_event_output(const toml::table& doc, ConfigTable& root, RunConfig& c) {
    if (auto out = root.table("output")) {
        c.log_interval = out->number("log_interval", c.log_interval);
        if (!(c.log_interval > 0))
            throw InputError(out->where("log_interval") + ": must be positive");
        c.snapshot_interval = out->number("snapshot_interval", 0.0);
        if (c.snapshot_interval < 0)
            throw InputError(out->where("snapshot_interval") + ": must be >= 0");
        if (out->has("formats")) c.formats = read_formats(doc, *out);
        if (auto b = out->integer("histogram_bins")) {
            if (*b < 1 || *b > 100000)
                throw InputError(out->where("histogram_bins") + ": must lie in [1, 100000]");
            c.histogram_bins = static_cast<int>(*b);
        }
        c.histogram_start = out->number("histogram_start");
        c.checkpoint_interval = out->number("checkpoint_interval", 0.0);
        if (c.checkpoint_interval < 0)
            throw InputError(out->where("checkpoint_interval") + ": must be >= 0");
        read_checkpoint_seconds(*out, c);
        c.progress = out->boolean("progress").value_or(true);
        out->finish();
    }
}

std::string other_engine_note(const std::string& key, const RunConfig& c); // (below)

// [output] checkpoint_seconds, every engine's: wall-clock seconds between checkpoints.
void read_checkpoint_seconds(ConfigTable& out, RunConfig& c) {
    c.checkpoint_seconds = out.number("checkpoint_seconds", 0.0);
    if (!(c.checkpoint_seconds >= 0 && std::isfinite(c.checkpoint_seconds)))
        throw InputError(out.where("checkpoint_seconds") + ": must be >= 0 (0: none)");
}

// [neighbor_list], [[force]], [[torque]], [[integrator]], [run] and [output] of the soft
// engines (intervals in steps).
void read_soft_sections(const toml::table& doc, ConfigTable& root, RunConfig& c) {
    if (auto nl = root.table("neighbor_list")) {
        c.list_r_cut = nl->number("r_cut", 0.0);
        if (nl->has("r_cut") && !(c.list_r_cut > 0))
            throw InputError(nl->where("r_cut") + ": must be positive");
        if (nl->has("pad") && nl->has("skin"))
            throw InputError(nl->where("pad") + ": give skin or pad (the same thing), not both");
        const std::string skin_key = nl->has("pad") ? "pad" : "skin";
        c.list_skin = nl->number(skin_key, c.list_skin);
        if (!(c.list_skin > 0)) throw InputError(nl->where(skin_key) + ": must be positive");
        c.sort_every = read_count(*nl, "sort_every", c.sort_every, false);
        nl->finish();
    }
    if (auto word = root.string("precision")) {
        const auto precision = precision_named(*word);
        if (!precision)
            throw InputError(root.where("precision") + ": must be \"double\" or \"mixed\", not \"" +
                             *word + "\"");
        c.precision = *precision;
        c.precision_where = root.where("precision");
    }
    for (auto& t : root.tables("force")) c.forces.push_back(read_plugin(t, PluginKind::force));
    for (auto& t : root.tables("torque")) c.torques.push_back(read_plugin(t, PluginKind::torque));
    for (auto& t : root.tables("integrator"))
        c.integrators.push_back(read_plugin(t, PluginKind::integrator));

    if (c.dynamics == "minimize") {
        check_minimize_terms(c.forces, c.torques, c.integrators);
    } else {
        // the rule the Python Evolver follows too (soft/integrator_set.hpp), and the position
        // integrator is the one `dynamics` names
        for (std::size_t k = 0; k < c.integrators.size(); ++k)
            check_integrator_added({c.integrators.begin(), c.integrators.begin() + k},
                                   c.integrators[k], PluginNaming::config);
        check_integrators_complete(c.integrators, c.torques,
                                   c.file + ": dynamics = \"" + c.dynamics +
                                       "\" needs an [[integrator]] with name = \"" + c.dynamics +
                                       "\"",
                                   PluginNaming::config);
        const auto mover =
            std::find_if(c.integrators.begin(), c.integrators.end(), moves_positions);
        if (mover->name != c.dynamics)
            throw InputError(root.where("dynamics") + ": is '" + c.dynamics +
                             "' but the position integrator is '" + mover->name + "'");
    }

    auto run = root.table("run");
    if (!run) throw InputError(c.file + ": missing [run] table (give steps and dt)");
    c.steps = read_count(*run, "steps", 0, true);
    if (!run->has("steps"))
        throw InputError(run->where("steps") + ": is required" +
                         (run->has("time") ? " (run.time: " + other_engine_note("run.time", c) + ")"
                                           : std::string()));
    c.dt = run->required_number("dt");
    if (!(c.dt > 0)) throw InputError(run->where("dt") + ": must be positive");
    if (auto device = run->string("device")) {
        if (*device != "cpu" && *device != "gpu")
            throw InputError(run->where("device") + ": must be \"cpu\" or \"gpu\", not \"" +
                             *device + "\"");
        c.device = *device;
        c.device_where = run->where("device");
    }
    run->finish();
    if (c.dynamics == "minimize") c.minimize = read_minimize_config(root, c.dt, c.list_skin);

    c.formats = {"vtp", "gsd"};
    if (auto out = root.table("output")) {
        c.log_every = read_count(*out, "log_every", c.log_every, true);
        c.snapshot_every = read_count(*out, "snapshot_every", 0, false);
        c.checkpoint_every = read_count(*out, "checkpoint_every", 0, false);
        read_checkpoint_seconds(*out, c);
        if (out->has("formats")) c.formats = read_formats(doc, *out);
        c.progress = out->boolean("progress").value_or(true);
        out->finish();
    }
}

// Refuses, before anything is allocated, particle counts that cannot be simulated: more
// than the 32-bit ids hold, more than the machine's memory (an estimate, per engine), or
// hard particles that fill more of the box than close packing allows.
void check_particle_budget(const RunConfig& c) {
    std::uint64_t n = 0;
    double filled = 0.0;
    std::string where = c.file; // the last count given: where the sum went too far
    for (const auto& s : c.species) {
        if (!s.count) continue;
        n += *s.count;
        where = s.count_where;
        filled += static_cast<double>(*s.count) * ball_volume(s.radius, c.dimension);
    }
    if (n == 0) return;
    if (n > 0xffffffffull)
        throw InputError(fmt::format("{}: N = {} particles, more than the "
                                     "4294967295 pedesis can number",
                                     where, n));
    // bytes per particle at the largest point of a run, from docs/performance.md's
    // measurements with room to spare (the event engine keeps neighbour lists and events)
    const double per_particle = c.soft() ? 400.0 : c.dynamics == "stepped" ? 300.0 : 600.0;
    const double need = static_cast<double>(n) * per_particle;
    const double have = physical_memory_bytes();
    if (have > 0.0 && need > have)
        throw InputError(fmt::format("{}: N = {} particles need about {:.3g} GB "
                                     "({:g} bytes each, an estimate), more than this machine's "
                                     "{:.3g} GB of memory",
                                     where, n, need / 1e9, per_particle, have / 1e9));
    if (c.soft() || c.box_lengths.empty()) return;
    double volume = 1.0;
    for (double l : c.box_lengths) volume *= l;
    const double densest = c.dimension == 2 ? 0.9069 : 0.7405; // hexagonal / fcc packing
    if (filled / volume > densest) {
        // the box that would hold them at close packing, as a cube (square) of this shape
        const double grow = std::pow(filled / volume / densest, 1.0 / c.dimension);
        std::string lengths;
        for (double l : c.box_lengths)
            lengths += fmt::format("{}{:.4g}", lengths.empty() ? "" : " x ", l * grow);
        throw InputError(fmt::format(
            "{}: the particles would fill {:.4g} of the box (packing fraction "
            "{:.4g}: their {} add up to {:.4g} times the box's); hard {} cannot fill more than "
            "{} of it (close packing). Give a box of at least {} (larger still to place them "
            "at random: that works up to about {}), or fewer particles",
            where, filled / volume, filled / volume, c.dimension == 2 ? "areas" : "volumes",
            filled / volume, c.dimension == 2 ? "disks" : "spheres", densest, lengths,
            c.dimension == 2 ? "0.5" : "0.35"));
    }
}

// Keys that some engines read and others do not: a config that gives one to the wrong
// engine is told whose key it is, and what this engine takes instead, rather than only
// "unknown key" (a soft config with [run] time, an event config with [[force]]).
struct EngineKey {
    const char* key;          // full key, as ConfigTable names it
    const char* engines;      // the dynamics that read it, as a config names them
    const char* soft_instead; // for a soft config (brownian, langevin, nve): what to give
    const char* hard_instead; // for an event or stepped config
};

constexpr EngineKey engine_keys[] = {
    {"neighbor_list", "brownian, langevin and nve", nullptr, nullptr},
    {"force", "brownian, langevin and nve", nullptr,
     "hard particles interact by contact alone (their radius in [[species]])"},
    {"torque", "brownian, langevin and nve", nullptr, nullptr},
    {"integrator", "brownian, langevin and nve", nullptr,
     "the event engine is exact; the stepped engine's step is [stepped] dt"},
    {"run.steps", "stepped, brownian, langevin and nve", nullptr,
     "stop the event engine on run.time, run.collisions_per_particle or run.energy_fraction"},
    {"run.dt", "brownian, langevin and nve", nullptr,
     "the event engine has no time step; the stepped engine's is [stepped] dt"},
    {"run.device", "brownian, langevin and nve", nullptr, "the hard engines run on the CPU"},
    {"precision", "brownian, langevin and nve", nullptr,
     "the hard engines compute in double, exactly"},
    {"output.log_every", "brownian, langevin and nve", nullptr,
     "output.log_interval (in time units)"},
    {"output.snapshot_every", "brownian, langevin and nve", nullptr,
     "output.snapshot_interval (in time units)"},
    {"output.checkpoint_every", "brownian, langevin and nve", nullptr,
     "output.checkpoint_interval (in time units)"},
    {"minimize", "minimize", nullptr, nullptr},
    {"event", "event", "the soft engines' terms are [[force]], [[torque]] and [[integrator]]",
     "[stepped] (this config's dynamics)"},
    {"run.time", "event and stepped", "the run lasts run.steps x run.dt", nullptr},
    {"run.collisions_per_particle", "event and stepped", "give run.steps", nullptr},
    {"run.energy_fraction", "event", "give run.steps", nullptr},
    {"run.grown", "event", "give run.steps", nullptr},
    {"output.log_interval", "event and stepped", "output.log_every (in steps)", nullptr},
    {"output.snapshot_interval", "event and stepped", "output.snapshot_every (in steps)", nullptr},
    {"output.checkpoint_interval", "event and stepped", "output.checkpoint_every (in steps)",
     nullptr},
    {"output.histogram_bins", "event and stepped", nullptr, nullptr},
    {"output.histogram_start", "event and stepped", nullptr, nullptr},
};

std::string other_engine_note(const std::string& key, const RunConfig& c) {
    for (const EngineKey& k : engine_keys) {
        if (key != k.key) continue;
        const char* instead = c.soft() ? k.soft_instead : k.hard_instead;
        return fmt::format("it is read by dynamics = {}, and this config runs \"{}\"{}{}",
                           k.engines, c.dynamics, instead ? "; " : "", instead ? instead : "");
    }
    return {};
}

} // namespace

namespace {

RunConfig read_run_config(const toml::table& doc, const std::string& path, bool scripted) {
    ConfigTable root(doc, path);
    RunConfig c;
    c.scripted = scripted;
    c.file = path;
    // (c.dynamics is read below, before any table could be finished)
    root.explain_unknown_keys([&c](const std::string& key) { return other_engine_note(key, c); });
    const auto dim = root.integer("dimension").value_or(2);
    if (dim != 2 && dim != 3) throw InputError(root.where("dimension") + ": must be 2 or 3");
    c.dimension = static_cast<int>(dim);
    c.dynamics = root.string("dynamics").value_or("event");
    if (c.dynamics != "event" && c.dynamics != "stepped" && c.dynamics != "brownian" &&
        c.dynamics != "langevin" && c.dynamics != "nve" && c.dynamics != "bussi" &&
        c.dynamics != "nose_hoover" && c.dynamics != "minimize")
        throw InputError(
            root.where("dynamics") + ": '" + c.dynamics +
            "' is not available (this build has: event, stepped, brownian, langevin, nve, bussi, "
            "nose_hoover, minimize)");
    if (auto s = root.integer("seed")) {
        if (*s < 0) throw InputError(root.where("seed") + ": must be >= 0");
        c.seed = static_cast<std::uint64_t>(*s);
    }

    SpeciesConfig defaults;
    defaults.positions = "random";
    defaults.velocities = c.soft() ? "zero" : "maxwell_boltzmann";
    if (auto init = root.table("initial")) {
        if (auto p = init->string("positions")) {
            check_positions(*p, init->where("positions"), c);
            defaults.positions = *p;
        }
        read_velocity_keys(*init, defaults, static_cast<std::size_t>(c.dimension));
        if (defaults.velocity) defaults.velocities = "given";
        if (auto f = init->string("file")) {
            std::filesystem::path p(*f);
            if (p.is_relative()) p = std::filesystem::path(path).parent_path() / p;
            c.initial_file = p.string();
            defaults.positions = "file";
        }
        // which frame of a GSD or XYZ file (the reader checks it against the file)
        if (auto k = init->integer("frame")) {
            if (!c.initial_file)
                throw InputError(init->where("frame") + ": a frame of what? give [initial] file");
            c.initial_frame = *k;
        }
        c.zero_momentum = init->boolean("zero_momentum").value_or(true);
        c.min_distance = init->number("min_distance", 0.0);
        init->finish();
    }
    if (root.has("box") || !(c.soft() && c.initial_file)) read_box(root, c);
    c.species_defaults = defaults;
    read_species(root, c, defaults);
    check_particle_budget(c);
    if (c.soft())
        read_soft_sections(doc, root, c);
    else
        read_event_sections(doc, root, c);
    read_transport_config(root, c.transport);
    read_barostat_config(root, c.dynamics, c.barostat);
    if (auto log = root.table("log")) {
        if (log->has("quantities")) {
            const toml::node* n = doc["log"]["quantities"].node();
            const auto* arr = n ? n->as_array() : nullptr;
            if (!arr || arr->empty())
                throw InputError(log->where("quantities") +
                                 ": expected a non-empty list of names such as [\"time\", "
                                 "\"temperature\"]");
            for (std::size_t k = 0; k < arr->size(); ++k) {
                const auto name = (*arr)[k].value_exact<std::string>();
                if (!name)
                    throw InputError(log->where("quantities") + ": entry " + std::to_string(k) +
                                     " is not a string");
                if (!find_quantity(*name))
                    throw InputError(log->where("quantities") + ": unknown quantity '" + *name +
                                     "' (known: " + quantity_names() +
                                     "; `pedesis run --list-quantities` explains each)");
                if (std::find(c.log_quantities.begin(), c.log_quantities.end(), *name) !=
                    c.log_quantities.end())
                    throw InputError(log->where("quantities") + ": '" + *name +
                                     "' is listed twice");
                c.log_quantities.push_back(*name);
            }
            log->strings("quantities", arr->size()); // marks the key as read
            c.log_quantities_where = log->where("quantities");
        }
        log->finish();
    }
    root.finish();
    return c;
}

} // namespace

// A species name is a column of log.csv, a type of GSD and XYZ and a key of JSON: letters,
// digits and a few marks that every one of those formats takes as they are.
bool valid_species_name(const std::string& name) {
    if (name.empty() || name.size() > 64) return false;
    for (const char ch : name) {
        const bool ok = (ch >= 'a' && ch <= 'z') || (ch >= 'A' && ch <= 'Z') ||
                        (ch >= '0' && ch <= '9') || ch == '_' || ch == '-' || ch == '.' ||
                        ch == '+';
        if (!ok) return false;
    }
    return true;
}

RunConfig load_run_config(const std::string& path, bool scripted) {
    enter_stage("reading the config");
    return read_run_config(parse_toml_file(path), path, scripted);
}

RunConfig parse_run_config(const std::string& text, const std::string& name, bool scripted) {
    return read_run_config(parse_toml_text(text, name), name, scripted);
}

} // namespace pedesis
