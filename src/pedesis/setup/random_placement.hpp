#pragma once
// Random sequential placement without overlap, accelerated by the shared cell list.
#include "pedesis/core/box.hpp"

#include <cstdint>
#include <functional>
#include <string>
#include <vector>

namespace pedesis {

template <int D> struct PlacementRequest {
    std::size_t count = 0;
    double radius = 0.5;         // centres at least 2 radius apart (0: soft particles)
    double body_radius = -1.0;   // the particles' size, where radius is 0 for overlap (-1: radius)
    Vec<D> lo{}, hi{};           // region for the centres
    double min_distance = 0.0;   // centres at least max(r_i + r_j, min_distance) apart
    std::uint32_t first_tag = 0; // tags first_tag, first_tag + 1, ... key the random streams
    std::string what;            // for error messages, e.g. "species 'A'"
    // Where else centres may not go (outside a container): empty for nowhere. (Set-up
    // only: once per trial position.)
    std::function<bool(const Vec<D>&)> allowed;
};

// Appends the new centres to `pos` (and their radii to `radii`), avoiding all
// particles already there. Throws InputError when the region is too crowded.
template <int D>
void place_randomly(std::vector<Vec<D>>& pos, std::vector<double>& radii, const Box<D>& box,
                    const PlacementRequest<D>& req, std::uint64_t seed);

} // namespace pedesis
