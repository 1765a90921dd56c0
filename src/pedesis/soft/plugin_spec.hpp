#pragma once
// A force, torque or integrator as the config names it, with its parameters read and
// checked but not yet bound to a species table or a dimension (the table may come from
// the initial-configuration file, which is read later).
#include <map>
#include <optional>
#include <string>
#include <utility>
#include <vector>

namespace pedesis {

enum class PluginKind { force, torque, integrator };

struct PluginParam {
    std::optional<double> uniform;                          // one value for every species
    std::vector<std::pair<std::string, double>> by_species; // or one per species name
    std::vector<double> components; // or one per axis (a trap's centre), when the key allows
    std::string where;              // file:line:column: key '...'
};

// The values a pair potential's config gives one pair of species ([[force.pairs]]).
struct PairValues {
    std::string a, b; // species names
    std::map<std::string, double> values;
    std::string where;
};

struct PluginSpec {
    PluginKind kind = PluginKind::force;
    std::string name;
    std::string where; // of the table, for messages about the plug-in as a whole
    std::map<std::string, PluginParam> params;  // only the keys the config gave
    std::map<std::string, bool> flags;          // likewise
    std::map<std::string, std::string> choices; // likewise (a wall's potential, an axis)
    std::vector<PairValues> pairs;              // pair potentials only
    std::string mixing = "geometric";           // pair potentials only
};

} // namespace pedesis
