#pragma once
// Kinetic energy, degrees of freedom and temperature, in total and per species (k_B = 1;
// fixed obstacles, particles of infinite mass, excluded). This is the one place where
// pedesis decides how many kinetic degrees of freedom a system has; docs/engines.md
// ("Temperature and degrees of freedom") states the rule for every engine and boundary.
//
// Equipartition gives <K> = f T / 2 with f the number of velocity components that are
// free. Dynamics that conserve total momentum (pair forces only: the event and stepped
// engines, `nve` without self-propulsion) fix one component per axis along which nothing
// else pushes the particles: a periodic axis, as long as no particle has infinite mass.
// Each such component removes one degree of freedom: f = d N_mobile - c, with c the
// number of conserved components (d in a fully periodic box, 0 with walls on every axis,
// under a thermostat or Brownian noise, or with a fixed obstacle).
//
// The temperature is then measured in the centre-of-mass frame along the conserved
// components, T = 2 (K - P^2 / 2M) / f, so that a drifting gas has the temperature of
// its thermal motion (with zero total momentum, K itself).
//
// Per species, the conserved components are shared in proportion to mass:
// f_s = d N_s - c M_s / M. This is exact for equipartition with a fixed total momentum
// (the velocities have covariance T (delta_ij / m_i - 1 / M), so <m_i v_i^2> = d T (1 -
// m_i / M)), the f_s add up to f, and T_s = 2 K_s / f_s equals T on average in a
// mixture of any size; the usual d N_s would be biased low by the factor 1 - m_s / M.
#include "pedesis/core/box.hpp"
#include "pedesis/core/particles.hpp"
#include "pedesis/core/sym_tensor.hpp"

#include <array>
#include <cmath>
#include <vector>

namespace pedesis {

// Whether the equations of motion conserve total momentum when nothing outside the
// particles pushes them (no wall, no fixed obstacle): pair forces and collisions do;
// a thermostat, Brownian noise or a one-body force such as self-propulsion does not.
enum class Momentum { conserving, not_conserving };

struct SpeciesKinetics {
    std::vector<double> kinetic;     // per species: sum m v^2 / 2 (lab frame)
    std::vector<double> thermal;     // per species: the same in the centre-of-mass frame
    std::vector<double> freedom;     // per species: degrees of freedom f_s
    std::vector<std::size_t> mobile; // per species: particles with finite mass
    double total_kinetic = 0.0;
    double total_thermal = 0.0;
    SymTensor thermal_tensor{}; // sum m u_a u_b, u the velocity in the centre-of-mass frame
    double total_freedom = 0.0;
    std::size_t total_mobile = 0;
    int conserved_components = 0; // c: momentum components fixed by the dynamics

    double temperature(std::size_t s) const {
        return freedom[s] > 0.0 ? 2.0 * thermal[s] / freedom[s] : 0.0;
    }
    double temperature() const {
        return total_freedom > 0.0 ? 2.0 * total_thermal / total_freedom : 0.0;
    }
};

// The momentum components a system keeps constant: along periodic axes, if the dynamics
// conserves momentum and no particle has infinite mass.
template <int D>
std::array<bool, D> conserved_momentum_axes(const ParticleStore<D>& p, const Box<D>& box,
                                            Momentum dynamics) {
    std::array<bool, D> axes{};
    if (dynamics == Momentum::not_conserving) return axes;
    for (std::size_t i = 0; i < p.size(); ++i)
        if (std::isinf(p.mass(i))) return axes;
    for (int a = 0; a < D; ++a) axes[a] = box.periodic(a);
    return axes;
}

template <int D>
SpeciesKinetics measure_kinetics(const ParticleStore<D>& p, const std::array<bool, D>& conserved) {
    const std::size_t species = p.species_table.size();
    SpeciesKinetics k;
    k.kinetic.assign(species, 0.0);
    k.thermal.assign(species, 0.0);
    k.mobile.assign(species, 0);
    std::vector<double> mass(species, 0.0);
    for (int a = 0; a < D; ++a) k.conserved_components += conserved[a] ? 1 : 0;

    // Centre-of-mass velocity along the conserved components (zero elsewhere, and zero
    // altogether when nothing is conserved, so that T is then exactly 2 K / (d N)).
    Vec<D> centre{};
    if (k.conserved_components > 0) {
        Vec<D> momentum{};
        double total_mass = 0.0;
        for (std::size_t i = 0; i < p.size(); ++i) {
            if (std::isinf(p.mass(i))) continue;
            momentum += p.mass(i) * p.velocity[i];
            total_mass += p.mass(i);
        }
        for (int a = 0; a < D; ++a)
            if (conserved[a] && total_mass > 0.0) centre[a] = momentum[a] / total_mass;
    }
    for (std::size_t i = 0; i < p.size(); ++i) {
        const double m = p.mass(i);
        if (std::isinf(m)) continue;
        const std::uint16_t s = p.species[i];
        const double e = 0.5 * m * norm2(p.velocity[i]);
        k.kinetic[s] += e;
        k.total_kinetic += e;
        const Vec<D> u = p.velocity[i] - centre;
        const double thermal = k.conserved_components > 0 ? 0.5 * m * norm2(u) : e;
        k.thermal[s] += thermal;
        k.total_thermal += thermal;
        add_sym_outer<D>(k.thermal_tensor, u, u, m);
        mass[s] += m;
        ++k.mobile[s];
        ++k.total_mobile;
    }

    double total_mass = 0.0;
    for (double m : mass) total_mass += m;
    const double c = k.conserved_components;
    k.freedom.assign(species, 0.0);
    for (std::size_t s = 0; s < species; ++s) {
        k.freedom[s] = D * static_cast<double>(k.mobile[s]);
        if (c > 0.0 && total_mass > 0.0) k.freedom[s] -= c * mass[s] / total_mass;
    }
    k.total_freedom = D * static_cast<double>(k.total_mobile);
    if (k.total_mobile > 0) k.total_freedom -= c;
    return k;
}

template <int D>
SpeciesKinetics measure_kinetics(const ParticleStore<D>& p, const Box<D>& box, Momentum dynamics) {
    return measure_kinetics<D>(p, conserved_momentum_axes(p, box, dynamics));
}

} // namespace pedesis
