#pragma once
// Lattice sites filling an orthorhombic region: square and hexagonal (2D), simple
// cubic and face-centred cubic (3D). The lattice is stretched slightly per axis so
// that a whole number of cells spans the region (and matches periodic images).
#include "pedesis/core/vec.hpp"

#include <array>
#include <string>
#include <vector>

namespace pedesis {

enum class LatticeKind { square, hexagonal, simple_cubic, fcc };

LatticeKind parse_lattice(const std::string& name, int dim);

// The first n sites (row-major) of the smallest lattice of the given kind that has
// at least n sites in the region [lo, hi]. On a `closed` axis the outermost sites sit
// exactly on lo and hi (pass the region the centres may occupy, e.g. inset by the
// radius from a wall); on an open (periodic) axis the lattice tiles with its images.
template <int D>
std::vector<Vec<D>> lattice_sites(LatticeKind kind, const Vec<D>& lo, const Vec<D>& hi,
                                  const std::array<bool, D>& closed, std::size_t n);

} // namespace pedesis
