#pragma once
// One frame as the renderer sees it, whichever file it came from (GSD, extended XYZ,
// tutorial JSON): everything is three-dimensional, a 2D run has z = 0.
#include <array>
#include <cstdint>
#include <optional>
#include <string>
#include <utility>
#include <vector>

namespace pedesis::render {

using Vec3 = std::array<double, 3>;

struct Frame {
    int dimension = 2;
    Vec3 box_lo{};     // the box spans [box_lo, box_lo + box_length) on each axis
    Vec3 box_length{}; // z: 0 for a 2D box
    std::array<bool, 3> periodic{true, true, true}; // false: walls on that axis
    std::optional<double> time;
    std::optional<std::uint64_t> step;
    std::vector<Vec3> position;
    std::vector<double> radius;
    std::vector<std::uint32_t> species;     // index into species_names
    std::vector<std::string> species_names; // the same list, in the same order, in every frame
    std::vector<Vec3> velocity;             // empty when the source stores none
    std::vector<Vec3> director;             // empty when the source stores none
    // Other numbers per particle that the file stores, by name, size() values each:
    // mass, id, and any column of the user's own (extended XYZ).
    std::vector<std::pair<std::string, std::vector<double>>> scalars;

    std::size_t size() const { return position.size(); }
};

} // namespace pedesis::render
