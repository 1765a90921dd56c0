#pragma once
// [barostat]: constant pressure for the inertial soft engines (soft/barostat.hpp, the
// Martyna-Tobias-Klein equations): the target pressure, the barostat's time constant and
// whether the axes follow one strain rate (isotropic) or each its own (anisotropic).
#include "pedesis/io/config_table.hpp"

#include <string>

namespace pedesis {

struct BarostatConfig {
    bool on = false; // the table is there
    double pressure = 0.0;
    double tau = 0.0;         // period scale of the volume's oscillation (LAMMPS' Pdamp)
    bool anisotropic = false; // coupling = "anisotropic": each axis its own strain rate
    std::string where;        // "file:line:col: table 'barostat'", for messages
};

// Reads the table if the config has one (InputError on a bad key or value). `dynamics`
// is the config's: the barostat drives the inertial engines only (nve, langevin).
void read_barostat_config(ConfigTable& root, const std::string& dynamics, BarostatConfig& b);

} // namespace pedesis
