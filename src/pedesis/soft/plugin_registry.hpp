#pragma once
// The named plug-ins of the soft/active engine: what each is called in a config and in
// Python, its parameters with their limits, its formula, and how it is built, in one
// row of the catalogue (plugin_registry.cpp). The config reader, the Python module and
// docs/engines.md read that row; adding a plug-in is its file and its row.
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
    // A pair potential mixes per-species values into pair values: lengths by the
    // mixing rule (arithmetic or geometric mean), everything else geometrically.
    bool length = false;
    // May be a list of one number per axis instead (a trap's centre, its stiffness per
    // axis): read with plugin_axes.
    bool per_axis = false;
};

// A yes/no option (lj's shift).
struct FlagInfo {
    const char* key;
    const char* meaning;
};

// A word among fixed options (a wall's potential, an axis), with the one taken when the
// config gives none.
struct ChoiceInfo {
    const char* key;
    std::vector<const char*> options;
    const char* fallback;
    const char* meaning;
};

template <int D>
using AddPlugin = void (*)(Evolver<D>&, const PluginSpec&, const std::vector<Species>&,
                           std::uint64_t seed);

struct PluginInfo {
    PluginKind kind;
    const char* name;
    const char* python_class; // pedesis.<python_class> in the Python module
    std::vector<ParamInfo> params;
    const char* formula;
    // Pair potentials take per-pair values ([[force.pairs]]) and a mixing rule.
    bool pair_potential = false;
    std::vector<FlagInfo> flags = {};
    std::vector<ChoiceInfo> choices = {};
    AddPlugin<2> add2 = nullptr; // builds the plug-in and registers it with the evolver
    AddPlugin<3> add3 = nullptr;
};

// Mixing rules for pair parameters not given per pair, as LAMMPS' pair_modify mix.
inline constexpr const char* mixing_rules[] = {"geometric", "arithmetic"};

const std::vector<PluginInfo>& plugin_catalogue();
const char* kind_name(PluginKind kind); // "force", "torque", "integrator"

// Reads one [[force]] / [[torque]] / [[integrator]] table: an unknown name lists the
// known ones, unknown keys, missing required keys and values outside their limits are
// InputErrors naming file, line and key.
PluginSpec read_plugin(ConfigTable& table, PluginKind kind);

// The same checks for parameters given by a program (the Python module): `given` maps
// parameter names to values, each with its own `where` for messages; unknown names are
// InputErrors listing the known ones.
// Pair potentials also take yes/no options (`flags`), per-pair values and a mixing rule.
PluginSpec make_plugin_spec(PluginKind kind, const std::string& name,
                            std::map<std::string, PluginParam> given, const std::string& where,
                            std::map<std::string, bool> flags = {},
                            std::vector<PairValues> pairs = {},
                            const std::string& mixing = "geometric",
                            std::map<std::string, std::string> choices = {});

// The value of parameter `key` for every species of the table, in table order.
PerSpecies plugin_parameter(const PluginSpec& spec, const std::string& key,
                            const std::vector<Species>& species);

// The word the spec gives for choice `key`, or the choice's fallback.
std::string plugin_choice(const PluginSpec& spec, const std::string& key);

// Parameter `key` (ParamInfo::per_axis) as one number per axis of a `dimension`-D box: a
// list of that length, or one number for every axis; `fallback` on every axis if the
// spec has none. Not per species.
std::vector<double> plugin_axes(const PluginSpec& spec, const std::string& key, int dimension,
                                double fallback);

// "x", "y", "z" as an axis index (ChoiceInfo options of an axis); InputError naming
// `where` for an axis the box does not have.
int axis_index(const std::string& name, int dimension, const std::string& where);

// The value of a pair potential's parameter `key` for the species pair (a, b): the
// [[force.pairs]] entry of that pair, else the mixing rule over per-species values, else
// the one value given, else `fallback`.
double pair_parameter(const PluginSpec& spec, const std::string& key,
                      const std::vector<Species>& species, std::size_t a, std::size_t b,
                      double fallback);

// Builds the plug-in for this dimension and species table and registers it. A
// per-species parameter must name exactly the species of the table.
template <int D>
void add_plugin(Evolver<D>& evolver, const PluginSpec& spec, const std::vector<Species>& species,
                std::uint64_t seed);

} // namespace pedesis
