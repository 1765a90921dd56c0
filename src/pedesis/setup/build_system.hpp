#pragma once
// Turns a run config into a box and a particle store: places every species
// (lattice, random, a point, or a file) and draws its velocities.
#include "pedesis/core/box.hpp"
#include "pedesis/core/particles.hpp"
#include "pedesis/observe/thermo.hpp"
#include "pedesis/setup/run_config.hpp"

namespace pedesis {

template <int D> Box<D> build_box(const RunConfig& c);

template <int D> ParticleStore<D> build_particles(const RunConfig& c, const Box<D>& box);

// Whether the config's equations of motion conserve momentum (observe/thermo.hpp): the
// event and stepped engines do, and so does `nve` unless a self-propulsion force is on;
// the Langevin and Brownian integrators do not.
Momentum momentum_of(const RunConfig& c);

} // namespace pedesis
