#pragma once
// Particles placed where rounding decides which cell (or domain) holds them: on a face
// of a grid exactly, or one ulp either side, at -L/2, one ulp inside +L/2, or on a
// wall; each with a partner a chosen distance away along an axis, across that face or
// across the periodic boundary. The spatial structures must find these pairs like any
// others.
#include "pedesis/core/box.hpp"

#include <array>
#include <cmath>
#include <random>
#include <type_traits>
#include <vector>

#include "support/lattices.hpp"

namespace pedesis::test {

// A coordinate along axis a of a box cut into n equal slabs, where rounding decides:
// slab faces (exactly, or a ulp either side), -L/2, a ulp inside +L/2 (walls: on the
// wall).
template <int D> double fragile_coordinate(const Box<D>& box, int a, int n, std::mt19937_64& gen) {
    const double L = box.length(a), lo = box.lo(a);
    std::uniform_int_distribution<int> kind(0, 5), slab(0, n);
    switch (kind(gen)) {
    case 0:
        return lo;
    case 1:
        return box.periodic(a) ? just_below_half(L) : box.hi(a);
    default: {
        const double face = std::min(lo + slab(gen) * (L / n), box.hi(a));
        const int ulps = kind(gen) % 3 - 1;
        return ulps == 0 ? face : std::nextafter(face, ulps > 0 ? 2.0 * L : -2.0 * L);
    }
    }
}

// Appends `count` pairs: one particle with a fragile coordinate on a random axis (and,
// half the time, on every axis: a corner), its partner `distance(gen)` away along that
// axis, wrapped on periodic axes; partners that would leave a walled axis go the other
// way. `slabs[a]` is the number of cells (or domains) along axis a.
template <int D, class Distance>
void add_face_pairs(const Box<D>& box, const std::type_identity_t<std::array<int, D>>& slabs,
                    std::size_t count, Distance&& distance, std::mt19937_64& gen,
                    std::vector<Vec<D>>& pos) {
    std::uniform_int_distribution<int> axis(0, D - 1), coin(0, 1);
    for (std::size_t k = 0; k < count; ++k) {
        Vec<D> p;
        for (int a = 0; a < D; ++a)
            p[a] = std::uniform_real_distribution<double>(box.lo(a), box.hi(a))(gen);
        const int a = axis(gen);
        const bool corner = coin(gen);
        for (int b = 0; b < D; ++b)
            if (b == a || corner) p[b] = fragile_coordinate(box, b, slabs[b], gen);
        Vec<D> q = p;
        const double d = distance(gen);
        q[a] = coin(gen) ? p[a] + d : p[a] - d;
        if (!box.periodic(a) && (q[a] < box.lo(a) || q[a] > box.hi(a)))
            q[a] = q[a] > p[a] ? p[a] - d : p[a] + d;
        if (!box.periodic(a) && (q[a] < box.lo(a) || q[a] > box.hi(a))) continue;
        box.wrap(p);
        box.wrap(q);
        pos.push_back(p);
        pos.push_back(q);
    }
}

// Distances at which a pair is or is not within `reach`, by a ulp.
inline auto near_reach(double reach) {
    return [reach](std::mt19937_64& gen) {
        switch (std::uniform_int_distribution<int>(0, 4)(gen)) {
        case 0:
            return std::nextafter(reach, 0.0);
        case 1:
            return reach;
        case 2:
            return std::nextafter(reach, 2.0 * reach);
        case 3:
            return reach * (1.0 - 1e-9);
        default:
            return std::uniform_real_distribution<double>(0.0, reach)(gen);
        }
    };
}

} // namespace pedesis::test
