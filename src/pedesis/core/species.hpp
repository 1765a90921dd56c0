#pragma once
#include <cmath>
#include <string>

namespace pedesis {

// Per-species constants. An infinite mass makes a fixed obstacle.
struct Species {
    std::string name;
    double radius = 0.5;
    double mass = 1.0;

    double inverse_mass() const { return std::isinf(mass) ? 0.0 : 1.0 / mass; }
};

} // namespace pedesis
