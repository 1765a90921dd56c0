// Sedimentation of ideal particles under gravity above a wall floor (2D, walls on y,
// periodic x), against exact results:
//
//  * the density's far-field decay n(y) ~ exp(-lambda y). Passive Brownian particles:
//    the barometric lambda = w / T. Active Brownian particles: lambda solves the
//    far-field eigenproblem of the Fokker-Planck equation. With P(y, theta) =
//    exp(-lambda y) g(theta), stationarity reads
//        D_r g'' + lambda v0 sin(theta) g = lambda (mu w - D_t lambda) g,
//    so lambda is where the largest eigenvalue of the left-hand operator (a Mathieu
//    operator; solved here in a Fourier basis) equals lambda (mu w - D_t lambda). For
//    mu w << v0 it tends to mu w / (D_t + v0^2 / (2 D_r)) (PHYSICS.md; Enculescu & Stark
//    2011 for the exact decay);
//  * the force on the walls: in steady state the walls carry the particles' whole
//    weight, so (F_floor + F_ceiling) / (2 A) = N w / (2 L_x) whatever the activity
//    (the ceiling, many decay lengths up, carries next to nothing).
// The particles start on the first-order profile and relax for 50 time units before
// sampling; every noise comes from a seed (deterministic runs).
#include "support/soft_builder.hpp"

#include "pedesis/soft/brownian.hpp"
#include "pedesis/soft/evolver.hpp"
#include "pedesis/soft/external_fields.hpp"
#include "pedesis/soft/self_propulsion.hpp"
#include "pedesis/soft/wall_force.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <numbers>
#include <vector>

using namespace pedesis;

