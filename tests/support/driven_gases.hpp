#pragma once
// Measurements shared by the physics tests of gravity and white-noise driving and their
// long versions in tests/validation/.
#include "pedesis/event/event_engine.hpp"
#include "pedesis/observe/theory.hpp"
#include "support/gas_builder.hpp"

#include <cmath>
#include <vector>

namespace pedesis::test {

// The slope of ln(counts) against the bins' centres (bin width `bin` from 0), weighted by
// the counts, over the bins whose centre lies in [lo, hi] and that hold at least 10.
inline double log_slope(const std::vector<double>& counts, double bin, double lo, double hi) {
    double sw = 0, sy = 0, syy = 0, sl = 0, syl = 0;
    for (std::size_t b = 0; b < counts.size(); ++b) {
        const double y = (static_cast<double>(b) + 0.5) * bin;
        if (y < lo || y > hi || counts[b] < 10) continue;
        const double w = counts[b], l = std::log(counts[b]);
        sw += w;
        sy += w * y;
        syy += w * y * y;
        sl += w * l;
        syl += w * y * l;
    }
    return (sw * syl - sy * sl) / (sw * syy - sy * sy);
}

// A white-noise-driven gas of N equal disks/spheres (diameter 1, mass 1) at packing
// fraction eta, restitution e, kick rate nu and strength s, relaxed for t_relax and
// sampled every 0.5 for t_sample: its mean temperature over the stationary temperature
// of the energy balance, T^(3/2) = m D s nu / ((1 - e^2) omega_1) (driven_granular_test.cpp
// derives it), and the measured collision frequency over Enskog's at that temperature.
// Also the mean injected power per particle, the temperature the balance gives for that
// measured power (T_balance^(3/2) = 2 power / ((1 - e^2) omega_1): the kicks' own scatter
// left out), and the books' residual, injected - lost - (K_end - K_start) over the
// sampling, relative to the injected energy.
struct DrivenResult {
    double T, T_theory, omega_ratio, power, T_balance, residual;
};
template <int D>
DrivenResult driven_gas(std::size_t n, double eta, double e, double nu, double s, double t_relax,
                        double t_sample, std::uint64_t seed) {
    auto spec = equal_gas<D>(n, eta, true, seed);
    spec.placement = Placement::random;
    const auto gas = make_gas(spec);
    EventParams params;
    params.restitution = e;
    params.driving_rate = nu;
    params.driving_strength = s;
    params.seed = seed;
    EventEngine<D> engine(gas.particles, gas.box, params);
    StopLimits lim;
    lim.time = t_relax;
    engine.run(lim);
    const std::uint64_t c0 = engine.counters().pair_collisions;
    const double injected0 = engine.driving().injected_energy;
    const double lost0 = engine.counters().energy_lost, k0 = engine.kinetic_energy();
    double kinetic = 0.0;
    const int samples = static_cast<int>(t_sample / 0.5);
    for (int k = 1; k <= samples; ++k) {
        lim.time = t_relax + 0.5 * k;
        engine.run(lim);
        kinetic += engine.kinetic_energy();
    }
    const double N = static_cast<double>(n);
    const double T = 2.0 * kinetic / samples / (D * (N - 1.0)); // momentum kept
    const double rho = N / gas.box.volume();
    const double omega1 = theory::enskog_collision_frequency(D, rho, 1.0, 1.0, 1.0);
    const double omega =
        2.0 * static_cast<double>(engine.counters().pair_collisions - c0) / t_sample / N;
    const double injected = engine.driving().injected_energy - injected0;
    const double lost = engine.counters().energy_lost - lost0;
    return {T,
            std::pow(D * s * nu / ((1.0 - e * e) * omega1), 2.0 / 3.0),
            omega / (omega1 * std::sqrt(T)),
            injected / t_sample / N,
            std::pow(2.0 * injected / t_sample / N / ((1.0 - e * e) * omega1), 2.0 / 3.0),
            (injected - lost - (engine.kinetic_energy() - k0)) / injected};
}

} // namespace pedesis::test
