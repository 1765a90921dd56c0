#pragma once
// The running totals of a hard-particle engine (event-driven or time-stepped): collisions,
// the collision virial and the momentum given to the walls, from which both engines'
// runs measure the pressure the same way (observe/pressure.hpp).
#include "pedesis/core/sym_tensor.hpp"
#include "pedesis/core/vec.hpp"

#include <array>
#include <cstdint>

namespace pedesis {

// Running totals since the engine was created (or restored).
template <int D> struct EventCounters {
    std::uint64_t pair_collisions = 0;
    std::uint64_t wall_collisions = 0;
    std::uint64_t list_rebuilds = 0;
    std::uint64_t stale_events = 0;
    SymTensor virial{}; // sum over collisions of J n_a r_ij,b (sym_tensor.hpp's slots)
    std::array<std::array<double, 2>, D> wall_impulse{}; // momentum given to each wall
    double energy_lost = 0.0;
};

// A collision's share of the virial: impulse J along the unit normal n, centres r_ij
// apart (parallel to n at contact, so J n_a r_ij,b is symmetric).
template <int D>
void add_collision_virial(EventCounters<D>& c, double impulse, const Vec<D>& n, const Vec<D>& r) {
    for (int a = 0; a < D; ++a)
        for (int b = a; b < D; ++b) c.virial[sym_slot(a, b)] += impulse * n[a] * r[b];
}

// Sum over the axes of the collision virial: sum over collisions of J n . r_ij.
template <int D> double virial_trace(const EventCounters<D>& c) {
    double w = 0.0;
    for (int a = 0; a < D; ++a) w += c.virial[a];
    return w;
}

} // namespace pedesis
