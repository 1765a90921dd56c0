#pragma once
// Event engines that compress by Lubachevsky-Stillinger growth, for the growth tests.
#include "pedesis/event/event_engine.hpp"
#include "support/gas_builder.hpp"

namespace pedesis::test {

// n spheres of diameter 1 placed at random at packing fraction eta in a periodic cube,
// growing at `rate` until `target` (0: none) or the reduced pressure 1000.
inline EventEngine<3> growing_gas(std::size_t n, double eta, std::uint64_t seed, double rate,
                                  double target) {
    auto spec = equal_gas<3>(n, eta, true, seed);
    spec.placement = Placement::random;
    auto gas = make_gas(spec);
    EventParams params;
    params.growth_rate = rate;
    params.growth_packing_fraction = target;
    params.growth_max_pressure = 1000.0;
    return EventEngine<3>(gas.particles, gas.box, params);
}

} // namespace pedesis::test
