#pragma once
// Perfect lattices and the degenerate coordinates of a box, for the differential tests
// of the spatial structures: the geometries where cell assignment and the minimum image
// are decided by rounding (sites on every cell face, at -L/2, one ulp inside +L/2, box
// lengths a ulp either side of a multiple of the range).
#include "pedesis/core/box.hpp"

#include <array>
#include <cmath>
#include <string>
#include <type_traits>
#include <vector>

namespace pedesis::test {

// sc and fcc in 3D, square and hexagonal (triangular) in 2D.
enum class LatticeKind { cubic, fcc, hexagonal };

inline std::string lattice_name(LatticeKind k, int dim) {
    switch (k) {
    case LatticeKind::cubic:
        return dim == 2 ? "square" : "sc";
    case LatticeKind::fcc:
        return "fcc";
    case LatticeKind::hexagonal:
        return "hexagonal";
    }
    return "?";
}

// The lattices a dimension has.
template <int D> std::vector<LatticeKind> lattice_kinds() {
    if constexpr (D == 2)
        return {LatticeKind::cubic, LatticeKind::hexagonal};
    else
        return {LatticeKind::cubic, LatticeKind::fcc};
}

// Edge lengths of the conventional cell of spacing a (nearest-neighbour distance a for
// sc, square and hexagonal; cube edge a for fcc, whose neighbours are a / sqrt 2 apart).
template <int D> Vec<D> unit_cell(LatticeKind k, double a) {
    Vec<D> e = Vec<D>::filled(a);
    if (k == LatticeKind::hexagonal) e[1] = a * std::sqrt(3.0);
    return e;
}

// Fractional coordinates of the basis.
template <int D> std::vector<Vec<D>> basis(LatticeKind k) {
    if constexpr (D == 2) {
        if (k == LatticeKind::hexagonal) return {Vec<2>{{0.0, 0.0}}, Vec<2>{{0.5, 0.5}}};
        return {Vec<2>{}};
    } else {
        if (k == LatticeKind::fcc)
            return {Vec<3>{}, Vec<3>{{0.5, 0.5, 0.0}}, Vec<3>{{0.5, 0.0, 0.5}},
                    Vec<3>{{0.0, 0.5, 0.5}}};
        return {Vec<3>{}};
    }
}

// cells[a] conventional cells of edge `cell` along each axis, starting exactly at the
// low face lo(a) of `box` (so that the first sites lie at -L/2), shifted by `offset`
// (in units of the cell edge) on the axes where offset is non-zero: walled axes shift
// by half a cell so that no centre touches a wall. Sites beyond the box are dropped
// (a box a ulp shorter than the lattice).
template <int D>
std::vector<Vec<D>> lattice_sites(const Box<D>& box, LatticeKind k,
                                  const std::type_identity_t<std::array<int, D>>& cells,
                                  const Vec<D>& cell, const Vec<D>& offset = {}) {
    std::vector<Vec<D>> out;
    const auto b = basis<D>(k);
    std::array<int, D> c{};
    while (true) {
        for (const auto& f : b) {
            Vec<D> r;
            bool inside = true;
            for (int a = 0; a < D; ++a) {
                r[a] = box.lo(a) + (c[a] + f[a] + offset[a]) * cell[a];
                inside = inside && (box.periodic(a) ? r[a] < box.hi(a) : r[a] <= box.hi(a));
            }
            if (inside) out.push_back(r);
        }
        int a = 0;
        while (a < D && ++c[a] == cells[a]) c[a++] = 0;
        if (a == D) break;
    }
    return out;
}

// The coordinate one ulp inside +L/2: the largest a wrapped position can take.
inline double just_below_half(double L) {
    return std::nextafter(0.5 * L, 0.0);
}

// L, or L one ulp below (nudge -1) or above (+1).
inline double nudged(double L, int nudge) {
    return nudge == 0 ? L : std::nextafter(L, nudge > 0 ? 2.0 * L : 0.0);
}

inline std::string nudge_name(int nudge) {
    return nudge == 0 ? "exactly" : nudge > 0 ? "+ 1 ulp" : "- 1 ulp";
}

// A lattice's box: `cells` unit cells of `edge` per axis, each length `nudge` ulps off;
// periodic axes by `pattern` (0 all, 1 none, 2 the even ones); the sites offset half a
// cell from a wall.
template <int D> struct LatticeBox {
    Box<D> box;
    Vec<D> offset;
    std::array<int, D> cells;
};
template <int D> LatticeBox<D> lattice_box(const Vec<D>& edge, int cells, int nudge, int pattern) {
    Vec<D> L, offset{};
    std::array<bool, D> periodic;
    std::array<int, D> along;
    for (int a = 0; a < D; ++a) {
        periodic[a] = pattern == 0 || (pattern == 2 && a % 2 == 0);
        L[a] = nudged(cells * edge[a], nudge);
        offset[a] = periodic[a] ? 0.0 : 0.5;
        along[a] = cells;
    }
    return {Box<D>(L, periodic), offset, along};
}

} // namespace pedesis::test
