// Equipartition in small periodic elastic gases with zero total momentum, N = 20 and
// N = 50: a binary mixture (masses 1 and 4, half of each; diameter 1, packing fraction
// pi / 16 ~ 0.2) started at the requested
// temperature T0 = 1 as the runs measure it (docs/engines.md, "Temperature and degrees
// of freedom"), then left to exchange energy between the species.
//
// Exact expectation: at fixed total momentum the velocities are uniform on the sphere
// sum m v^2 = 2K within the subspace sum m v = 0, so <m_i v_i^2> = (2K / f) d (1 - m_i / M)
// with f = d (N - 1). Hence the time-averaged species temperatures T_s = 2 K_s / f_s with
// f_s = d N_s - d M_s / M equal T = 2K / f = T0, which never changes (elastic). The
// convention d N_s would give T_s / T0 = 0.98 and 0.92 (N = 20) or 0.992 and 0.968
// (N = 50) for the light and heavy species; d N for T would give T / T0 = N / (N - 1).
//
// Statistics: one snapshot of T_s has a relative spread of about sqrt(2 / f_s) (0.32 at
// N_s = 10); 40000 snapshots one time unit apart (about one collision per particle) give
// a standard error near 0.25% (N = 20) and 0.1% (N = 50), which the test measures from
// blocks of 1000 snapshots and asserts below 0.4%; about 2 s in all. The tolerance, 1.5%, is then
// at least 3.75 standard errors and still half the smallest bias the test must detect (3.2%).
#include "pedesis/event/event_engine.hpp"
#include "pedesis/observe/thermo.hpp"
#include "pedesis/setup/build_system.hpp"
#include "support/gas_builder.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

using namespace pedesis;
using namespace pedesis::test;

namespace {

// Mean and standard error from the means of consecutive blocks of `per_block` samples.
BlockStats blocks_of(const std::vector<double>& x, std::size_t per_block) {
    std::vector<double> means;
    for (std::size_t b = 0; b + per_block <= x.size(); b += per_block) {
        double s = 0.0;
        for (std::size_t k = b; k < b + per_block; ++k) s += x[k];
        means.push_back(s / static_cast<double>(per_block));
    }
    return block_stats(means);
}

void mixture_case(std::size_t n) {
    // through the config, as a user starts it: the Maxwell-Boltzmann start is part of
    // what is tested
    const std::string half = std::to_string(n / 2);
    const std::string text =
        "dimension = 2\nseed = 11\n[box]\nlength = " +
        std::to_string(std::sqrt(static_cast<double>(n) * 4.0)) +
        "\nboundary = \"periodic\"\n[[species]]\nname = \"light\"\ncount = " + half +
        "\nmass = 1.0\npositions = \"random\"\n[[species]]\nname = "
        "\"heavy\"\ncount = " +
        half + "\nmass = 4.0\npositions = \"random\"\n";
    const RunConfig c = parse_run_config(text, "small_mixture.toml", true);
    const Box<2> box = build_box<2>(c);
    EventEngine<2> e(build_particles<2>(c, box), box, EventParams{});

    const auto start = measure_kinetics(e.snapshot(), box, momentum_of(c));
    ASSERT_EQ(start.total_freedom, 2.0 * static_cast<double>(n - 1));
    EXPECT_NEAR(start.temperature(0), 1.0, 1e-12);
    EXPECT_NEAR(start.temperature(1), 1.0, 1e-12);
    EXPECT_NEAR(start.temperature(), 1.0, 1e-12);

    StopLimits lim;
    lim.time = 50.0;
    e.run(lim);
    std::vector<double> light, heavy, total, heavy_dn; // heavy_dn: 2 K_s / (d N_s)
    for (int k = 0; k < 40000; ++k) {
        lim.time = e.time() + 1.0;
        e.run(lim);
        const auto m = measure_kinetics(e.snapshot(), box, momentum_of(c));
        light.push_back(m.temperature(0));
        heavy.push_back(m.temperature(1));
        total.push_back(m.temperature());
        heavy_dn.push_back(m.kinetic[1] / static_cast<double>(m.mobile[1]));
    }
    const BlockStats l = blocks_of(light, 1000), h = blocks_of(heavy, 1000),
                     t = blocks_of(total, 1000);
    std::printf("N = %zu: T = %.6f, T_light = %.4f +- %.4f, T_heavy = %.4f +- %.4f (with d N_s: "
                "%.4f) (%.1f collisions per particle)\n",
                n, t.mean, l.mean, l.std_error, h.mean, h.std_error, blocks_of(heavy_dn, 1000).mean,
                2.0 * static_cast<double>(e.counters().pair_collisions) / static_cast<double>(n));
    EXPECT_NEAR(t.mean, 1.0, 1e-9) << "elastic collisions keep T at its start value";
    for (const BlockStats& s : {l, h}) {
        EXPECT_LT(s.std_error, 0.004) << "run too short for the tolerance";
        EXPECT_NEAR(s.mean, 1.0, 0.015);
    }
}

} // namespace

TEST(SmallSystemEquipartition, TwentyParticles) {
    mixture_case(20);
}
TEST(SmallSystemEquipartition, FiftyParticles) {
    mixture_case(50);
}
