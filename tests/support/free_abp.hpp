#pragma once
// Free active Brownian particles against their exact MSD and orientation correlation:
// one check for the CPU engine (tests/physics/abp_dynamics_test.cpp) and the GPU
// (tests/gpu/gpu_engine_test.cpp).
#include "support/soft_builder.hpp"

#include "pedesis/soft/brownian.hpp"
#include "pedesis/soft/evolver.hpp"
#include "pedesis/soft/self_propulsion.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <functional>

namespace pedesis::test {

// Hands the evolver to a device before the run (none: the CPU).
template <int D> using OnDevice = std::function<void(SoftState<D>&, Evolver<D>&)>;

// Free ABPs: MSD(t) = 2 d D_t t + 2 v0^2 tau^2 (t/tau - 1 + e^{-t/tau}), tau = 1/((d-1) D_r),
// and <n(t).n(0)> = e^{-t/tau}; in 2D this is PHYSICS.md's formula with tau = 1/D_r.
//
// Tolerance 3% on the MSD. Statistics: N = 20000 independent particles, one time origin;
// Delta r^2 of one particle has a relative spread of about 1 (exponential-like in 2D,
// less in 3D), so the mean has a relative standard error of about 1/sqrt(N) = 0.7%, a
// quarter of the tolerance. Discretisation: Euler-Maruyama uses n at the start of each
// step; its relative error in the active part is O((d-1) D_r dt) = 0.25% (2D), 1% (3D).
// Orientation: the mean of n(t).n(0) over N has a standard error below 0.7/sqrt(N) =
// 0.005; tolerance 0.02 absolute (4 standard errors).
template <int D> void check_free_abp(const OnDevice<D>& on_device = {}) {
    const std::size_t n = 20000;
    const double v0 = 1.0, T = 0.1, Tr = 0.5, gamma = 1.0, dt = D == 2 ? 0.005 : 0.01;
    auto s = test::random_soft_system<D>(n, 200.0, 1.0, 11);
    const std::vector<Vec<D>> n0 = s.director;
    Evolver<D> e(s, 2.0);
    e.add_force(std::make_unique<SelfPropulsion<D>>(v0 * gamma));
    e.add_integrator(std::make_unique<BrownianIntegrator<D>>(T, gamma, 5));
    e.add_integrator(std::make_unique<BrownianRotationIntegrator<D>>(Tr, gamma, 5));
    if (on_device) on_device(s, e);
    // by tag: a device keeps the particles in an order of its own
    std::vector<Vec<D>> start(n), n_start(n);
    for (std::size_t i = 0; i < n; ++i) {
        start[s.p.tag[i]] = s.unwrapped(i);
        n_start[s.p.tag[i]] = n0[i];
    }

    const double Dt = T / gamma, Dr = Tr / gamma, tau = 1.0 / ((D - 1) * Dr);
    std::uint64_t done = 0;
    for (double t : {0.2, 1.0, 4.0}) {
        const auto steps = static_cast<std::uint64_t>(std::llround(t / dt));
        e.run(steps - done, dt);
        done = steps;
        e.sync_host();
        double msd = 0.0, corr = 0.0;
        for (std::size_t i = 0; i < n; ++i) {
            msd += norm2(s.unwrapped(i) - start[s.p.tag[i]]);
            corr += dot(s.director[i], n_start[s.p.tag[i]]);
        }
        msd /= n;
        corr /= n;
        const double theory =
            2.0 * D * Dt * t + 2.0 * v0 * v0 * tau * tau * (t / tau - 1.0 + std::exp(-t / tau));
        EXPECT_NEAR(msd / theory, 1.0, 0.03) << "MSD at t = " << t << " (D = " << D << ")";
        EXPECT_NEAR(corr, std::exp(-t / tau), 0.02) << "orientation correlation at t = " << t;
    }
}

} // namespace pedesis::test
