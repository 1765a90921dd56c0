#pragma once
// dynamics = "minimize": FIRE energy minimisation of the soft engine (soft/fire.hpp). Its
// [minimize] table, and the terms it refuses.
#include "pedesis/io/config_table.hpp"
#include "pedesis/soft/fire_params.hpp"
#include "pedesis/soft/plugin_spec.hpp"

#include <string>
#include <vector>

namespace pedesis {

// FIRE moves the particles itself and minimises the potential energy: an [[integrator]]
// would move them a second way, a [[torque]] turns directors no energy depends on, and an
// active force (self_propulsion, active_ou) has no potential energy to minimise. Each is
// an InputError naming its table.
void check_minimize_terms(const std::vector<PluginSpec>& forces,
                          const std::vector<PluginSpec>& torques,
                          const std::vector<PluginSpec>& integrators);

// [minimize] (every key optional), its defaults taken from run.dt and the neighbour list's
// skin; InputError on a bad key or value.
FireParams read_minimize_config(ConfigTable& root, double dt, double skin);

} // namespace pedesis
