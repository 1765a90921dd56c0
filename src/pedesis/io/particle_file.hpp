#pragma once
// A start read from any particle file pedesis knows, for [initial] file and the Python
// System: the ABP tutorial's JSON (io/tutorial_json.hpp), a frame of a GSD file
// (HOOMD-blue's or pedesis' own trajectory.gsd; io/gsd_reader.hpp) or a frame of an
// extended XYZ file (pedesis' trajectory.xyz, OVITO's, ASE's; io/xyz_reader.hpp). The
// format is told by the content, not the name: GSD's magic number, a JSON document's
// opening brace, else XYZ's particle count.
//
// Every format ends in a ParticleFile in pedesis' conventions:
// * positions in a box centred at the origin, as HOOMD-blue's and pedesis' are; an XYZ
//   cell is moved from its Origin (its corner; 0 when not given) to the centre;
// * radius = diameter / 2 (GSD);
// * the boundaries, where the file states them: GSD's log/pedesis/periodic (pedesis'
//   own chunk; HOOMD-blue's files have none), XYZ's pbc key;
// * the director is the x axis turned by the GSD orientation quaternion (w, x, y, z), the
//   inverse of what pedesis' GsdWriter stores; in 2D it must stay in the plane;
// * ids: the XYZ id column where present, else the row (a pedesis GSD is in id order);
// * a 2D start needs a 2D frame: GSD configuration/dimensions = 2; XYZ every z equal
//   (the plane) and no velocity along z.
// What the frame does not store (velocities, orientations, diameters, masses) is left
// unset, for the caller's defaults.
#include "pedesis/io/tutorial_json.hpp"

#include <cstdint>
#include <filesystem>
#include <optional>

namespace pedesis {

enum class ParticleFileFormat { tutorial_json, gsd, xyz };

// By the first bytes of the file (InputError when it cannot be opened).
ParticleFileFormat particle_file_format(const std::filesystem::path& path);

// "JSON", "GSD", "XYZ", for messages.
const char* format_name(ParticleFileFormat f);

// Frame `frame` of the file (0-based; a negative one counts from the end, -1 being the
// last; unset: the last). The tutorial's JSON has one frame and refuses `frame`. Every
// fault is an InputError naming the file (and the frame, particle, chunk or line).
template <int D>
ParticleFile<D> read_particle_file(const std::filesystem::path& path,
                                   std::optional<std::int64_t> frame = std::nullopt);

// The dimension of the file's frame: GSD's configuration/dimensions; for XYZ 2 when the
// cell is not periodic along z and every z is the same (what pedesis writes for 2D),
// else 3; for the tutorial's JSON 3 when the box has "Lz" or the first particle's "r"
// has three components, else 2.
int particle_file_dimension(const std::filesystem::path& path,
                            std::optional<std::int64_t> frame = std::nullopt);

} // namespace pedesis
