// The uniform_noise flag of the brownian and langevin integrators (soft/batch_normals.hpp):
// kicks uniform on [-sqrt 3, sqrt 3], the mean and variance of the standard normals they
// replace, as LAMMPS' fix langevin draws them. Against exact results (docs/engines.md,
// "Uniform noise"): the kicks' moments, free diffusion, and the stationary velocity
// distribution of the Ornstein-Uhlenbeck step, whose temperature is exact and whose
// kurtosis falls below the Gaussian's 3 by a known amount.
#include "support/soft_builder.hpp"

#include "pedesis/soft/brownian.hpp"
#include "pedesis/soft/evolver.hpp"
#include "pedesis/soft/langevin.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <memory>
#include <vector>

using namespace pedesis;
using detail::NoiseShape;

namespace {

// Sample moments <x>, <x^2>, <x^4> and the largest |x|.
struct Moments {
    double mean = 0.0, second = 0.0, fourth = 0.0, largest = 0.0;
};

Moments moments_of(const std::vector<double>& x) {
    Moments m;
    for (double v : x) {
        m.mean += v;
        m.second += v * v;
        m.fourth += v * v * v * v;
        m.largest = std::max(m.largest, std::abs(v));
    }
    const auto n = static_cast<double>(x.size());
    m.mean /= n;
    m.second /= n;
    m.fourth /= n;
    return m;
}

// Free particles need no forces, but the evolver still bins them: a modest box keeps the
// 3D cell grid small.
template <int D> constexpr double free_box = D == 2 ? 400.0 : 60.0;

const char* shape_name(NoiseShape shape) {
    return shape == NoiseShape::uniform ? "uniform" : "gaussian";
}

// One brownian step of free particles moves each component by sqrt(2 T dt / gamma) z.
// z has mean 0 and variance 1 either way; its fourth moment is 9/5 for the uniform
// (whose |z| never exceeds sqrt 3) and 3 for the normal.
//
// Tolerances, over M = 20000 D components (5 standard errors or more each): the mean's
// standard error is 1 / sqrt(M) <= 0.005 (tolerance 0.025); the second moment's is
// sqrt((<z^4> - 1) / M) <= 0.0071 (0.035); the fourth's sqrt((<z^8> - <z^4>^2) / M):
// 0.012 for the uniform (<z^8> = 9; tolerance 0.06), 0.049 for the normal (<z^8> = 105;
// 0.25). The two fourth moments are 1.2 apart, so noise of the wrong shape fails.
template <int D> void check_brownian_kicks(NoiseShape shape) {
    auto s = test::random_soft_system<D>(20000, free_box<D>, 0.5, 3);
    const auto before = s.p.position;
    const double T = 0.7, gamma = 2.0, dt = 0.01;
    Evolver<D> e(s, 1.0);
    e.add_integrator(std::make_unique<BrownianIntegrator<D>>(T, gamma, 5, shape));
    e.run(1, dt);
    const double kick = std::sqrt(2.0 * T * dt / gamma);
    std::vector<double> z;
    for (std::size_t i = 0; i < s.size(); ++i) {
        const Vec<D> move = s.box.minimum_image(s.p.position[i] - before[i]);
        for (int a = 0; a < D; ++a) z.push_back(move[a] / kick);
    }
    const Moments m = moments_of(z);
    std::printf("brownian %dD %s kicks: mean %.4f, <z^2> %.4f, <z^4> %.4f, largest %.4f\n", D,
                shape_name(shape), m.mean, m.second, m.fourth, m.largest);
    EXPECT_NEAR(m.mean, 0.0, 0.025);
    EXPECT_NEAR(m.second, 1.0, 0.035);
    if (shape == NoiseShape::uniform) {
        EXPECT_NEAR(m.fourth, 1.8, 0.06);
        // the move is rounded once beside the position: far below this margin
        EXPECT_LE(m.largest, std::sqrt(3.0) * (1.0 + 1e-9));
    } else {
        EXPECT_NEAR(m.fourth, 3.0, 0.25);
    }
}

// Free diffusion with uniform kicks: <dr^2> = 2 d (T / gamma) t exactly in expectation
// (the kicks' variance is the normals'). After 200 steps each displacement is a sum of
// 200 kicks; its square has a relative spread of about sqrt(2 / d), so over N = 10000
// the standard error is 1% (2D) or 0.8% (3D); tolerance 4%.
template <int D> void check_uniform_diffusion() {
    auto s = test::random_soft_system<D>(10000, free_box<D>, 0.5, 7);
    std::vector<Vec<D>> start(s.size());
    for (std::size_t i = 0; i < s.size(); ++i) start[i] = s.unwrapped(i);
    const double T = 0.5, gamma = 1.0, dt = 0.01;
    Evolver<D> e(s, 1.0);
    e.add_integrator(std::make_unique<BrownianIntegrator<D>>(T, gamma, 9, NoiseShape::uniform));
    e.run(200, dt);
    double msd = 0.0;
    for (std::size_t i = 0; i < s.size(); ++i) msd += norm2(s.unwrapped(i) - start[i]);
    msd /= static_cast<double>(s.size());
    const double theory = 2.0 * D * (T / gamma) * 200 * dt;
    std::printf("brownian %dD uniform MSD: %.5f (theory %.5f)\n", D, msd, theory);
    EXPECT_NEAR(msd / theory, 1.0, 0.04);
}

// Free particles under langevin reach, whatever the noise's shape, <m v_a^2> = T: the O
// step v' = c1 v + c2 xi keeps the variance c2^2 / (1 - c1^2) = T / m of any xi of unit
// variance, and without forces B and A do not touch v. The shape shows in the fourth
// cumulant, c2^4 k4(xi) / (1 - c1^4) with k4 = -6/5 for the uniform and 0 for the
// normal: the kurtosis <v^4> / <v^2>^2 is 3 - (6/5) (1 - c1^2) / (1 + c1^2), here 2.880
// (c1 = e^-0.1), and 3 with Gaussian noise.
//
// Tolerances: M = 4000 D components in each of 40 snapshots one relaxation time apart
// (v correlates as e^-1 between them, v^2 and v^4 far less): the temperature's standard
// error is sqrt(2 * 1.31 / M) <= 0.29% (tolerance 1.5%), the kurtosis's about
// sqrt(24 / M) <= 0.009 (tolerance 0.04). The two shapes' kurtoses are 0.12 apart.
template <int D> void check_langevin_velocities(NoiseShape shape) {
    auto s = test::random_soft_system<D>(4000, free_box<D>, 0.5, 11);
    s.p.species_table[0].mass = 2.0;
    const double T = 1.5, gamma = 1.0, m = 2.0, dt = 0.2;
    const int per_tau = 10; // tau = m / gamma = 2
    Evolver<D> e(s, 1.0);
    e.add_integrator(std::make_unique<LangevinIntegrator<D>>(T, gamma, 13, shape));
    e.run(10 * per_tau, dt);
    std::vector<double> v;
    for (int k = 0; k < 40; ++k) {
        e.run(per_tau, dt);
        for (std::size_t i = 0; i < s.size(); ++i)
            for (int a = 0; a < D; ++a) v.push_back(s.p.velocity[i][a]);
    }
    const Moments mo = moments_of(v);
    const double c1sq = std::exp(-2.0 * gamma * dt / m);
    const double kurtosis = mo.fourth / (mo.second * mo.second);
    const double want =
        shape == NoiseShape::uniform ? 3.0 - 1.2 * (1.0 - c1sq) / (1.0 + c1sq) : 3.0;
    std::printf("langevin %dD %s noise: <m v_a^2> / T = %.4f, kurtosis %.4f (theory %.4f)\n", D,
                shape_name(shape), m * mo.second / T, kurtosis, want);
    EXPECT_NEAR(m * mo.second / T, 1.0, 0.015);
    EXPECT_NEAR(kurtosis, want, 0.04);
}

} // namespace

TEST(UniformNoise, BrownianKicksHaveTheMomentsOfTheirShape2D) {
    check_brownian_kicks<2>(NoiseShape::uniform);
    check_brownian_kicks<2>(NoiseShape::gaussian);
}
TEST(UniformNoise, BrownianKicksHaveTheMomentsOfTheirShape3D) {
    check_brownian_kicks<3>(NoiseShape::uniform);
    check_brownian_kicks<3>(NoiseShape::gaussian);
}

TEST(UniformNoise, FreeDiffusionIsTheGaussians2D) {
    check_uniform_diffusion<2>();
}
TEST(UniformNoise, FreeDiffusionIsTheGaussians3D) {
    check_uniform_diffusion<3>();
}

TEST(UniformNoise, LangevinTemperatureExactKurtosisAsTheory2D) {
    check_langevin_velocities<2>(NoiseShape::uniform);
    check_langevin_velocities<2>(NoiseShape::gaussian);
}
TEST(UniformNoise, LangevinTemperatureExactKurtosisAsTheory3D) {
    check_langevin_velocities<3>(NoiseShape::uniform);
    check_langevin_velocities<3>(NoiseShape::gaussian);
}
