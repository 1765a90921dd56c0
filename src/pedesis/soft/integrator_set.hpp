#pragma once
// The one rule for which integrators a soft/active run may have, shared by the config
// reader and the Python Evolver so that neither accepts what the other refuses: exactly
// one integrator moves the positions (brownian, langevin or nve); beside it the director
// integrators, brownian_rotation and run_and_tumble, at most one of each (either, both or
// none); and a torque needs brownian_rotation to turn anything (run_and_tumble only
// redraws directors).
#include "pedesis/soft/plugin_spec.hpp"

#include <string>
#include <vector>

namespace pedesis {

// How a message names the plug-ins: as a config does (brownian_rotation) or as the
// Python module does (BrownianRotIntegrator).
enum class PluginNaming { config, python };

// Refuses `added` when it can never fit beside `present`: a second position integrator,
// a second brownian_rotation or a second run_and_tumble. Messages start with added.where.
void check_integrator_added(const std::vector<PluginSpec>& present, const PluginSpec& added,
                            PluginNaming naming);

// Refuses a set that cannot take a step: no position integrator (`missing` is the whole
// message then, since only the caller knows what to suggest), or a torque without
// brownian_rotation. `torques` are the torque terms registered.
void check_integrators_complete(const std::vector<PluginSpec>& integrators,
                                const std::vector<PluginSpec>& torques, const std::string& missing,
                                PluginNaming naming);

// True for the integrators that move positions (all but the director integrators).
bool moves_positions(const PluginSpec& integrator);

// Their names, as `naming` gives them, for messages: "brownian, langevin, nve".
std::string position_integrators(PluginNaming naming);

} // namespace pedesis
