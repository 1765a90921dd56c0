#pragma once
// Compressibility factor of a hard-particle gas in a periodic box from the collision
// virial, measured in blocks after an equilibration period.
//
//   P V = 2 K / D + (1 / (D t)) sum_collisions J n . r_ij     (virial theorem)
//   Z = P V / (N T) with T = 2 K / (D N)  =>  Z = 1 + sum J n . r_ij / (2 K t)
//
// (T is the kinetic temperature of all N particles; in a box with zero total momentum
// the thermodynamic temperature is 2K / (D (N - 1)), which would change Z - 1 by a
// relative 1/N, far below every tolerance used with these helpers.)
#include "pedesis/event/event_engine.hpp"
#include "support/gas_builder.hpp"

#include <vector>

namespace pedesis::test {

struct ZMeasurement {
    BlockStats z;             // block mean and standard error of Z
    BlockStats frequency;     // collisions per particle per unit time (2 x pairs / N / t)
    double temperature = 0.0; // 2 K / (D N)
    double collisions_per_particle = 0.0; // during the measurement
};

template <int D>
ZMeasurement measure_z(const GasSpec<D>& spec, double t_equilibrate, int blocks,
                       double block_time) {
    auto gas = make_gas(spec);
    EventEngine<D> e(gas.particles, gas.box, EventParams{});
    StopLimits lim;
    lim.time = t_equilibrate;
    e.run(lim);
    const double K = e.kinetic_energy(); // constant: elastic collisions
    std::vector<double> z, freq;
    const double n = static_cast<double>(e.size());
    auto virial_sum = [&] {
        double s = 0.0;
        for (int a = 0; a < D; ++a) s += e.counters().virial[a];
        return s;
    };
    const auto c0 = e.counters().pair_collisions;
    for (int b = 0; b < blocks; ++b) {
        const double t0 = e.time(), v0 = virial_sum();
        const auto n0 = e.counters().pair_collisions;
        lim.time = t0 + block_time;
        e.run(lim);
        const double dt = e.time() - t0;
        z.push_back(1.0 + (virial_sum() - v0) / (2.0 * K * dt));
        freq.push_back(2.0 * static_cast<double>(e.counters().pair_collisions - n0) / (n * dt));
    }
    ZMeasurement m;
    m.z = block_stats(z);
    m.frequency = block_stats(freq);
    m.temperature = 2.0 * K / (D * n);
    m.collisions_per_particle =
        static_cast<double>(e.counters().pair_collisions - c0) / static_cast<double>(e.size());
    return m;
}

} // namespace pedesis::test
