// The NVT thermostats of the soft engine (`bussi`, soft/bussi.hpp; `nose_hoover`,
// soft/nose_hoover.hpp) against exact results, on a 2D WCA fluid of 144 particles at
// density 0.7 and T = 1 in a periodic box:
// - canonical kinetic energy: in the canonical ensemble K is independent of the
//   configuration and Gamma-distributed with shape f / 2 and scale T, so that
//   <K> = f T / 2 and var K = f T^2 / 2, f = 2 N - 2 (the total momentum is conserved and
//   zero; observe/thermo.hpp counts f so). Each is checked within 4 standard errors from
//   block averages, and the errors are checked small enough that the test has power: a
//   thermostat that counted f = 2 N (1% off) or rescaled without noise (var K -> 0)
//   fails;
// - the conserved quantity K + U + bath_energy() drifts by less than a stated bound per
//   particle and unit time, and by much less than the energy the bath exchanges (a sign
//   error in the bath's bookkeeping would leave twice the exchange);
// - the trajectory does not depend on the number of OpenMP threads.
// Also: the chi-square draws of Bussi's rescale have the mean n and variance 2 n.
#include "support/thread_independence.hpp"

#include "pedesis/core/rng.hpp"
#include "pedesis/observe/thermo.hpp"
#include "pedesis/soft/bussi.hpp"
#include "pedesis/soft/evolver.hpp"
#include "pedesis/soft/nose_hoover.hpp"
#include "pedesis/soft/pair_force.hpp"
#include "pedesis/soft/pair_potentials.hpp"

#include <gtest/gtest.h>
#include <omp.h>

#include <cmath>
#include <cstdio>
#include <memory>
#include <vector>

using namespace pedesis;

namespace {

constexpr int side = 12;            // 144 particles
constexpr double density = 0.7;     // a dense WCA fluid, sigma = 1
constexpr double temperature = 1.0; // the bath's
constexpr double dt = 0.005;

// A square lattice at the density, jittered, with Maxwell-Boltzmann velocities at T and
// zero total momentum.
SoftState<2> wca_fluid(std::uint64_t seed) {
    const double spacing = 1.0 / std::sqrt(density), L = side * spacing;
    SoftState<2> s;
    s.box = Box<2>(Vec<2>::filled(L), std::array<bool, 2>{true, true});
    s.resize(side * side);
    s.p.species_table = {Species{"A", 0.5, 1.0}};
    Vec<2> momentum{};
    for (std::size_t i = 0; i < s.size(); ++i) {
        CounterRng rng(seed, RngStream::placement, static_cast<std::uint32_t>(i));
        s.p.position[i] = Vec<2>{{(static_cast<double>(i % side) + 0.5) * spacing - 0.5 * L,
                                  (static_cast<double>(i / side) + 0.5) * spacing - 0.5 * L}};
        s.p.velocity[i] = Vec<2>{{rng.normal(), rng.normal()}} * std::sqrt(temperature);
        momentum += s.p.velocity[i];
        s.p.tag[i] = static_cast<std::uint32_t>(i);
        s.director[i][0] = 1.0;
    }
    for (auto& v : s.p.velocity) v -= momentum * (1.0 / static_cast<double>(s.size()));
    return s;
}

enum class Bath { bussi, nose_hoover };

struct Fluid {
    SoftState<2> state;
    std::unique_ptr<Evolver<2>> evolver;
    Integrator<2>* thermostat = nullptr;

