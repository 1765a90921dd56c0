// Walls and containers of the soft engine (soft/wall_force.hpp) against exact results:
//
//  * each wall law's force is -dU/dh (central differences) and its energy is continuous
//    where it ends;
//  * an ideal gas in a container (circle, sphere, cylinder): its density is
//    n_b exp(-U(h)/T) exactly, so the mean outward force on the wall is the Boltzmann
//    average of -U'(h) times N, computed here by quadrature; the run's wall_pressure
//    column must match it;
//  * ideal ABPs between flat walls: the pressure on each wall is
//    n_bulk (D_t + v0^2 / (d (d-1) D_r)) / mu for torque-free walls of any stiffness
//    (Solon et al., Nature Physics 11, 673 (2015)), and a wall that turns the swimmers
//    away lowers it.
// Every noise is drawn from a seed: the runs are deterministic. Tolerances are stated
// at each check, from the statistical error of the samples (several standard errors).
#include "support/soft_builder.hpp"

#include "pedesis/soft/brownian.hpp"
#include "pedesis/soft/evolver.hpp"
#include "pedesis/soft/self_propulsion.hpp"
#include "pedesis/soft/wall_force.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <functional>
#include <numbers>
#include <vector>

using namespace pedesis;

namespace {

TEST(WallLaw, ForceIsMinusTheEnergysSlopeAndTheEnergyEndsAtZero) {
    for (WallPotential p : {WallPotential::wca, WallPotential::lj93, WallPotential::harmonic}) {
        const WallLaw law = WallLaw::make(p, 1.5, 0.8, 30.0, 2.5);
        for (double h = 0.5; h < law.reach - 1e-3; h += 0.01) {
            double f, u, f1, u1, f2, u2;
            ASSERT_TRUE(law.eval(h, f, u));
            ASSERT_TRUE(law.eval(h - 1e-6, f1, u1));
            ASSERT_TRUE(law.eval(h + 1e-6, f2, u2));
            EXPECT_NEAR(f, -(u2 - u1) / 2e-6, 1e-5 * (1.0 + std::abs(f))) << int(p) << " h " << h;
        }
        double f, u;
        ASSERT_TRUE(law.eval(law.reach * (1.0 - 1e-9), f, u));
        EXPECT_NEAR(u, 0.0, 1e-6) << int(p);
        EXPECT_FALSE(law.eval(law.reach, f, u)) << int(p);
    }
}

// Particles of one species ("A", radius 0.5) placed uniformly inside `inside`.
template <int D>
SoftState<D> gas(std::size_t n, const Vec<D>& lengths, const std::array<bool, D>& periodic,
                 const std::function<bool(const Vec<D>&)>& inside, std::uint64_t seed) {
    SoftState<D> s = test::random_soft_system<D>(n, 1.0, 0.5, seed);
    s.box = Box<D>(lengths, periodic);
    for (std::size_t i = 0; i < n; ++i) {
        CounterRng rng(seed + 7, RngStream::placement, static_cast<std::uint32_t>(i));
        do {
            for (int a = 0; a < D; ++a)
                s.p.position[i][a] = rng.uniform(-0.5 * lengths[a], 0.5 * lengths[a]);
        } while (!inside(s.p.position[i]));
    }
    return s;
}

// Integral of f over [a, b], Simpson's rule with 20000 intervals (f smooth there).
double integrate(const std::function<double(double)>& f, double a, double b) {
    const int n = 20000;
    const double h = (b - a) / n;
    double sum = f(a) + f(b);
    for (int k = 1; k < n; ++k) sum += f(a + k * h) * (k % 2 ? 4.0 : 2.0);
    return sum * h / 3.0;
}

// The mean outward force on a container of radius R holding N ideal particles at
// temperature T: N <-U'(h)> over the Boltzmann density, in a shell whose measure grows
// as rho^(m-1) (m = 2 for a circle or a cylinder's cross-section, 3 for a sphere).
double ideal_container_push(const WallLaw& law, double R, double T, double N, int m) {
    const auto weight = [&](double rho) {
        double f = 0.0, u = 0.0;
        law.eval(R - rho, f, u);
        return std::exp(-u / T) * std::pow(rho, m - 1);
    };
    const auto pushed = [&](double rho) {
        double f = 0.0, u = 0.0;
        if (!law.eval(R - rho, f, u)) return 0.0;
        return f * std::exp(-u / T) * std::pow(rho, m - 1);
    };
    const double deep = R - law.reach; // (the weight is rho^(m-1) below)
    const double inner = std::pow(deep, m) / m;
    return N * integrate(pushed, deep, R) / (inner + integrate(weight, deep, R));
}

struct Sampled {
    double mean = 0.0, error = 0.0; // error: standard error from 20 block means
};

// Runs `blocks` x `per_block` steps of dt, reading value() every `every` steps.
template <int D>
Sampled sample(Evolver<D>& e, int warm, int blocks, int per_block, int every, double dt,
               const std::function<double()>& value) {
    e.run(static_cast<std::uint64_t>(warm), dt);
    std::vector<double> block_means;
    for (int b = 0; b < blocks; ++b) {
        double sum = 0.0;
        int count = 0;
        for (int k = 0; k < per_block; k += every) {
            e.run(static_cast<std::uint64_t>(every), dt);
            sum += value();
            ++count;
        }
        block_means.push_back(sum / count);
    }
    Sampled s;
    for (double m : block_means) s.mean += m / blocks;
    double var = 0.0;
    for (double m : block_means) var += (m - s.mean) * (m - s.mean) / (blocks - 1);
    s.error = std::sqrt(var / blocks);
    return s;
}

template <int D> double wall_column(const WallForce<D>& w, const SoftState<D>& s, int k = 0) {
    std::vector<double> v;
    w.log_values(s, v);
    return v.at(static_cast<std::size_t>(k));
}

template <int D>
void expect_ideal_container(WallShape shape, WallPotential potential, double R,
                            const Vec<D>& lengths, double sigma, double T) {
    const double gamma = 1.0;
    const std::size_t n = 400;
    typename WallForce<D>::Shape geometry{shape, R, Vec<D>{}, D - 1};
    std::array<bool, D> periodic;
    periodic.fill(true);
    auto s = gas<D>(
        n, lengths, periodic,
        [&](const Vec<D>& r) {
            Vec<D> d = r;
            if (shape == WallShape::cylinder) d[D - 1] = 0.0;
            return norm(d) < R - 1.2 * sigma;
        },
        11);
    Evolver<D> e(s, 0.5);
    auto wall =
        std::make_unique<WallForce<D>>(potential, geometry, 1.0, PerSpecies(sigma), 40.0, 2.5, 0.0);
    const WallForce<D>& w = *wall;
    e.add_force(std::move(wall));
    e.add_integrator(std::make_unique<BrownianIntegrator<D>>(T, gamma, 5));
    const Sampled p = sample<D>(e, 10000, 20, 5000, 10, 1e-3, [&] { return wall_column(w, s); });
    const WallLaw law = WallLaw::make(potential, 1.0, sigma, 40.0, 2.5);
    const int m = shape == WallShape::sphere ? D : 2;
    const double area = shape == WallShape::cylinder ? 2.0 * std::numbers::pi * R * lengths[D - 1]
                        : m == 2                     ? 2.0 * std::numbers::pi * R
                                                     : 4.0 * std::numbers::pi * R * R;
    const double expected = ideal_container_push(law, R, T, n, m) / area;
    std::printf("container %d potential %d: wall pressure %.5f +- %.5f, exact %.5f\n", int(shape),
                int(potential), p.mean, p.error, expected);
    // 5 standard errors of 20 blocks of 5 time units (longer than the slowest density
    // mode's relaxation, R^2 / (3.8^2 D)), and 2% for the time step's bias at dt = 1e-3
    // (dt U'' <= 0.04 where the particles meet the wall: T / sigma^2 small, what sigma = 2
    // is for with wca and lj93)
    EXPECT_NEAR(p.mean, expected, 5.0 * p.error + 0.02 * expected);
}

TEST(IdealGasInAContainer, CircleHarmonicWall) {
    expect_ideal_container<2>(WallShape::sphere, WallPotential::harmonic, 6.0, Vec<2>{{20.0, 20.0}},
                              0.5, 1.0);
}
TEST(IdealGasInAContainer, CircleWcaWall) {
    expect_ideal_container<2>(WallShape::sphere, WallPotential::wca, 8.0, Vec<2>{{24.0, 24.0}}, 2.0,
                              1.0);
}
TEST(IdealGasInAContainer, SphereLj93Wall) {
    expect_ideal_container<3>(WallShape::sphere, WallPotential::lj93, 6.0,
                              Vec<3>{{16.0, 16.0, 16.0}}, 2.0, 1.0);
}
TEST(IdealGasInAContainer, CylinderHarmonicWall) {
    expect_ideal_container<3>(WallShape::cylinder, WallPotential::harmonic, 4.0,
                              Vec<3>{{12.0, 12.0, 6.0}}, 0.5, 1.0);
}

// Ideal ABPs between the walls of axis x (y, z periodic): the mean pressure on the two
// walls against n_bulk (D_t + v0^2 / (d (d-1) D_r)) / mu, n_bulk the density of the
// middle half of the slab, both sampled over the same steps.
struct SlabResult {
    Sampled pressure, bulk;
};

template <int D>
SlabResult abp_slab(WallPotential potential, double torque, std::size_t n, double L, int blocks,
                    double sigma = 0.5) {
    Vec<D> lengths = Vec<D>::filled(L / (D == 2 ? 1.0 : 2.0));
    lengths[0] = L;
    std::array<bool, D> periodic;
    periodic.fill(true);
    periodic[0] = false;
    auto s = gas<D>(
        n, lengths, periodic,
        [&](const Vec<D>& r) { return std::abs(r[0]) < 0.5 * L - 2.0 * sigma; }, 3);
    Evolver<D> e(s, 0.5);
    auto wall = std::make_unique<WallForce<D>>(potential, typename WallForce<D>::Shape{}, 1.0,
                                               PerSpecies(sigma), 50.0, 2.5, torque);
    const WallForce<D>& w = *wall;
    e.add_force(std::move(wall));
    e.add_force(std::make_unique<SelfPropulsion<D>>(1.0));
    e.add_integrator(std::make_unique<BrownianIntegrator<D>>(0.1, 1.0, 9));
    e.add_integrator(std::make_unique<BrownianRotationIntegrator<D>>(0.5, 1.0, 9));
    double cross_section = 1.0;
    for (int a = 1; a < D; ++a) cross_section *= lengths[a];
    // both sampled together: the pressure at a sample, the bulk density remembered
    std::vector<double> bulk_samples;
    const auto pressure_and_bulk = [&] {
        std::size_t middle = 0;
        for (const auto& r : s.p.position) middle += std::abs(r[0]) < 0.25 * L;
        bulk_samples.push_back(static_cast<double>(middle) / (0.5 * L * cross_section));
        return wall_column(w, s);
    };
    SlabResult out;
    out.pressure = sample<D>(e, 4000, blocks, 2000, 20, 0.005, pressure_and_bulk);
    // the bulk density's blocks, as sample() makes them (100 samples a block)
    std::vector<double> block_means;
    const std::size_t per = bulk_samples.size() / static_cast<std::size_t>(blocks);
    for (int b = 0; b < blocks; ++b) {
        double sum = 0.0;
        for (std::size_t k = 0; k < per; ++k) sum += bulk_samples[b * per + k];
        block_means.push_back(sum / static_cast<double>(per));
    }
    for (double m : block_means) out.bulk.mean += m / blocks;
    double var = 0.0;
    for (double m : block_means) var += (m - out.bulk.mean) * (m - out.bulk.mean) / (blocks - 1);
    out.bulk.error = std::sqrt(var / blocks);
    return out;
}

template <int D> double solon_pressure(double bulk) {
    const double T = 0.1, gamma = 1.0, v0 = 1.0, Dr = 0.5;
    return bulk * (T / gamma + v0 * v0 / (D * (D - 1) * Dr)) * gamma;
}

template <int D> void expect_solon(WallPotential potential, std::size_t n, double L, double sigma) {
    const SlabResult r = abp_slab<D>(potential, 0.0, n, L, 20, sigma);
    const double expected = solon_pressure<D>(r.bulk.mean);
    const double error = std::hypot(r.pressure.error, solon_pressure<D>(r.bulk.error));
    std::printf("%dD ABPs, wall potential %d: pressure %.4f +- %.4f, n_bulk %.4f -> Solon et al. "
                "%.4f\n",
                D, int(potential), r.pressure.mean, r.pressure.error, r.bulk.mean, expected);
    // 5 standard errors, plus 2% for the time step (dt D_r = 0.0025, v0 dt = 0.005)
    EXPECT_NEAR(r.pressure.mean, expected, 5.0 * error + 0.02 * expected);
}

TEST(ActivePressureOnAWall, SoftHarmonicWall2D) {
    expect_solon<2>(WallPotential::harmonic, 1500, 20.0, 0.5);
}
TEST(ActivePressureOnAWall, StiffWcaWall2D) {
    expect_solon<2>(WallPotential::wca, 1500, 20.0, 1.0);
}
TEST(ActivePressureOnAWall, WcaWall3D) {
    expect_solon<3>(WallPotential::wca, 1000, 12.0, 1.0);
}

// A wall that turns the swimmers away from it (tau = c n x F, c > 0) breaks the
// equation of state: the pressure falls well below the torque-free value for the same
// bulk density.
TEST(ActivePressureOnAWall, ATorqueOnTheSwimmersChangesIt) {
    const SlabResult r = abp_slab<2>(WallPotential::harmonic, 1.0, 1500, 20.0, 10);
    const double torque_free = solon_pressure<2>(r.bulk.mean);
    std::printf("with torque: pressure %.4f +- %.4f, torque-free value %.4f\n", r.pressure.mean,
                r.pressure.error, torque_free);
    EXPECT_LT(r.pressure.mean, 0.85 * torque_free);
}

} // namespace
