#pragma once
// What the event engine reads of a particle at nearly every event it takes part in, and
// of each neighbour at every prediction: one record, so that at 10^6 particles (where
// each particle an event touches is a cache miss) a neighbour costs one line instead of
// one per array. In 3D it is exactly one 64-byte line.
#include "pedesis/core/vec.hpp"

#include <cstdint>

namespace pedesis {

template <int D> struct alignas(D == 3 ? 64 : 16) Flight {
    Vec<D> x; // position at time t (positions are advanced lazily)
    double t;
    Vec<D> v;
    std::uint32_t count;   // collisions so far: an event predicted with a partner whose
                           // count has moved on since is stale
    std::uint16_t species; // (a copy of the particle store's)
    std::uint16_t n_nbr;   // entries in the neighbour row
};

static_assert(sizeof(Flight<3>) == 64);
static_assert(sizeof(Flight<2>) == 48);

} // namespace pedesis