    Fluid(Bath bath, double tau, std::uint64_t seed) : state(wca_fluid(seed)) {
        evolver = std::make_unique<Evolver<2>>(state, 0.3);
        evolver->add_force(std::make_unique<PairForce<2, WcaPair>>("wca", WcaPair{1.0, -1.0}));
        std::unique_ptr<Integrator<2>> i;
        if (bath == Bath::bussi)
            i = std::make_unique<BussiIntegrator<2>>(temperature, tau, seed);
        else
            i = std::make_unique<NoseHooverIntegrator<2>>(temperature, tau, 3);
        i->set_conserved_momentum({true, true});
        thermostat = i.get();
        evolver->add_integrator(std::move(i));
    }
    // K in the centre-of-mass frame and f, as the log's temperature measures them
    SpeciesKinetics kinetics() const {
        return measure_kinetics<2>(state.p, std::array<bool, 2>{true, true});
    }
    double conserved() {
        return kinetics().total_kinetic + evolver->pair_totals().energy + thermostat->bath_energy();
    }
};

struct Moments {
    double mean, mean_error, variance, variance_error;
};

// Mean and variance of the series with their standard errors from `blocks` block
// averages (each block's mean, and its mean square deviation from the whole series' mean).
Moments block_moments(const std::vector<double>& x, int blocks) {
    double mean = 0.0;
    for (double v : x) mean += v;
    mean /= static_cast<double>(x.size());
    const std::size_t per = x.size() / static_cast<std::size_t>(blocks);
    std::vector<double> means, variances;
    for (int b = 0; b < blocks; ++b) {
        double m = 0.0, q = 0.0;
        for (std::size_t k = b * per; k < (b + 1) * per; ++k) {
            m += x[k];
            q += (x[k] - mean) * (x[k] - mean);
        }
        means.push_back(m / static_cast<double>(per));
        variances.push_back(q / static_cast<double>(per));
    }
    auto mean_and_error = [blocks](const std::vector<double>& v) {
        double m = 0.0, q = 0.0;
        for (double a : v) m += a;
        m /= blocks;
        for (double a : v) q += (a - m) * (a - m);
        return std::pair{m, std::sqrt(q / (blocks - 1) / blocks)};
    };
    const auto [m, me] = mean_and_error(means);
    const auto [var, ve] = mean_and_error(variances);
    return {m, me, var, ve};
}

// K sampled every `every` steps over `samples` samples after `equilibration` steps.
std::vector<double> kinetic_series(Fluid& run, int equilibration, int samples, int every,
                                   double& freedom) {
    run.evolver->run(static_cast<std::uint64_t>(equilibration), dt);
    std::vector<double> k;
    for (int n = 0; n < samples; ++n) {
        run.evolver->run(static_cast<std::uint64_t>(every), dt);
        const SpeciesKinetics kin = run.kinetics();
        k.push_back(kin.total_thermal);
        freedom = kin.total_freedom;
    }
    return k;
}

void expect_canonical(Bath bath, double tau, const char* label) {
    omp_set_num_threads(1); // (144 particles: threads would only add their overhead)
    Fluid run(bath, tau, 11);
    double f = 0.0;
    // 2500 samples 20 steps (0.1 time units, a few relaxation times of K) apart
    const std::vector<double> k = kinetic_series(run, 2000, 2500, 20, f);
    ASSERT_EQ(f, 2.0 * side * side - 2.0);
    const Moments m = block_moments(k, 25);
    const double mean = 0.5 * f * temperature, variance = 0.5 * f * temperature * temperature;
    std::printf("%s: <K> = %.3f +- %.3f (theory %.3f), var K = %.2f +- %.2f (theory %.2f)\n", label,
                m.mean, m.mean_error, mean, m.variance, m.variance_error, variance);
    EXPECT_NEAR(m.mean, mean, 4.0 * m.mean_error) << label;
    EXPECT_NEAR(m.variance, variance, 4.0 * m.variance_error) << label;
    // power: a 1% error in f moves <K> by 1.43, which 4 errors must not cover; the variance
    // is known to 10%
    EXPECT_LT(4.0 * m.mean_error, 0.01 * mean) << label;
    EXPECT_LT(m.variance_error, 0.1 * variance) << label;
}

TEST(NvtThermostats, BussiKineticEnergyIsCanonical) {
    expect_canonical(Bath::bussi, 0.05, "bussi");
}

TEST(NvtThermostats, NoseHooverKineticEnergyIsCanonical) {
    expect_canonical(Bath::nose_hoover, 0.1, "nose_hoover");
}

// The conserved quantity over 50 time units after 5 of equilibration: its drift (the slope
// of a least-squares line) per particle and unit time under the bound, and its largest
// excursion far below the energy the bath exchanged (the spread of bath_energy()).
void expect_conserved(Bath bath, double tau, const char* label) {
    omp_set_num_threads(1);
    Fluid run(bath, tau, 5);
    run.evolver->run(1000, dt);
    std::vector<double> t, h, b;
    for (int n = 0; n <= 500; ++n) {
        if (n) run.evolver->run(20, dt);
        t.push_back(run.state.time);
        h.push_back(run.conserved());
        b.push_back(run.thermostat->bath_energy());
    }
    double tm = 0.0, hm = 0.0;
    for (std::size_t k = 0; k < t.size(); ++k) {
        tm += t[k];
        hm += h[k];
    }
    tm /= static_cast<double>(t.size());
    hm /= static_cast<double>(t.size());
    double sxy = 0.0, sxx = 0.0, excursion = 0.0;
    for (std::size_t k = 0; k < t.size(); ++k) {
        sxy += (t[k] - tm) * (h[k] - hm);
        sxx += (t[k] - tm) * (t[k] - tm);
        excursion = std::max(excursion, std::abs(h[k] - h[0]));
    }
    const double n = side * side, drift = std::abs(sxy / sxx) / n;
    const auto [bmin, bmax] = std::minmax_element(b.begin(), b.end());
    const double exchanged = *bmax - *bmin;
    std::printf("%s: drift %.2e per particle per unit time, largest excursion %.3g, bath energy "
                "spread %.3g\n",
                label, drift, excursion, exchanged);
    // bound: 1e-4 per particle per unit time (velocity Verlet's error at dt = 0.005 in this
    // fluid is a bounded oscillation of ~1e-3 per particle: no drift of its own)
    EXPECT_LT(drift, 1e-4) << label;
    EXPECT_LT(excursion, 0.02 * exchanged) << label;
}

TEST(NvtThermostats, BussiConservedEnergyDriftIsBounded) {
    expect_conserved(Bath::bussi, 0.1, "bussi");
}

TEST(NvtThermostats, NoseHooverConservedEnergyDriftIsBounded) {
    expect_conserved(Bath::nose_hoover, 0.1, "nose_hoover");
}

TEST(NvtThermostats, TrajectoriesDoNotDependOnThreadCount) {
    for (Bath bath : {Bath::bussi, Bath::nose_hoover})
        test::expect_thread_independent<2>([bath] {
            Fluid run(bath, 0.1, 3);
            run.evolver->run(300, dt);
            return run.state;
        });
}

TEST(NvtThermostats, ChiSquareDrawsHaveTheirMeanAndVariance) {
    // mean n, variance 2 n; 20000 draws give the mean to sqrt(2 n / 20000) and the variance
    // to about 2 n sqrt(12 / 20000) (a chi-square's fourth cumulant 48 n)
    for (std::uint64_t n : {1u, 2u, 5u, 142u, 2999u}) {
        const int draws = 20000;
        double m = 0.0, q = 0.0;
        std::vector<double> x;
        for (int k = 0; k < draws; ++k) {
            CounterRng rng(7, RngStream::thermostat, static_cast<std::uint32_t>(k), 0);
            x.push_back(detail::chi_square_variate(n, rng));
            m += x.back();
        }
        m /= draws;
        for (double v : x) q += (v - m) * (v - m);
        q /= draws - 1;
        const double nn = static_cast<double>(n);
        EXPECT_NEAR(m, nn, 4.0 * std::sqrt(2.0 * nn / draws)) << n;
        EXPECT_NEAR(q, 2.0 * nn, 4.0 * 2.0 * nn * std::sqrt(12.0 / nn / draws + 2.0 / draws)) << n;
    }
}

} // namespace
