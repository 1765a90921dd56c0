#pragma once
// Where the soft engine's walls let a start put the centres of each species: at least
// the wall's core from a walled face (sigma for wca, (2/15)^(1/6) sigma, where the
// energy passes 0, for lj93; the particle's radius for a harmonic wall, as the hard
// engines keep it), and as far inside each container. A random start drawn there does
// not begin deep in a wall's repulsion, which would throw particles out at the first
// step; without wall forces the margins are the radii, as before.
#include "pedesis/core/box.hpp"
#include "pedesis/setup/run_config.hpp"

#include <vector>

namespace pedesis {

template <int D> struct WallMargins {
    std::vector<double> face; // per species: how far centres keep from a walled face
    struct Container {
        bool cylinder = false;
        int axis = D - 1;
        double radius = 0.0;
        Vec<D> centre{};
        std::vector<double> margin; // per species
    };
    std::vector<Container> containers;

    // Whether a centre of species s at r lies inside every container by its margin.
    bool inside(const Vec<D>& r, std::size_t s, const Box<D>& box) const;
};

template <int D> WallMargins<D> wall_margins(const RunConfig& c);

} // namespace pedesis
