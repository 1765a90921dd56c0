#pragma once
// Pressure tensor of a hard-particle gas over a time interval, from the engines' running
// totals. A walled axis's diagonal component is the momentum delivered to its two walls
// per unit time and area (the kinetic-theory definition of seed 003). Every other
// component is the virial's: <sum m u_a u_b> / V + sum J n_a r_ij,b / (V dt), with u the
// velocities in the centre-of-mass frame along conserved axes (thermo.hpp), whose trace
// is 2 K_thermal = f T. Smooth walls push only along their normal, so they add to the
// diagonal alone. The reported pressure is the mean of the diagonal (all equal in
// equilibrium).
#include "pedesis/core/box.hpp"
#include "pedesis/core/collision_counters.hpp"
#include "pedesis/core/sym_tensor.hpp"

namespace pedesis {

// `mean_thermal`: the interval's mean of sum m u_a u_b.
template <int D>
SymTensor interval_pressure_tensor(const Box<D>& box, const EventCounters<D>& before,
                                   const EventCounters<D>& after, double dt,
                                   const SymTensor& mean_thermal) {
    SymTensor p{};
    if (!(dt > 0.0)) return p;
    const double V = box.volume();
    for (int a = 0; a < D; ++a)
        for (int b = a; b < D; ++b) {
            const int c = sym_slot(a, b);
            if (a == b && !box.periodic(a)) {
                const double area = V / box.length(a);
                const double impulse = after.wall_impulse[a][0] - before.wall_impulse[a][0] +
                                       after.wall_impulse[a][1] - before.wall_impulse[a][1];
                p[c] = impulse / (2.0 * area * dt);
            } else {
                p[c] = mean_thermal[c] / V + (after.virial[c] - before.virial[c]) / (V * dt);
            }
        }
    return p;
}

template <int D>
double interval_pressure(const Box<D>& box, const EventCounters<D>& before,
                         const EventCounters<D>& after, double dt, const SymTensor& mean_thermal) {
    return sym_trace<D>(interval_pressure_tensor(box, before, after, dt, mean_thermal)) / D;
}

} // namespace pedesis
