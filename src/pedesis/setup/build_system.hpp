#pragma once
// Turns a run config into a box and a particle store: places every species
// (lattice, random, a point, or a file) and draws its velocities.
#include "pedesis/core/box.hpp"
#include "pedesis/core/particles.hpp"
#include "pedesis/io/tutorial_json.hpp"
#include "pedesis/observe/thermo.hpp"
#include "pedesis/setup/run_config.hpp"

namespace pedesis {

// The [initial] file of `c` (its frame c.initial_frame), in any format
// (io/particle_file.hpp). With [[species]] in the config and a file that names its types
// (GSD, XYZ), each particle's type becomes the index of the species of that name, and a
// type no species is named after is an InputError; the tutorial's JSON numbers its types,
// which index the species in config order.
template <int D> ParticleFile<D> read_initial_file(const RunConfig& c);

template <int D> Box<D> build_box(const RunConfig& c);

template <int D> ParticleStore<D> build_particles(const RunConfig& c, const Box<D>& box);
// The same with the [initial] file already read (read_initial_file), so that a caller
// that needs it too reads a large file once.
template <int D>
ParticleStore<D> build_particles(const RunConfig& c, const Box<D>& box,
                                 const ParticleFile<D>* initial);

// Whether the config's equations of motion conserve momentum (observe/thermo.hpp): the
// event and stepped engines do, and so does `nve` unless a self-propulsion force is on;
// the Langevin and Brownian integrators do not.
Momentum momentum_of(const RunConfig& c);

} // namespace pedesis
