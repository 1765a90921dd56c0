// Active Ornstein-Uhlenbeck particles (soft/active_ou.hpp) against exact results:
//
//  * free AOUPs: <dr^2> = 2 d D_t t + 2 d D_a [t - tau (1 - e^{-t/tau})]
//    (../shared/PHYSICS.md), 2D and 3D;
//  * the active velocity starts and stays stationary: <p^2> = d D_a / tau;
//  * the swim pressure. For a free AOUP started stationary, dr = int_0^t p ds + thermal
//    noise independent of p, so <gamma p(t) . dr> = gamma int_0^t d (D_a/tau)
//    e^{-(t-s)/tau} ds = gamma d D_a (1 - e^{-t/tau}): the swim pressure
//    N <F_a . dr> / (d V) tends to n gamma D_a (the swim diffusivity D_a times gamma
//    times n, as n gamma v0^2 tau_r / d = n gamma D_swim for ABPs). The log's sums
//    (soft_log_sums with ForceTerm::add_active_forces) give the same number;
//  * the same trajectory, bit for bit, on 1 and 2 threads and with storage sorts.
//
// Statistics: N = 20000 independent particles, one time origin; |dr|^2 of one particle
// has a relative spread of about 1, so the MSD's relative standard error is ~0.7%, and
// |p|^2's sqrt(2/d)/sqrt(N) <= 0.7%; tolerance 3%. F_a . dr has a spread of about
// sqrt(2 t / (d tau)) times its mean (2.2 at t = 5 tau, 2D): 1.6% standard error;
// tolerance 7%. Discretisation: p is updated exactly; the positions move by p dt with p
// at the end of each step, which changes the MSD by 2 10^-4 relatively at t = 0.2 tau
// (dt = 0.01 tau, computed from the discrete sum) and the swim pressure by dt / (2 tau)
// = 0.5%.
#include "support/soft_builder.hpp"

#include "pedesis/observe/soft_observables.hpp"
#include "pedesis/soft/active_ou.hpp"
#include "pedesis/soft/brownian.hpp"
#include "pedesis/soft/evolver.hpp"
#include "pedesis/soft/velocity_verlet.hpp"

#include <gtest/gtest.h>
#include <omp.h>

#include <cmath>
#include <cstring>

using namespace pedesis;

