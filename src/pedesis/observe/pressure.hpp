#pragma once
// Pressure of a hard-particle gas over a time interval, from the event engine's
// running totals. Per axis: a walled axis gives the momentum delivered to its two
// walls per unit time and area (the kinetic-theory definition of seed 003); a
// periodic axis gives the virial: (f / d) T / V + sum J n_a r_ij,a / (V dt), where
// f T / d = 2 K / d is the kinetic part with f the degrees of freedom of thermo.hpp
// (N T / V when nothing is conserved). The reported pressure is the mean over axes (all
// equal in equilibrium).
#include "pedesis/core/box.hpp"
#include "pedesis/core/collision_counters.hpp"

namespace pedesis {

template <int D>
double interval_pressure(const Box<D>& box, const EventCounters<D>& before,
                         const EventCounters<D>& after, double dt, double mean_temperature,
                         double degrees_of_freedom) {
    if (!(dt > 0.0)) return 0.0;
    const double V = box.volume();
    double sum = 0.0;
    for (int a = 0; a < D; ++a) {
        if (box.periodic(a)) {
            sum += degrees_of_freedom / D * mean_temperature / V +
                   (after.virial[a] - before.virial[a]) / (V * dt);
        } else {
            const double area = V / box.length(a);
            const double impulse = after.wall_impulse[a][0] - before.wall_impulse[a][0] +
                                   after.wall_impulse[a][1] - before.wall_impulse[a][1];
            sum += impulse / (2.0 * area * dt);
        }
    }
    return sum / D;
}

} // namespace pedesis
