// Free rotational diffusion of directors against the heat kernel on the sphere (3D) and
// on the circle (2D): each Legendre mode decays as <P_l(n(t).n(0))> = exp(-l (l + 1) D_r t)
// in 3D, and <cos(l dtheta)> = exp(-l^2 D_r t) in 2D.
//
// At a coarse step, D_r dt = 0.05, so that a first-order step shows: the earlier 3D step
// (a kick normal to n, then renormalised) gave <P1> = 0.438 and <P2> = 0.081 at
// D_r t = 0.5 instead of 0.368 and 0.050; the rotation with the scaled angle
// (core/sphere_rotation.hpp) is off by 4e-5 and 1.3e-5 there (computed by quadrature of
// its one-step distribution). N = 50000 independent directors: the standard error of
// <P1> is about 0.48 / sqrt(N) = 0.0021, of <P2> about 0.002; tolerance 0.01, 4.5 of them.
#include "support/soft_builder.hpp"

#include "pedesis/soft/brownian.hpp"
#include "pedesis/soft/evolver.hpp"

#include <gtest/gtest.h>

#include <cmath>

using namespace pedesis;

namespace {

// Means of the first two modes after `steps` steps of dt; D_r = Tr / gamma.
template <int D>
std::pair<double, double> modes(double Tr, double dt, int steps, std::size_t n = 50000) {
    auto s = test::random_soft_system<D>(n, D == 3 ? 60.0 : 400.0, 1.0, 7); // (no forces)
    std::vector<Vec<D>> start(n);
    for (std::size_t i = 0; i < n; ++i) start[s.p.tag[i]] = s.director[i];
    Evolver<D> e(s, 2.0);
    e.add_integrator(std::make_unique<BrownianRotationIntegrator<D>>(Tr, 1.0, 3));
    e.run(static_cast<std::uint64_t>(steps), dt);
    double first = 0.0, second = 0.0;
    for (std::size_t i = 0; i < n; ++i) {
        const double c = dot(s.director[i], start[s.p.tag[i]]);
        EXPECT_NEAR(norm(s.director[i]), 1.0, 1e-14) << "particle " << i;
        if constexpr (D == 3) {
            first += c;
            second += 1.5 * c * c - 0.5;
        } else {
            first += c;                  // cos(dtheta)
            second += 2.0 * c * c - 1.0; // cos(2 dtheta)
        }
    }
    return {first / n, second / n};
}

TEST(RotationalDiffusion, ThreeDimensionsFollowsTheHeatKernelAtACoarseStep) {
    const auto [p1, p2] = modes<3>(0.5, 0.1, 10); // D_r dt = 0.05, D_r t = 0.5
    EXPECT_NEAR(p1, std::exp(-2.0 * 0.5), 0.01);
    EXPECT_NEAR(p2, std::exp(-6.0 * 0.5), 0.01);
}

TEST(RotationalDiffusion, ThreeDimensionsAtTheTutorialsStep) {
    // D_r dt = 0.002 as in the validation suite, D_r t = 0.5: the old step was 0.0036
    // high in <P1> here (the validation's +0.003 at t = 1), the new one 6e-8. With
    // N = 400000 the standard error of <P1> is 0.48 / sqrt(N) = 0.00076: tolerance 0.0025
    // (3.3 of them; the seed is fixed, so the test is not flaky either way).
    const auto [p1, p2] = modes<3>(0.5, 0.004, 250, 400000);
    EXPECT_NEAR(p1, std::exp(-1.0), 0.0025);
    EXPECT_NEAR(p2, std::exp(-3.0), 0.0025);
}

TEST(RotationalDiffusion, TwoDimensionsIsExactAtAnyStep) {
    const auto [c1, c2] = modes<2>(0.5, 0.1, 10); // D_r t = 0.5
    EXPECT_NEAR(c1, std::exp(-0.5), 0.01);
    EXPECT_NEAR(c2, std::exp(-4.0 * 0.5), 0.01);
}

} // namespace
