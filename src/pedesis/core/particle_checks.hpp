#pragma once
// Checks of a restored particle store that every engine's checkpoint loader makes after
// the envelope's checksum has passed, before it builds anything from the particles: a
// file that is not corrupt but crafted (or written by a broken build) must still not
// index outside an array, overflow a cell index, or start a run from a state no
// simulation can reach.
#include "pedesis/core/box.hpp"
#include "pedesis/core/error.hpp"
#include "pedesis/core/particles.hpp"

#include <cmath>
#include <string>
#include <vector>

namespace pedesis {

// Species indices within the table, tags 0..N-1 each once, finite positions and
// velocities with speeds up to 1e100, positions within a box length of the centre (the
// event engine keeps each particle where its last event left it, a little past a periodic
// face); with `wrapped`, inside the box on periodic axes (the soft engine wraps them).
// InputError naming the particle otherwise.
template <int D>
void check_restored_particles(const ParticleStore<D>& p, const Box<D>& box, bool wrapped) {
    const std::size_t n = p.size();
    if (p.velocity.size() != n || p.tag.size() != n || p.species.size() != n)
        throw InputError("corrupt state: the particle arrays differ in length");
    std::vector<bool> seen(n, false);
    for (std::size_t i = 0; i < n; ++i) {
        const std::uint32_t tag = p.tag[i];
        if (tag >= n || seen[tag])
            throw InputError("corrupt state: particle tags are not 0.." + std::to_string(n - 1) +
                             " each once (storage index " + std::to_string(i) + ")");
        seen[tag] = true;
        const std::string who = "corrupt state: particle " + std::to_string(tag);
        if (p.species[i] >= p.species_table.size())
            throw InputError(who + " has species index " + std::to_string(p.species[i]) +
                             ", but there are " + std::to_string(p.species_table.size()));
        for (int a = 0; a < D; ++a) {
            if (!std::isfinite(p.position[i][a]) || !std::isfinite(p.velocity[i][a]))
                throw InputError(who + ": position or velocity is not a finite number");
            if (std::abs(p.velocity[i][a]) > 1e100) throw InputError(who + ": speed above 1e100");
            if (std::abs(p.position[i][a]) > box.length(a))
                throw InputError(who + ": position far outside the box");
            const double half = 0.5 * box.length(a) * (1.0 + 1e-12);
            if (wrapped && box.periodic(a) && std::abs(p.position[i][a]) > half)
                throw InputError(who + ": position outside the box");
        }
    }
}

} // namespace pedesis
