#pragma once
// The hard-particle engines' drives in the config: [event] gravity (and [stepped]
// gravity), [event] thermostat = "andersen" with thermostat_rate and temperature, and
// [event] driving = "white_noise" with driving_rate and driving_strength. The meanings:
// EventParams (event/event_engine.hpp); docs/config.md.
#include "pedesis/io/config_table.hpp"
#include "pedesis/setup/run_config.hpp"

namespace pedesis {

// `gravity` of this table (an acceleration, one component per axis): none along a
// periodic axis of c's box.
void read_gravity(ConfigTable& t, RunConfig& c);
// thermostat = "andersen" (the caller has read `thermostat`, whose location is
// c.thermostat_where): thermostat_rate and temperature.
void read_andersen(ConfigTable& ev, RunConfig& c);
// driving = "white_noise", driving_rate and driving_strength; an error for
// thermostat_rate without a thermostat.
void read_driving(ConfigTable& ev, RunConfig& c);

} // namespace pedesis
