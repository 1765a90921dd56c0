#pragma once
// [transport]: transport coefficients measured during a run (run/transport_measurement.hpp):
// self-diffusion from the MSD, shear and bulk viscosity and heat conduction from the
// Helfand moments (hard particles) or the pressure tensor (soft particles).
#include "pedesis/io/config_table.hpp"

#include <cstdint>
#include <optional>
#include <string>

namespace pedesis {

struct TransportConfig {
    bool on = false; // the table is there
    // Time between samples of the moments (unset: a fifth of the Enskog mean free time for
    // hard particles, twenty steps for soft ones); rounded to whole steps where there are steps.
    std::optional<double> interval;
    // Time between samples of the particles' positions for D (unset: hard particles two
    // mean free times, soft ones three moment intervals); a whole number of intervals.
    std::optional<double> diffusion_interval;
    std::int64_t blocks = 8; // independent blocks for the errors
    // Length of a block (unset: the run's length over `blocks`, when [run] fixes it).
    std::optional<double> block_time;
    // D and the velocity autocorrelation follow the particles with tags below this (the
    // cost and memory grow with it).
    std::int64_t particles = 1000;
    bool velocity_autocorrelation = false;
    std::string where; // "file:line:col: table 'transport'", for messages
};

// Reads the table if the config has one (InputError on a bad key or value).
void read_transport_config(ConfigTable& root, TransportConfig& t);

} // namespace pedesis
