#pragma once
// What a run's config.toml places in the box besides particles and the box's own walls:
// containers (a sphere or cylinder wall), harmonic traps and gravity. The pictures draw
// them (painter.cpp, the viewer page); nothing here is needed to read the frames.
#include "pedesis/render/frame.hpp"

#include <filesystem>
#include <vector>

namespace pedesis::render {

enum class ContainerShape { sphere, cylinder };

struct Container {
    ContainerShape shape = ContainerShape::sphere;
    double radius = 0.0; // > 0 and finite
    Vec3 centre{};       // z = 0 in 2D
    int axis = 2;        // a cylinder's axis (0, 1, 2); cylinders are 3D only
};

struct Scenery {
    std::vector<Container> containers;
    std::vector<Vec3> traps; // trap centres
    std::vector<Vec3> pulls; // unit directions gravity pulls some species in
    bool empty() const { return containers.empty() && traps.empty() && pulls.empty(); }
};

// At most this many of each: a config with thousands of [[force]] tables draws no faster
// for listing them (the page and the frames carry the first ones).
inline constexpr std::size_t max_scenery_items = 16;

// From [[force]] tables name = "wall" (shape "sphere" | "cylinder", radius, centre, axis),
// "harmonic_trap" (k, centre) and "gravity" (force, axis). A config that is missing or
// broken gives nothing; a table with a value of the wrong kind (a string for a number, a
// negative or non-finite radius, a centre with the wrong number of coordinates, a cylinder
// in 2D) is left out alone, as the run would refuse it: the frames are what counts.
Scenery read_scenery(const std::filesystem::path& config_toml);

} // namespace pedesis::render
