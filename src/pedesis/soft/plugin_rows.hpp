#pragma once
// What the rows of the plug-in catalogue share (plugin_registry.hpp): each family of
// plug-ins keeps its rows in a file of its own, and plugin_catalogue() joins them.
#include "pedesis/soft/plugin_registry.hpp"

#include <utility>
#include <vector>

namespace pedesis::rows {

inline constexpr bool required = true, optional = false;
inline constexpr bool per_species = true, shared = false;
inline constexpr bool length = true;

// Both dimensions' builders of a row, from one template lambda
// []<int D>(Evolver<D>&, const PluginSpec&, const std::vector<Species>&, std::uint64_t).
template <class F> std::pair<AddPlugin<2>, AddPlugin<3>> builders(F f) {
    return {static_cast<AddPlugin<2>>(f), static_cast<AddPlugin<3>>(f)};
}

inline PluginInfo row(PluginInfo info, std::pair<AddPlugin<2>, AddPlugin<3>> add) {
    info.add2 = add.first;
    info.add3 = add.second;
    return info;
}

// The one value of a shared parameter, or `fallback` when the spec has none.
inline double uniform(const PluginSpec& spec, const std::string& key, double fallback) {
    const auto it = spec.params.find(key);
    return it == spec.params.end() ? fallback : *it->second.uniform;
}

inline bool flag(const PluginSpec& spec, const char* key) {
    const auto it = spec.flags.find(key);
    return it != spec.flags.end() && it->second;
}

// The families beyond the pair potentials, ABP terms and integrators of
// plugin_registry.cpp: chiral, run-and-tumble and Ornstein-Uhlenbeck activity and the
// alignments (plugin_rows_active.cpp), active Ornstein-Uhlenbeck particles
// (plugin_rows_active_ou.cpp), gravity and traps (plugin_rows_fields.cpp), walls and
// containers (plugin_rows_walls.cpp).
std::vector<PluginInfo> active_model_rows();
std::vector<PluginInfo> active_ou_rows();
std::vector<PluginInfo> external_field_rows();
std::vector<PluginInfo> wall_rows();

} // namespace pedesis::rows
