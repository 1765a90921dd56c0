#pragma once
// The named plug-ins of the soft/active engine: what each is called in a config, its
// parameters with their limits, and how it is built. docs/engines.md lists the same
// catalogue with the formulas; adding a plug-in is one entry here and one file.
#include "pedesis/core/species.hpp"
#include "pedesis/soft/evolver.hpp"
#include "pedesis/soft/per_species.hpp"
#include "pedesis/soft/plugin_spec.hpp"

#include <cstdint>
#include <map>
#include <string>
#include <vector>

namespace pedesis {

class ConfigTable;

enum class ParamLimit { any, non_negative, positive };

struct ParamInfo {
    const char* key;
    bool required;
    ParamLimit limit;
    bool per_species; // may be given as { A = .., B = .. }
    const char* meaning;
};

struct PluginInfo {
    PluginKind kind;
    const char* name;
    std::vector<ParamInfo> params;
    const char* formula;
};

const std::vector<PluginInfo>& plugin_catalogue();
const char* kind_name(PluginKind kind); // "force", "torque", "integrator"

// Reads one [[force]] / [[torque]] / [[integrator]] table: an unknown name lists the
// known ones, unknown keys, missing required keys and values outside their limits are
// InputErrors naming file, line and key.
PluginSpec read_plugin(ConfigTable& table, PluginKind kind);

// The same checks for parameters given by a program (the Python module): `given` maps
// parameter names to values, each with its own `where` for messages; unknown names are
// InputErrors listing the known ones.
PluginSpec make_plugin_spec(PluginKind kind, const std::string& name,
                            std::map<std::string, PluginParam> given, const std::string& where);

// The value of parameter `key` for every species of the table, in table order.
PerSpecies plugin_parameter(const PluginSpec& spec, const std::string& key,
                            const std::vector<Species>& species);

// Builds the plug-in for this dimension and species table and registers it. A
// per-species parameter must name exactly the species of the table.
template <int D>
void add_plugin(Evolver<D>& evolver, const PluginSpec& spec, const std::vector<Species>& species,
                std::uint64_t seed);

} // namespace pedesis
