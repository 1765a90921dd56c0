#include "pedesis/setup/minimize_config.hpp"

#include "pedesis/core/error.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>

namespace pedesis {

void check_minimize_terms(const std::vector<PluginSpec>& forces,
                          const std::vector<PluginSpec>& torques,
                          const std::vector<PluginSpec>& integrators) {
    if (!integrators.empty())
        throw InputError(integrators.front().where +
                         ": dynamics = \"minimize\" moves the particles by FIRE and takes no "
                         "[[integrator]]; remove it (its settings are in [minimize])");
    if (!torques.empty())
        throw InputError(torques.front().where +
                         ": dynamics = \"minimize\" relaxes positions only, and a torque turns "
                         "directors that no energy depends on; remove the [[torque]]");
    for (const PluginSpec& f : forces)
        if (f.name == "self_propulsion" || f.name == "active_ou")
            throw InputError(f.where + ": " + f.name +
                             " is an active force, with no potential energy for dynamics = "
                             "\"minimize\" to minimise; remove it");
}

namespace {

double positive(ConfigTable& t, const char* key, double fallback) {
    const double v = t.number(key, fallback);
    if (!(v > 0.0 && std::isfinite(v))) throw InputError(t.where(key) + ": must be positive");
    return v;
}

// A factor in (lo, hi) or (lo, hi]: the message says which.
double factor(ConfigTable& t, const char* key, double fallback, double lo, double hi,
              bool hi_included) {
    const double v = t.number(key, fallback);
    if (!(v > lo && (hi_included ? v <= hi : v < hi)))
        throw InputError(fmt::format("{}: must lie in ({:g}, {:g}{}", t.where(key), lo, hi,
                                     hi_included ? "]" : ")"));
    return v;
}

} // namespace

FireParams read_minimize_config(ConfigTable& root, double dt, double skin) {
    FireParams p;
    p.dt_start = dt;
    p.dt_max = 10.0 * dt;
    p.dt_min = 0.02 * dt;
    p.max_move = std::min(p.max_move, skin);
    auto t = root.table("minimize");
    if (!t) return p;
    p.force_tolerance = positive(*t, "force_tolerance", p.force_tolerance);
    p.energy_tolerance = t->number("energy_tolerance", 0.0);
    if (!(p.energy_tolerance >= 0.0 && p.energy_tolerance < 1.0))
        throw InputError(t->where("energy_tolerance") +
                         ": must lie in [0, 1) (a relative change; 0: not checked)");
    p.dt_max = positive(*t, "dt_max", p.dt_max);
    if (p.dt_max < dt)
        throw InputError(fmt::format("{}: must be at least run.dt ({:g})", t->where("dt_max"), dt));
    p.dt_min = positive(*t, "dt_min", p.dt_min);
    if (p.dt_min > dt)
        throw InputError(fmt::format("{}: must be at most run.dt ({:g})", t->where("dt_min"), dt));
    if (const auto n = t->integer("n_delay")) {
        if (*n < 0 || *n > 1000000)
            throw InputError(t->where("n_delay") + ": must be an integer from 0 to 1000000");
        p.n_delay = static_cast<std::uint64_t>(*n);
    }
    p.f_inc = factor(*t, "f_inc", p.f_inc, 1.0, 10.0, true);
    p.f_dec = factor(*t, "f_dec", p.f_dec, 0.0, 1.0, false);
    p.alpha_start = factor(*t, "alpha_start", p.alpha_start, 0.0, 1.0, false);
    p.f_alpha = factor(*t, "f_alpha", p.f_alpha, 0.0, 1.0, true);
    p.max_move = positive(*t, "max_move", p.max_move);
    // (with no skin the evolver bounds a step by the cutoff: Evolver::step)
    if (skin > 0.0 && p.max_move > skin)
        throw InputError(fmt::format("{}: must be at most the neighbour list's skin ({:g}), so "
                                     "that the list's rebuild check sees every move; raise "
                                     "[neighbor_list] skin or lower max_move",
                                     t->where("max_move"), skin));
    p.initial_delay = t->boolean("initial_delay").value_or(p.initial_delay);
    t->finish();
    return p;
}

} // namespace pedesis
