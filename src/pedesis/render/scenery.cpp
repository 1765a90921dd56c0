#include "pedesis/render/scenery.hpp"

#include "pedesis/render/config_table.hpp"

#include <algorithm>
#include <cmath>
#include <optional>
#include <string>

namespace pedesis::render {

namespace {

std::optional<double> finite(const toml::node* node) {
    const auto v = node ? node->value<double>() : std::nullopt; // integers too
    if (v && std::isfinite(*v)) return v;
    return std::nullopt;
}

// "centre": the origin when absent, one finite number for every axis, or exactly one per
// axis (as plugin_axes reads it).
std::optional<Vec3> centre_of(const toml::table& force, int dimension) {
    const toml::node* node = force.get("centre");
    if (!node) return Vec3{};
    if (const auto all = finite(node)) return Vec3{*all, *all, dimension == 3 ? *all : 0.0};
    const toml::array* list = node->as_array();
    if (!list || list->size() != static_cast<std::size_t>(dimension)) return std::nullopt;
    Vec3 c{};
    for (std::size_t a = 0; a < list->size(); ++a) {
        const auto x = finite(list->get(a));
        if (!x) return std::nullopt;
        c[a] = *x;
    }
    return c;
}

// An axis word as an index below `axes`; `fallback` when absent.
std::optional<int> axis_of(const toml::table& force, int axes, int fallback) {
    const toml::node* node = force.get("axis");
    if (!node) return fallback;
    const auto word = node->value<std::string>();
    if (!word || word->size() != 1) return std::nullopt;
    const int a = (*word)[0] - 'x';
    if (a < 0 || a >= axes) return std::nullopt;
    return a;
}

// k as the trap takes it: one number, one per species ({A = 1.0}) or one per axis.
bool valid_stiffness(const toml::node* k, int dimension) {
    if (!k) return false;
    if (finite(k)) return true;
    if (const toml::table* per_species = k->as_table()) {
        if (per_species->empty()) return false;
        return std::all_of(per_species->begin(), per_species->end(),
                           [](const auto& entry) { return finite(&entry.second).has_value(); });
    }
    if (const toml::array* per_axis = k->as_array()) {
        if (per_axis->size() != static_cast<std::size_t>(dimension)) return false;
        return std::all_of(per_axis->begin(), per_axis->end(),
                           [](const toml::node& x) { return finite(&x).has_value(); });
    }
    return false;
}

// The signs gravity's force takes over the species: +1 (some pulled along -axis), -1
// (some pushed along +axis); nothing when a value is not a finite number.
std::optional<std::array<bool, 2>> force_signs(const toml::node* force) {
    if (!force) return std::nullopt;
    std::array<bool, 2> signs{false, false}; // {positive, negative}
    auto take = [&](const toml::node* value) {
        const auto f = finite(value);
        if (!f) return false;
        if (*f > 0.0) signs[0] = true;
        if (*f < 0.0) signs[1] = true;
        return true;
    };
    if (const toml::table* per_species = force->as_table()) {
        if (per_species->empty()) return std::nullopt;
        for (const auto& [name, value] : *per_species)
            if (!take(&value)) return std::nullopt;
        return signs;
    }
    if (!take(force)) return std::nullopt;
    return signs;
}

void add_wall(const toml::table& force, int dimension, Scenery& out) {
    const auto shape = force["shape"].value<std::string>();
    if (!shape || (*shape != "sphere" && *shape != "cylinder")) return; // planes: the box's
    const auto radius = finite(force.get("radius"));
    const auto centre = centre_of(force, dimension);
    if (!radius || !(*radius > 0.0) || !centre) return;
    Container c;
    c.shape = *shape == "sphere" ? ContainerShape::sphere : ContainerShape::cylinder;
    c.radius = *radius;
    c.centre = *centre;
    // a cylinder is 3D only (the run refuses one in 2D); its axis is the last by default
    if (c.shape == ContainerShape::cylinder && dimension != 3) return;
    const auto axis = axis_of(force, dimension, dimension - 1);
    if (!axis) return;
    c.axis = *axis;
    out.containers.push_back(c);
}

void add_trap(const toml::table& force, int dimension, Scenery& out) {
    const auto centre = centre_of(force, dimension);
    if (!centre || !valid_stiffness(force.get("k"), dimension)) return;
    out.traps.push_back(*centre);
}

void add_gravity(const toml::table& force, int dimension, Scenery& out) {
    const auto axis = axis_of(force, dimension, dimension - 1);
    const auto signs = force_signs(force.get("force"));
    if (!axis || !signs) return;
    for (int k = 0; k < 2; ++k) {
        if (!(*signs)[static_cast<std::size_t>(k)]) continue;
        Vec3 pull{};
        pull[static_cast<std::size_t>(*axis)] = k == 0 ? -1.0 : 1.0; // a positive force: -axis
        if (std::find(out.pulls.begin(), out.pulls.end(), pull) == out.pulls.end())
            out.pulls.push_back(pull);
    }
}

} // namespace

Scenery read_scenery(const std::filesystem::path& config_toml) {
    Scenery out;
    const auto config = parse_config_table(config_toml);
    if (!config) return out;
    const int dimension = config_dimension(*config);
    const toml::array* forces = (*config)["force"].as_array();
    if (!forces) return out;
    for (const toml::node& item : *forces) {
        const toml::table* force = item.as_table();
        const auto name = force ? (*force)["name"].value<std::string>() : std::nullopt;
        if (!name) continue;
        if (*name == "wall" && out.containers.size() < max_scenery_items)
            add_wall(*force, dimension, out);
        else if (*name == "harmonic_trap" && out.traps.size() < max_scenery_items)
            add_trap(*force, dimension, out);
        else if (*name == "gravity" && out.pulls.size() < max_scenery_items)
            add_gravity(*force, dimension, out);
    }
    return out;
}

} // namespace pedesis::render
