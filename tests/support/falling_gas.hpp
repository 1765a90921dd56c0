#pragma once
// Hard disks or spheres of diameter 1 and mass 1 in a box periodic along every axis but
// the last, which has walls: what gravity along -e_{D-1} needs. The particles start at
// random (no overlap) within the lowest `start_fraction` of the box's height, with
// Maxwell-Boltzmann velocities at temperature 1.
#include "support/gas_builder.hpp"

namespace pedesis::test {

template <int D>
Gas<D> falling_gas(std::size_t n, const Vec<D>& lengths, double start_fraction,
                   std::uint64_t seed) {
    // the gas builder fills a walled box of the start region's shape at its density
    Vec<D> start = lengths;
    start[D - 1] *= start_fraction;
    double volume = 1.0;
    for (int a = 0; a < D; ++a) volume *= start[a];
    auto spec =
        equal_gas<D>(n, static_cast<double>(n) * particle_volume(D, 0.5) / volume, false, seed);
    spec.aspect = start;
    spec.placement = Placement::random;
    Gas<D> gas = make_gas(spec);
    // the same centres, shifted so that the region sits on the floor of the full box
    const double shift = 0.5 * (start[D - 1] - lengths[D - 1]) * (1.0 - 1e-12);
    for (auto& r : gas.particles.position) r[D - 1] += shift;
    std::array<bool, D> periodic;
    periodic.fill(true);
    periodic[D - 1] = false;
    gas.box = Box<D>(lengths, periodic);
    return gas;
}

} // namespace pedesis::test
