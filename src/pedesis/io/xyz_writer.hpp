#pragma once
// Extended-XYZ trajectory frames, the text format OVITO and ASE read directly.
#include "pedesis/core/frame.hpp"

#include <string>

namespace pedesis {

// One frame: the particle count, a comment line with the cell (Lattice, Origin),
// the column layout (Properties), the time and the periodicity, then one line per
// particle in tag order, so that row k is the same particle in every frame.
// Columns: species name, position, velocity, radius, mass ("inf" for fixed
// obstacles), tag. Values are written with the shortest text that reads back to
// the same double. 2D systems are written with z = 0 in a cell of unit height.
template <int D> std::string xyz_frame(const Frame<D>& f);

} // namespace pedesis
