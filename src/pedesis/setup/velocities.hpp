#pragma once
// Initial velocity distributions. Each particle's draw is keyed by its tag, so the
// same seed gives the same velocities whatever the storage order.
#include "pedesis/core/particles.hpp"

#include <cstdint>
#include <string>
#include <vector>

namespace pedesis {

enum class VelocityKind { zero, equal_speed, uniform, normal, maxwell_boltzmann, given };

struct VelocitySpec {
    VelocityKind kind = VelocityKind::maxwell_boltzmann;
    double speed = 1.0;       // equal_speed: |v|; uniform: components in [-speed, speed]
    double sigma = 1.0;       // normal: standard deviation of each component
    double temperature = 1.0; // maxwell_boltzmann: components N(0, T/m)
};

VelocityKind parse_velocity_kind(const std::string& name);

template <int D>
Vec<D> draw_velocity(const VelocitySpec& spec, double mass, std::uint64_t seed, std::uint32_t tag);

// Removes the centre-of-mass velocity of the mobile particles among `which`.
template <int D> void remove_drift(ParticleStore<D>& p, const std::vector<std::size_t>& which);

// Scales the velocities of `which` so that their kinetic temperature is exactly T:
// sum m v^2 = T (d n - removed_freedom) over their n mobile particles, where
// removed_freedom is their share of the momentum components the dynamics conserves
// (c m_which / M, see observe/thermo.hpp; 0 when nothing is conserved).
template <int D>
void rescale_temperature(ParticleStore<D>& p, const std::vector<std::size_t>& which, double T,
                         double removed_freedom = 0.0);

} // namespace pedesis
