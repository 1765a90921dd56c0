#pragma once
// From [transport] to a TransportMeasurement's plan, for the hard-particle engines and the
// soft one: the sampling intervals (defaults from the mean free time or the time step),
// the blocks, the particles followed, the units and references of the summary.
#include "pedesis/core/box.hpp"
#include "pedesis/core/particles.hpp"
#include "pedesis/run/transport_measurement.hpp"
#include "pedesis/setup/run_config.hpp"

#include <cstdint>
#include <vector>

namespace pedesis {

// A fresh measurement from time `start`. step: the engine's time step (0 for the event
// engine): intervals become whole numbers of steps. contact: the diameter of the Enskog
// mean free time that sets the fit window (0: the particles' mean diameter; soft
// particles give their potential's core). soft_heat: a soft run measures the heat flux
// (hard particles always do). InputError (naming [transport]) for a box with walls, a
// growing run, a run whose length does not fix the blocks.
template <int D>
TransportMeasurement<D> start_transport(const RunConfig& c, const ParticleStore<D>& p,
                                        const Box<D>& box, double start, double step,
                                        double contact = 0.0, bool soft_heat = false);

// The storage indices of the particles D follows: those with tags below the count, in
// storage order (the order the measurement keeps).
template <int D>
std::vector<std::uint32_t> followed_particles(const ParticleStore<D>& p, std::size_t count);

// Units and references at the end: the box, the run's mean temperature, Enskog's values
// for one species of hard particles.
template <int D>
typename TransportMeasurement<D>::Scales transport_scales(const RunConfig& c, const Box<D>& box,
                                                          const ParticleStore<D>& p,
                                                          double temperature);

} // namespace pedesis
