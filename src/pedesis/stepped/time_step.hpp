#pragma once
// The largest safe time step of the stepped engine. Overlaps are found only at the end
// of a step, so a pair that crosses the whole of its overlap within one step is never
// seen: with every particle moving at most a fraction f < 1 of its own radius per step,
// two particles come closer by at most f (r_i + r_j), less than their contact distance,
// and neither can pass through the other (nor, by the same bound, skip a wall layer).
#include "pedesis/core/box.hpp"
#include "pedesis/core/particles.hpp"

#include <cstddef>
#include <string>

namespace pedesis {

struct FastestParticle {
    std::size_t index = 0;     // storage index
    double speed = 0.0;        // |v|
    double radii_per_step = 0; // |v| dt / r: the distance moved in one step, in radii
};

// The particle that moves the most radii in one step of dt (fixed obstacles excluded).
template <int D> FastestParticle fastest_particle(const ParticleStore<D>& p, double dt);

// Collisions per particle expected in `duration` at the Enskog frequency of the gas,
// taken at the mean diameter and mean mass of the mobile particles and their kinetic
// temperature (a mixture's frequencies differ by species; this is an estimate).
template <int D>
double expected_collisions_per_particle(const ParticleStore<D>& p, const Box<D>& box,
                                        double duration);

// A time step that keeps every particle within max_move radii per step now and, with
// room to spare, throughout a run that draws `samples` independent speeds from the
// equilibrium distribution (N at the start and N again per collision per particle: see
// expected_collisions_per_particle). The tail exp(-m v^2 / 2T) of the Rayleigh (2D) and
// Maxwell (3D) distributions puts the fastest of S samples below
// v_S = sqrt(2 (ln S + 6) T / m) with probability about 99% or more. The result is
// max_move times the smallest r / max(|v|, v_S) over the particles, rounded down to two
// significant digits; +infinity when nothing moves.
template <int D>
double suggested_time_step(const ParticleStore<D>& p, double max_move, double samples);

// dt against the starting speeds, as bad input: a step that carries a particle further
// than max_move radii could let it pass through another particle or a wall. The
// InputError names `where` (the config key), the particle and a dt to use instead.
template <int D>
void check_time_step(const ParticleStore<D>& p, double dt, double max_move,
                     const std::string& where, double samples);

} // namespace pedesis
