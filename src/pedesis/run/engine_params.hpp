#pragma once
// The hard-particle engines' parameters as a run config gives them: one translation
// for `pedesis run`, restarts and the Python module.
#include "pedesis/event/event_engine.hpp"
#include "pedesis/setup/run_config.hpp"
#include "pedesis/stepped/stepped_engine.hpp"

namespace pedesis {

inline EventParams event_params(const RunConfig& c) {
    EventParams p;
    p.restitution = c.restitution;
    p.wall_restitution = c.wall_restitution;
    p.tc = c.tc;
    p.skin = c.skin;
    p.check_overlaps = c.check_overlaps;
    p.growth_rate = c.growth_rate;
    p.growth_packing_fraction = c.growth_packing_fraction;
    p.growth_max_pressure = c.growth_max_pressure;
    p.thermostat_temperature = c.thermostat_temperature;
    p.thermostat_interval = c.thermostat_interval;
    for (std::size_t a = 0; a < c.gravity.size() && a < 3; ++a) p.gravity[a] = c.gravity[a];
    p.andersen_rate = c.andersen_rate;
    p.andersen_temperature = c.andersen_temperature;
    p.driving_rate = c.driving_rate;
    p.driving_strength = c.driving_strength;
    p.moving_wall_axis = c.moving_wall_axis;
    p.moving_wall_upper = c.moving_wall_upper;
    p.moving_wall = c.moving_wall;
    p.seed = c.seed;
    return p;
}

inline SteppedParams stepped_params(const RunConfig& c) {
    SteppedParams p;
    p.dt = c.dt;
    p.max_move = c.max_move;
    for (std::size_t a = 0; a < c.gravity.size() && a < 3; ++a) p.gravity[a] = c.gravity[a];
    return p;
}

} // namespace pedesis