namespace {

constexpr double tau = 1.0, Da = 0.8, T = 0.1, gamma = 2.0, dt = 0.01;

template <int D> double mean_p2(const SoftState<D>& s) {
    double sum = 0.0;
    for (const auto& p : s.active_velocity) sum += norm2(p);
    return sum / static_cast<double>(s.size());
}

template <int D> std::vector<Vec<D>> start_positions(const SoftState<D>& s) {
    std::vector<Vec<D>> start(s.size());
    for (std::size_t i = 0; i < s.size(); ++i) start[s.p.tag[i]] = s.unwrapped(i);
    return start;
}

template <int D> void check_free_aoup() {
    const std::size_t n = 20000;
    auto s = test::random_soft_system<D>(n, D == 2 ? 300.0 : 60.0, 0.5, 71);
    Evolver<D> e(s, 2.0);
    add_active_ou(e, tau, Da, 73);
    e.add_integrator(std::make_unique<BrownianIntegrator<D>>(T, gamma, 79));
    e.compute_forces(); // draws the stationary p
    ASSERT_EQ(s.active_velocity.size(), n);
    EXPECT_NEAR(mean_p2(s) / (D * Da / tau), 1.0, 0.03) << "at the start";
    const auto start = start_positions(s);
    const double Dt = T / gamma;
    std::uint64_t done = 0;
    for (double t : {0.2, 1.0, 4.0}) {
        const auto steps = static_cast<std::uint64_t>(std::llround(t / dt));
        e.run(steps - done, dt);
        done = steps;
        const double msd = mean_squared_displacement(s, start);
        const double theory =
            2.0 * D * Dt * t + 2.0 * D * Da * (t - tau * (1.0 - std::exp(-t / tau)));
        EXPECT_NEAR(msd / theory, 1.0, 0.03) << "MSD at t = " << t << " (D = " << D << ")";
    }
    EXPECT_NEAR(mean_p2(s) / (D * Da / tau), 1.0, 0.03) << "after 4 tau";
}

TEST(ActiveOU, FreeMsdAndStationaryActiveVelocity2D) {
    check_free_aoup<2>();
}
TEST(ActiveOU, FreeMsdAndStationaryActiveVelocity3D) {
    check_free_aoup<3>();
}

template <int D> void check_swim_pressure() {
    const std::size_t n = 20000;
    auto s = test::random_soft_system<D>(n, D == 2 ? 300.0 : 60.0, 0.5, 83);
    Evolver<D> e(s, 2.0);
    add_active_ou(e, tau, Da, 89);
    e.add_integrator(std::make_unique<BrownianIntegrator<D>>(T, gamma, 97));
    e.compute_forces();
    const auto start = start_positions(s);
    const double density = static_cast<double>(n) / s.box.volume();
    const ForceTerm<D>& ou = *e.forces().front();
    std::uint64_t done = 0;
    for (double t : {0.5 * tau, 5.0 * tau}) {
        const auto steps = static_cast<std::uint64_t>(std::llround(t / dt));
        e.run(steps - done, dt);
        done = steps;
        const double theory = density * gamma * Da * (1.0 - std::exp(-t / tau));
        const double swim = ou.swim_pressure(s, start);
        EXPECT_NEAR(swim / theory, 1.0, 0.07) << "t = " << t << " (D = " << D << ")";
        // the log's sums: the same number from the per-particle active forces
        std::vector<Vec<D>> active;
        ou.add_active_forces(s, active);
        ASSERT_EQ(active.size(), n);
        const SoftLogSums<D> sums = soft_log_sums(s, start, std::vector<double>{0.0}, active);
        const double from_sums =
            (sums.swim - dot(sums.displacement * (1.0 / sums.particles), sums.swim_direction)) /
            (D * s.box.volume());
        EXPECT_NEAR(from_sums, swim, 1e-9 * std::abs(swim));
        const SymTensor tensor = swim_tensor_of(sums);
        double trace = 0.0;
        for (int a = 0; a < D; ++a) trace += tensor[a];
        EXPECT_NEAR(trace / (D * s.box.volume()), swim, 1e-9 * std::abs(swim));
    }
}

TEST(ActiveOU, SwimPressureTendsToDensityGammaDa2D) {
    check_swim_pressure<2>();
}
TEST(ActiveOU, SwimPressureTendsToDensityGammaDa3D) {
    check_swim_pressure<3>();
}

// Same seed: 1 thread, 2 threads, and 2 threads with the storage sorted at the start and
// every 20 steps give the same positions and active velocities, bit for bit (by tag).
template <int D> SoftState<D> aoup_run(int threads, std::uint64_t sort_every) {
    omp_set_num_threads(threads);
    auto s = test::random_soft_system<D>(3000, 40.0, 0.5, 101);
    Evolver<D> e(s, 1.0);
    e.set_sort_interval(sort_every);
    // (as pedesis run does: sorted before the active velocities are drawn)
    if (sort_every > 0) e.sort_storage_at_start();
    add_active_ou(e, PerSpecies(0.5), PerSpecies(1.0), 103);
    e.add_integrator(std::make_unique<BrownianIntegrator<D>>(0.2, 1.0, 107));
    e.run(200, 0.005);
    e.restore_tag_order();
    return s;
}

template <int D> void check_threads() {
    const int previous = omp_get_max_threads();
    const auto one = aoup_run<D>(1, 0);
    const auto two = aoup_run<D>(2, 0);
    const auto sorted = aoup_run<D>(2, 20);
    omp_set_num_threads(previous);
    const std::size_t bytes = one.size() * sizeof(Vec<D>);
    for (const auto* other : {&two, &sorted}) {
        ASSERT_EQ(other->active_velocity.size(), one.size());
        EXPECT_EQ(std::memcmp(one.p.position.data(), other->p.position.data(), bytes), 0);
        EXPECT_EQ(std::memcmp(one.active_velocity.data(), other->active_velocity.data(), bytes), 0);
    }
}

TEST(ActiveOU, OneAndTwoThreadsAndSortsBitIdentical2D) {
    check_threads<2>();
}
TEST(ActiveOU, OneAndTwoThreadsAndSortsBitIdentical3D) {
    check_threads<3>();
}

// Its force is gamma p with the position integrator's gamma: nve has none.
TEST(ActiveOU, NeedsAFrictionToMakeAForce) {
    auto s = test::random_soft_system<2>(10, 20.0, 0.5, 109);
    Evolver<2> e(s, 1.0);
    add_active_ou(e, 1.0, 1.0, 113);
    e.add_integrator(std::make_unique<VelocityVerletIntegrator<2>>());
    try {
        e.run(1, 0.01);
        FAIL() << "no error";
    } catch (const InputError& err) {
        EXPECT_NE(std::string(err.what()).find("brownian or langevin"), std::string::npos)
            << err.what();
    }
}

} // namespace
