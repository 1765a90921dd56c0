#pragma once
// What the viewer page asks of a frame, as the bytes it reads straight into typed arrays:
// little-endian float32 (positions, radii, directors and every number to colour by) or
// uint32 (species) in particle order, three numbers per particle for vectors (z = 0 in
// 2D). 10^5 particles' positions are 1.2 MB, against ~5 MB of JSON text that the page
// would parse.
#include "pedesis/render/frame.hpp"

#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace pedesis::view {

// The arrays the page draws with.
enum class Field { position, radius, species, director };

// The field of that name ("position", "radius", "species", "director"), or none.
std::optional<Field> field_named(std::string_view name);

// The name of the field, as field_named reads it.
std::string_view field_name(Field field);

// Whether the frame has what the field is made of (director needs directors).
bool frame_has(const render::Frame& frame, Field field);

// The field's array, as bytes. Requires frame_has.
std::string frame_bytes(const render::Frame& frame, Field field);

// The numbers per particle the page can colour by, in the order its menu lists them:
// with velocities, speed |v|, the components vx, vy (vz in 3D) and, where the file also
// has masses, kinetic_energy m v^2 / 2; with directors, angle atan2(n_y, n_x) in
// (-pi, pi] (the polarity in 2D, its azimuth in 3D); radius; then every number the file
// stores per particle beyond those (render::Frame::scalars: mass, id, a column of the
// user's own).
std::vector<std::string> colour_fields(const render::Frame& frame);

// That number per particle as float32 bytes, or none when the frame lacks it.
std::optional<std::string> colour_field_bytes(const render::Frame& frame, std::string_view name);

} // namespace pedesis::view
