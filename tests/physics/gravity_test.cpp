// A dilute elastic hard-disk gas under gravity (event engine, [event] gravity):
// - its total energy (kinetic plus the weight times the height) holds to rounding;
// - its density profile is barometric, n(y) ~ exp(-m g y / T), with T its own kinetic
//   temperature (the canonical distribution of a gas in a uniform field);
// - the floor carries the weight: its impulse per time and area is N m g / L_x.
//
// The gas: N = 200 disks of diameter 1, mass 1, in a box 8000 wide (periodic) and 16 high
// (walls), g = 1, started in the lowest eighth at T = 1; it settles at T ~ 0.75, a scale
// height T / (m g) ~ 0.75, after 4000 time units (~25 collisions per particle: the gas is
// dilute, and its collisions are what make the x and y temperatures one). The area fraction at the
// floor is then ~ N pi/4 / (L_x T/(m g)) ~ 0.02, so the excluded volume changes the local slope of
// ln n by at most ~4 phi ~ 1% at one scale height and less above: the fit takes heights from 1 to 6
// scale heights (the top, at 15, holds exp(-15) of the gas: no truncation to speak of). Statistics:
// 5000 snapshots 2 time units apart (about one flight each) give ~3 10^5 heights in the fit's
// range, so the slope's standard error is ~0.3%: tolerance 3% (measured: 0.987, the excluded
// volume's lift near the floor included).
#include "pedesis/event/event_engine.hpp"
#include "support/driven_gases.hpp"
#include "support/falling_gas.hpp"

#include <gtest/gtest.h>

#include <cmath>

using namespace pedesis;
using namespace pedesis::test;

namespace {

EventEngine<2> settled_gas(double t_settle) {
    Gas<2> gas = falling_gas<2>(200, Vec<2>{8000.0, 16.0}, 0.125, 11);
    EventParams params;
    params.gravity = {0.0, -1.0, 0.0};
    EventEngine<2> e(gas.particles, gas.box, params);
    StopLimits lim;
    lim.time = t_settle;
    e.run(lim);
    return e;
}

} // namespace

TEST(Gravity, ElasticRunKeepsTheTotalEnergyToRounding) {
    Gas<2> gas = falling_gas<2>(200, Vec<2>{8000.0, 16.0}, 0.125, 3);
    EventParams params;
    params.gravity = {0.0, -1.0, 0.0};
    EventEngine<2> e(gas.particles, gas.box, params);
    const double e0 = e.kinetic_energy() + e.potential_energy();
    double worst = 0.0;
    for (int k = 1; k <= 400; ++k) {
        StopLimits lim;
        lim.time = 5.0 * k;
        e.run(lim);
        worst = std::max(worst, std::abs(e.kinetic_energy() + e.potential_energy() - e0) / e0);
    }
    // ~10^5 collisions with the floor and each other
    EXPECT_GT(e.counters().wall_collisions + e.counters().pair_collisions, 100000u);
    EXPECT_GT(e.counters().pair_collisions, 4000u);
    EXPECT_LT(worst, 1e-12) << "relative drift of the total energy";
    std::printf("[gravity] energy drift %.2e over %llu collisions\n", worst,
                static_cast<unsigned long long>(e.counters().wall_collisions +
                                                e.counters().pair_collisions));
    e.check_no_overlap(1e-9);
}

TEST(Gravity, BarometricProfileAndTheFloorCarriesTheWeight) {
    EventEngine<2> e = settled_gas(4000.0);
    const Box<2> box = e.box();
    const double floor = box.lo(1) + 0.5; // the centres' lowest height
    const double t0 = e.time();
    const double floor_impulse0 = std::abs(e.counters().wall_impulse[1][0]);
    const double ceiling_impulse0 = std::abs(e.counters().wall_impulse[1][1]);
    const double bin = 0.25;
    std::vector<double> counts(static_cast<std::size_t>(15.0 / bin), 0.0);
    double kinetic_sum = 0.0;
    const int snapshots = 5000;
    for (int k = 1; k <= snapshots; ++k) {
        StopLimits lim;
        lim.time = t0 + 2.0 * k;
        e.run(lim);
        kinetic_sum += e.kinetic_energy();
        for (std::size_t i = 0; i < e.size(); ++i) {
            const auto b = static_cast<std::size_t>((e.position_now(i)[1] - floor) / bin);
            if (b < counts.size()) counts[b] += 1.0;
        }
    }
    // T = 2 <K> / f, f = 2 N - 1 (the momentum along the periodic x is kept)
    const double T = 2.0 * kinetic_sum / snapshots / (2.0 * 200 - 1);
    // weighted least squares of ln n against the bin's centre, weights = counts
    const double slope = log_slope(counts, bin, 1.0 * T, 6.0 * T);
    const double expected = -1.0 / T; // -m g / T
    std::printf("[gravity] T = %.4f, fitted slope %.4f, -m g / T = %.4f (ratio %.4f)\n", T, slope,
                expected, slope / expected);
    EXPECT_NEAR(slope / expected, 1.0, 0.03);
    EXPECT_NEAR(T, 0.75, 0.1); // (where the settling leaves it)

    // the floor's impulse less the ceiling's over the window: the weight's, N m g dt,
    // up to the change of the total momentum (|P_y| ~ sqrt(N m T) ~ 14 against 4 10^5)
    const double dt = e.time() - t0;
    const double floor_force = (std::abs(e.counters().wall_impulse[1][0]) - floor_impulse0) / dt;
    const double ceiling_force =
        (std::abs(e.counters().wall_impulse[1][1]) - ceiling_impulse0) / dt;
    const double weight_per_area = 200.0 * 1.0 * 1.0 / box.length(0);
    std::printf("[gravity] floor pressure %.6g, ceiling %.3g, weight per area %.6g\n",
                floor_force / box.length(0), ceiling_force / box.length(0), weight_per_area);
    EXPECT_NEAR(floor_force / box.length(0) / weight_per_area, 1.0, 1e-3);
    EXPECT_LT(ceiling_force, 1e-3 * floor_force);
}
