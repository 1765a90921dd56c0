#include "pedesis/setup/hard_driving_config.hpp"

#include "pedesis/core/error.hpp"

#include <fmt/format.h>

#include <cmath>

namespace pedesis {

namespace {
double positive(ConfigTable& t, const std::string& key, const std::string& needed_by) {
    if (!t.has(key)) throw InputError(needed_by + ": needs " + t.full_key(key));
    const double v = t.number(key, 0.0);
    if (!(v > 0.0 && v <= 1e100))
        throw InputError(t.where(key) + ": must be a positive number (at most 1e100)");
    return v;
}
} // namespace

void read_gravity(ConfigTable& t, RunConfig& c) {
    const auto d = static_cast<std::size_t>(c.dimension);
    auto g = t.numbers("gravity", d);
    if (!g) return;
    for (std::size_t a = 0; a < d; ++a) {
        if (!(std::abs((*g)[a]) <= 1e100))
            throw InputError(t.where("gravity") + ": components must be at most 1e100");
        if ((*g)[a] != 0.0 && a < c.periodic.size() && c.periodic[a])
            throw InputError(fmt::format(
                "{}: component {:g} along axis {}, which is periodic: the particles would fall "
                "for ever (no stationary state); make that axis a wall ([box] boundary) or give 0",
                t.where("gravity"), (*g)[a], "xyz"[a]));
    }
    if (c.shear_rate > 0.0)
        throw InputError(t.where("gravity") + ": not with Lees-Edwards shear ([box] shear_rate)");
    for (const auto& s : c.species)
        if (std::isinf(s.mass))
            throw InputError(t.where("gravity") + ": species '" + s.name +
                             "' is a fixed obstacle (mass = inf), which does not fall; not with "
                             "gravity");
    c.gravity = *g;
}

void read_andersen(ConfigTable& ev, RunConfig& c) {
    if (ev.has("thermostat_interval"))
        throw InputError(ev.where("thermostat_interval") +
                         ": is for thermostat = \"rescale\"; the Andersen thermostat takes "
                         "thermostat_rate");
    c.andersen_rate = positive(ev, "thermostat_rate", c.thermostat_where);
    c.andersen_temperature = positive(ev, "temperature", c.thermostat_where);
    if (c.growth_rate > 0.0)
        throw InputError(c.thermostat_where + ": not with growth (event.growth_rate)");
    if (c.shear_rate > 0.0)
        throw InputError(c.thermostat_where + ": not with Lees-Edwards shear ([box] shear_rate)");
}

void read_driving(ConfigTable& ev, RunConfig& c) {
    if (ev.has("thermostat_rate") && !ev.has("thermostat"))
        throw InputError(ev.where("thermostat_rate") + ": needs event.thermostat = \"andersen\"");
    const auto kind = ev.string("driving");
    if (!kind) {
        for (const char* key : {"driving_rate", "driving_strength"})
            if (ev.has(key))
                throw InputError(ev.where(key) + ": needs event.driving = \"white_noise\"");
        return;
    }
    const std::string where = ev.where("driving");
    if (*kind != "white_noise")
        throw InputError(where + ": unknown driving '" + *kind +
                         "' (the event engine has \"white_noise\")");
    c.driving_rate = positive(ev, "driving_rate", where);
    c.driving_strength = positive(ev, "driving_strength", where);
    if (c.growth_rate > 0.0) throw InputError(where + ": not with growth (event.growth_rate)");
    if (c.shear_rate > 0.0)
        throw InputError(where + ": not with Lees-Edwards shear ([box] shear_rate)");
}

} // namespace pedesis
