#pragma once
// What the viewer page asks of a frame, as the bytes it reads straight into typed arrays:
// little-endian float32 (positions, radii, speeds, angles, directors) or uint32 (species)
// in particle order, three numbers per particle for vectors (z = 0 in 2D). 10^5
// particles' positions are 1.2 MB, against ~5 MB of JSON text that the page would parse.
#include "pedesis/render/frame.hpp"

#include <optional>
#include <string>
#include <string_view>

namespace pedesis::view {

enum class Field { position, radius, species, speed, angle, director };

// The field of that name ("position", "radius", "species", "speed", "angle",
// "director"), or none.
std::optional<Field> field_named(std::string_view name);

// The name of the field, as field_named reads it.
std::string_view field_name(Field field);

// Whether the frame has what the field is made of (speed needs velocities; angle and
// director need directors).
bool frame_has(const render::Frame& frame, Field field);

// The field's array, as bytes. speed is |v|; angle is the director's angle atan2(n_y, n_x)
// in (-pi, pi] (the polarity in 2D, its azimuth in 3D). Requires frame_has.
std::string frame_bytes(const render::Frame& frame, Field field);

} // namespace pedesis::view