namespace {

// The largest eigenvalue of D_r d^2/dtheta^2 + a sin(theta) on 2 pi-periodic functions.
// sin(theta) couples the Fourier modes e^{i m theta} to m +- 1; the operator is similar
// to the real symmetric tridiagonal matrix with diagonal -D_r m^2 and off-diagonal a / 2
// (the shift to cos(theta) is a rotation of theta), whose top eigenvalue bisection on
// the Sturm sequence finds.
double top_eigenvalue(double Dr, double a) {
    const int M = 40; // modes -M..M: ample for a / D_r up to ~100
    const int n = 2 * M + 1;
    const auto count_below = [&](double x) { // eigenvalues < x (Sturm sequence)
        int count = 0;
        double q = 1.0;
        for (int k = 0; k < n; ++k) {
            const double m = k - M;
            const double off = k ? 0.5 * a : 0.0;
            q = (-Dr * m * m - x) - (k ? off * off / q : 0.0);
            if (q == 0.0) q = 1e-300;
            count += q < 0.0;
        }
        return count;
    };
    double lo = -Dr * M * M - std::abs(a), hi = std::abs(a) + 1.0;
    for (int it = 0; it < 200; ++it) {
        const double mid = 0.5 * (lo + hi);
        (count_below(mid) < n ? lo : hi) = mid;
    }
    return 0.5 * (lo + hi);
}

// The far-field decay rate of ideal ABPs (v0, D_r, D_t, mobility mu = 1) under weight w:
// the root lambda > 0 of top_eigenvalue(D_r, lambda v0) = lambda (w - D_t lambda).
double exact_decay_rate(double v0, double Dr, double Dt, double w) {
    if (v0 == 0.0) return w / Dt;
    const auto f = [&](double l) { return top_eigenvalue(Dr, l * v0) - l * (w - Dt * l); };
    double lo = 1e-9, hi = w / Dt; // f(lo) > 0 > ... : f(0+) ~ l^2 (v0^2/(2 Dr) + Dt) - l w < 0
    // f < 0 just above 0, f > 0 at w / Dt (the eigenvalue is >= 0): bisect
    lo = 1e-6 * hi;
    for (int it = 0; it < 200; ++it) {
        const double mid = 0.5 * (lo + hi);
        (f(mid) < 0.0 ? lo : hi) = mid;
    }
    return 0.5 * (lo + hi);
}

TEST(SedimentationTheory, DecayRateHasItsLimits) {
    // passive, and the weak-force limit mu w / (D_t + v0^2 / (2 D_r))
    EXPECT_DOUBLE_EQ(exact_decay_rate(0.0, 1.0, 0.5, 0.3), 0.6);
    const double weak = exact_decay_rate(1.0, 1.0, 0.1, 0.01);
    EXPECT_NEAR(weak, 0.01 / 0.6, 1e-3 * 0.01 / 0.6);
    // the eigenvalue of a constant function at a = 0 is 0; second order in a: a^2 / (2 D_r)
    EXPECT_NEAR(top_eigenvalue(2.0, 1e-2), 1e-4 / 4.0, 1e-8);
}

struct Profile {
    double rate = 0.0, rate_error = 0.0; // fitted far-field decay rate
    double wall_pressure = 0.0;          // mean of wall_pressure_y over the samples
};

// Ideal particles (ABPs if v0 > 0) between walls at y = -H/2 (floor) and H/2, weight w
// along -y; the far-field decay rate fitted to the density between `from` and `to`
// above the floor, with its standard error from 10 blocks.
Profile sediment(double v0, double Dr, double T, double w, double from, double to,
                 double guess_rate) {
    const std::size_t n = 3000;
    const double Lx = 20.0, H = 60.0, dt = 0.01;
    auto s = test::random_soft_system<2>(n, 1.0, 0.5, 17);
    s.box = Box<2>(Vec<2>{{Lx, H}}, {true, false});
    for (std::size_t i = 0; i < n; ++i) { // the exponential profile of the guessed rate
        CounterRng rng(23, RngStream::placement, static_cast<std::uint32_t>(i));
        s.p.position[i][0] = rng.uniform(-0.5 * Lx, 0.5 * Lx);
        s.p.position[i][1] = -0.5 * H + 1.0 - std::log(1.0 - rng.uniform(0.0, 0.999)) / guess_rate;
        s.p.position[i][1] = std::min(s.p.position[i][1], 0.5 * H - 1.0);
    }
    // (no pair forces: the skin only bounds a step, and the passive noise, sqrt(2 T dt) =
    // 0.1, must not be taken for a blow-up in 10^7 draws)
    Evolver<2> e(s, 1.0);
    auto wall = std::make_unique<WallForce<2>>(WallPotential::harmonic, WallForce<2>::Shape{}, 1.0,
                                               std::nullopt, 20.0, 2.5, 0.0);
    const WallForce<2>& walls = *wall;
    e.add_force(std::move(wall));
    e.add_force(std::make_unique<Gravity<2>>(PerSpecies(w), 1));
    if (v0 > 0.0) e.add_force(std::make_unique<SelfPropulsion<2>>(v0));
    e.add_integrator(std::make_unique<BrownianIntegrator<2>>(T, 1.0, 29));
    e.add_integrator(std::make_unique<BrownianRotationIntegrator<2>>(Dr, 1.0, 29));
    e.run(5000, dt);
    const double bin = 0.5;
    const int bins = static_cast<int>((to - from) / bin);
    const int blocks = 10;
    std::vector<double> rates;
    Profile out;
    int samples = 0;
    for (int b = 0; b < blocks; ++b) {
        std::vector<double> count(static_cast<std::size_t>(bins), 0.0);
        for (int k = 0; k < 200; ++k) {
            e.run(10, dt);
            for (const auto& r : s.p.position) {
                const double y = r[1] + 0.5 * H - from;
                if (y >= 0.0 && y < bins * bin) count[static_cast<std::size_t>(y / bin)] += 1.0;
            }
            std::vector<double> v;
            walls.log_values(s, v);
            out.wall_pressure += v.at(0);
            ++samples;
        }
        // weighted least squares of log(count) against height (weights: the counts)
        double sw = 0, sy = 0, sl = 0, syy = 0, syl = 0;
        for (int k = 0; k < bins; ++k) {
            if (count[k] <= 0.0) continue;
            const double y = (k + 0.5) * bin, l = std::log(count[k]), wk = count[k];
            sw += wk;
            sy += wk * y;
            sl += wk * l;
            syy += wk * y * y;
            syl += wk * y * l;
        }
        rates.push_back(-(sw * syl - sy * sl) / (sw * syy - sy * sy));
    }
    for (double r : rates) out.rate += r / blocks;
    double var = 0.0;
    for (double r : rates) var += (r - out.rate) * (r - out.rate) / (blocks - 1);
    out.rate_error = std::sqrt(var / blocks);
    out.wall_pressure /= samples;
    return out;
}

void expect_sedimentation(double v0, double Dr, double T, double w, double from, double to) {
    const double exact = exact_decay_rate(v0, Dr, T, w);
    const Profile p = sediment(v0, Dr, T, w, from, to, exact);
    const double weight_per_area = 3000.0 * w / (2.0 * 20.0);
    std::printf("v0 %g: decay rate %.4f +- %.4f, exact %.4f (first order %.4f); wall pressure "
                "%.4f, weight / (2 L_x) %.4f\n",
                v0, p.rate, p.rate_error, exact, w / (T + v0 * v0 / (2.0 * Dr)), p.wall_pressure,
                weight_per_area);
    // 5 standard errors of 10 blocks, and 3% for the time step (v0 dt = 0.01)
    EXPECT_NEAR(p.rate, exact, 5.0 * p.rate_error + 0.03 * exact);
    // the walls carry the weight: within 2% (the same time averages; no statistical
    // spread beyond the slow exchange with the far field)
    EXPECT_NEAR(p.wall_pressure, weight_per_area, 0.02 * weight_per_area);
}

TEST(Sedimentation, PassiveBarometricProfile) {
    expect_sedimentation(0.0, 1.0, 0.5, 0.5, 2.0, 8.0); // lambda = 1
}

TEST(Sedimentation, ActiveSedimentationLength) {
    // mu w / v0 = 0.3: the first-order formula is several % off; the exact rate is not
    expect_sedimentation(1.0, 1.0, 0.1, 0.3, 4.0, 16.0);
}

} // namespace
