#pragma once
// Kinetic energy and temperature per species (k_B = 1; fixed obstacles excluded).
#include "pedesis/core/particles.hpp"

#include <cmath>
#include <vector>

namespace pedesis {

struct SpeciesKinetics {
    std::vector<double> kinetic;     // per species
    std::vector<std::size_t> mobile; // per species: particles with finite mass
    double total_kinetic = 0.0;
    std::size_t total_mobile = 0;

    double temperature(int dim, std::size_t s) const {
        return mobile[s] ? 2.0 * kinetic[s] / (dim * static_cast<double>(mobile[s])) : 0.0;
    }
    double temperature(int dim) const {
        return total_mobile ? 2.0 * total_kinetic / (dim * static_cast<double>(total_mobile)) : 0.0;
    }
};

template <int D> SpeciesKinetics measure_kinetics(const ParticleStore<D>& p) {
    SpeciesKinetics k;
    k.kinetic.assign(p.species_table.size(), 0.0);
    k.mobile.assign(p.species_table.size(), 0);
    for (std::size_t i = 0; i < p.size(); ++i) {
        const double m = p.mass(i);
        if (std::isinf(m)) continue;
        const double e = 0.5 * m * norm2(p.velocity[i]);
        k.kinetic[p.species[i]] += e;
        ++k.mobile[p.species[i]];
        k.total_kinetic += e;
        ++k.total_mobile;
    }
    return k;
}

} // namespace pedesis
