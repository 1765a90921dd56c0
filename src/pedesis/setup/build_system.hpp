#pragma once
// Turns a run config into a box and a particle store: places every species
// (lattice, random, a point, or a file) and draws its velocities.
#include "pedesis/core/box.hpp"
#include "pedesis/core/particles.hpp"
#include "pedesis/io/run_config.hpp"

namespace pedesis {

template <int D> Box<D> build_box(const RunConfig& c);

template <int D> ParticleStore<D> build_particles(const RunConfig& c, const Box<D>& box);

} // namespace pedesis
