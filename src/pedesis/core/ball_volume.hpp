#pragma once
// The area of a disk (dim 2) or the volume of a sphere (dim 3) of radius r: what packing
// fractions and the messages about crowded boxes are made of.
#include <numbers>

namespace pedesis {

inline double ball_volume(double r, int dim) {
    return dim == 2 ? std::numbers::pi * r * r : 4.0 / 3.0 * std::numbers::pi * r * r * r;
}

} // namespace pedesis
