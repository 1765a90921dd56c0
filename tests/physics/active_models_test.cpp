// The active models beyond ABPs against exact results (../shared/PHYSICS.md, "Active
// particles: exact results for new models"): chiral ABPs (active_torque), run-and-tumble
// particles, inertial ABPs (langevin with self_propulsion), and the nematic and velocity
// alignments; and trajectories independent of the number of OpenMP threads.
//
// Statistics: N independent (ideal) particles, one time origin. |Delta r|^2 of one
// particle has a relative spread of about 1 (exponential-like in 2D, less in 3D), so an
// MSD over N particles has a relative standard error of about 1/sqrt(N): 0.7% for N =
// 20000, 1% for N = 10000. The tolerances, 3-5%, are 4-5 of those; the discretisation
// errors (Euler-Maruyama's O(D_r dt), a tumble counted at step resolution) are below 0.5%.
// The storage is never sorted here (Evolver's sort interval is 0 unless set), so index i
// holds tag i throughout.
#include "support/soft_builder.hpp"
#include "support/thread_independence.hpp"

#include "pedesis/soft/active_torque.hpp"
#include "pedesis/soft/brownian.hpp"
#include "pedesis/soft/evolver.hpp"
#include "pedesis/soft/langevin.hpp"
#include "pedesis/soft/nematic_align.hpp"
#include "pedesis/soft/pair_force.hpp"
#include "pedesis/soft/pair_potentials.hpp"
#include "pedesis/soft/run_and_tumble.hpp"
#include "pedesis/soft/self_propulsion.hpp"
#include "pedesis/soft/velocity_align.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <complex>
#include <numbers>

using namespace pedesis;

namespace {

// Free ABP-like MSD with persistence time tau: 2 d D_t t + 2 v0^2 tau^2 (t/tau - 1 +
// e^{-t/tau}) (PHYSICS.md; for ABPs 1/tau = (d-1) D_r, for run-and-tumble lambda, with
// both lambda + (d-1) D_r).
double persistent_msd(int d, double Dt, double v0, double tau, double t) {
    return 2.0 * d * Dt * t + 2.0 * v0 * v0 * tau * tau * (t / tau - 1.0 + std::exp(-t / tau));
}

// Chiral ABP in 2D (van Teeffelen & Loewen 2008; PHYSICS.md): K = D_r^2 + omega^2,
// <Delta r^2> = 4 D_t t + (2 v0^2/K)[D_r t - (D_r^2 - omega^2)/K
//               + e^{-D_r t}((D_r^2 - omega^2) cos omega t - 2 D_r omega sin omega t)/K].
double chiral_msd(double Dt, double Dr, double omega, double v0, double t) {
    const double K = Dr * Dr + omega * omega, c = Dr * Dr - omega * omega;
    return 4.0 * Dt * t +
           (2.0 * v0 * v0 / K) *
               (Dr * t - c / K +
                std::exp(-Dr * t) *
                    (c * std::cos(omega * t) - 2.0 * Dr * omega * std::sin(omega * t)) / K);
}

template <int D>
double msd_of(const SoftState<D>& s, const std::vector<Vec<D>>& start, std::size_t first = 0,
              std::size_t stride = 1) {
    double sum = 0.0;
    std::size_t count = 0;
    for (std::size_t i = first; i < s.size(); i += stride, ++count)
        sum += norm2(s.unwrapped(i) - start[i]);
    return sum / static_cast<double>(count);
}

template <int D> std::vector<Vec<D>> unwrapped_positions(const SoftState<D>& s) {
    std::vector<Vec<D>> r(s.size());
    for (std::size_t i = 0; i < s.size(); ++i) r[i] = s.unwrapped(i);
    return r;
}

template <int D> double mean_alignment(const SoftState<D>& s, const std::vector<Vec<D>>& n0) {
    double sum = 0.0;
    for (std::size_t i = 0; i < s.size(); ++i) sum += dot(s.director[i], n0[i]);
    return sum / static_cast<double>(s.size());
}

// ---- chiral ABPs --------------------------------------------------------------------

// Two species with torques +2 and -1 (per species), gamma_r = 1: omega = +2 and -1. The
// MSD of each species against the closed form at three times (tolerance 5%: N = 10000
// per species, 5 standard errors), and the mean angular velocity, the accumulated turn
// of each director over the run divided by t, against tau / gamma_r: the turn's noise has
// variance 2 D_r t, so the mean has the standard error sqrt(2 D_r t / N) / t (0.014 at
// t = 0.5, 0.004 at t = 6); tolerance 4 of those.
TEST(ChiralAbp, FreeMsdAndAngularVelocity2D) {
    const std::size_t n = 20000;
    const double v0 = 1.0, T = 0.1, Tr = 0.5, gamma = 1.0, gamma_r = 1.0, dt = 0.005;
    const double torque[2] = {2.0, -1.0};
    auto s = test::random_soft_system<2>(n, 300.0, 1.0, 31);
    s.p.species_table = {Species{"A", 1.0, 1.0}, Species{"B", 1.0, 1.0}};
    for (std::size_t i = 0; i < n; ++i) s.p.species[i] = static_cast<std::uint16_t>(i % 2);
    Evolver<2> e(s, 2.0);
    e.add_force(std::make_unique<SelfPropulsion<2>>(v0 * gamma));
    e.add_torque(
        std::make_unique<ActiveTorque<2>>(PerSpecies(std::vector<double>{torque[0], torque[1]})));
    e.add_integrator(std::make_unique<BrownianIntegrator<2>>(T, gamma, 5));
    e.add_integrator(std::make_unique<BrownianRotationIntegrator<2>>(Tr, gamma_r, 5));
    const auto start = unwrapped_positions(s);
    std::vector<double> turned(n, 0.0);
    const double Dt = T / gamma, Dr = Tr / gamma_r;
    std::uint64_t done = 0;
    for (double t : {0.5, 2.0, 6.0}) {
        const auto steps = static_cast<std::uint64_t>(std::llround(t / dt));
        for (; done < steps; ++done) {
            const std::vector<Vec<2>> before = s.director;
            e.run(1, dt);
            for (std::size_t i = 0; i < n; ++i)
                turned[i] +=
                    std::atan2(before[i][0] * s.director[i][1] - before[i][1] * s.director[i][0],
                               dot(before[i], s.director[i]));
        }
        for (std::size_t sp = 0; sp < 2; ++sp) {
            const double omega = torque[sp] / gamma_r;
            const double theory = chiral_msd(Dt, Dr, omega, v0, t);
            EXPECT_NEAR(msd_of(s, start, sp, 2) / theory, 1.0, 0.05)
                << "MSD of species " << sp << " (omega " << omega << ") at t = " << t;
            double mean_turn = 0.0;
            for (std::size_t i = sp; i < n; i += 2) mean_turn += turned[i];
            mean_turn /= static_cast<double>(n / 2);
            const double standard_error = std::sqrt(2.0 * Dr * t / static_cast<double>(n / 2)) / t;
            std::printf("species %zu, t = %g: MSD / theory %.4f, angular velocity %.4f (omega "
                        "%g, standard error %.4f)\n",
                        sp, t, msd_of(s, start, sp, 2) / theory, mean_turn / t, omega,
                        standard_error);
            EXPECT_NEAR(mean_turn / t, omega, 4.0 * standard_error)
                << "mean angular velocity of species " << sp << " at t = " << t;
        }
    }
}

// 3D: a lab-frame torque c e (|e| = 1), no noise: the director precesses about e at
// omega = c / gamma_r, n(t) = n0 cos(omega t) + (e x n0) sin(omega t) + e (e.n0)(1 - cos).
// The Euler step turns about the part of w normal to n, an error O(omega^2 dt) in the
// angle over the run: 2e-4 here, tolerance 5e-3.
TEST(ChiralAbp, LabFrameTorquePrecesses3D) {
    auto s = test::random_soft_system<3>(50, 20.0, 1.0, 9);
    const Vec<3> e_axis = Vec<3>{{1.0, 2.0, 2.0}} * (1.0 / 3.0);
    const double c = 1.5, gamma_r = 2.0, omega = c / gamma_r, dt = 0.001, t = 2.0;
    const std::vector<Vec<3>> n0 = s.director;
    Evolver<3> e(s, 0.5);
    e.add_torque(std::make_unique<ActiveTorque<3>>(1.0, c * e_axis));
    e.add_integrator(std::make_unique<BrownianIntegrator<3>>(0.0, 1.0, 1));
    e.add_integrator(std::make_unique<BrownianRotationIntegrator<3>>(0.0, gamma_r, 1));
    e.run(static_cast<std::uint64_t>(std::llround(t / dt)), dt);
    const double cs = std::cos(omega * t), sn = std::sin(omega * t);
    for (std::size_t i = 0; i < s.size(); ++i) {
        const Vec<3>& a = n0[i];
        const Vec<3> exa{{e_axis[1] * a[2] - e_axis[2] * a[1], e_axis[2] * a[0] - e_axis[0] * a[2],
                          e_axis[0] * a[1] - e_axis[1] * a[0]}};
        const Vec<3> expected = cs * a + sn * exa + (dot(e_axis, a) * (1.0 - cs)) * e_axis;
        EXPECT_LT(norm(s.director[i] - expected), 5e-3) << "particle " << i;
    }
}

// ---- run-and-tumble -----------------------------------------------------------------

// Free run-and-tumble particles (tumble rate lambda), with rotational diffusion D_r on
// top where D_r > 0: the ABP MSD with 1/tau = lambda + (d-1) D_r, and <n(t).n(0)> =
// e^{-t/tau} (its mean over N has a standard error below 0.7/sqrt(N) = 0.005;
// tolerance 0.02).
template <int D> void check_free_run_and_tumble(double lambda, double Tr) {
    const std::size_t n = 20000;
    const double v0 = 1.0, T = 0.05, gamma = 1.0, dt = 0.01;
    auto s = test::random_soft_system<D>(n, 200.0, 1.0, 13);
    const std::vector<Vec<D>> n0 = s.director;
    Evolver<D> e(s, 2.0);
    e.add_force(std::make_unique<SelfPropulsion<D>>(v0 * gamma));
    e.add_integrator(std::make_unique<BrownianIntegrator<D>>(T, gamma, 7));
    e.add_integrator(std::make_unique<RunAndTumble<D>>(lambda, 7));
    if (Tr > 0.0) e.add_integrator(std::make_unique<BrownianRotationIntegrator<D>>(Tr, 1.0, 7));
    const auto start = unwrapped_positions(s);
    const double tau = 1.0 / (lambda + (D - 1) * Tr);
    std::uint64_t done = 0;
    for (double t : {0.3, 1.0, 4.0}) {
        const auto steps = static_cast<std::uint64_t>(std::llround(t / dt));
        e.run(steps - done, dt);
        done = steps;
        EXPECT_NEAR(msd_of(s, start) / persistent_msd(D, T / gamma, v0, tau, t), 1.0, 0.03)
            << "MSD at t = " << t << " (D = " << D << ", lambda = " << lambda << ", D_r = " << Tr
            << ")";
        EXPECT_NEAR(mean_alignment(s, n0), std::exp(-t / tau), 0.02)
            << "orientation correlation at t = " << t;
    }
}

TEST(RunAndTumble, FreeMsd2D) {
    check_free_run_and_tumble<2>(1.0, 0.0);
}
TEST(RunAndTumble, FreeMsdWithRotationalDiffusion2D) {
    check_free_run_and_tumble<2>(0.5, 0.5);
}
TEST(RunAndTumble, FreeMsd3D) {
    check_free_run_and_tumble<3>(1.0, 0.0);
}
TEST(RunAndTumble, FreeMsdWithRotationalDiffusion3D) {
    check_free_run_and_tumble<3>(0.5, 0.25);
}

// ---- alignments: the formulas on one pair -------------------------------------------

// Two particles 1 apart, alignment range 2: one torque evaluation.
template <int D> SoftState<D> pair_state(const Vec<D>& ni, const Vec<D>& nj) {
    auto s = test::random_soft_system<D>(2, 10.0, 0.5, 1);
    s.p.position[0] = Vec<D>{};
    s.p.position[1] = Vec<D>{};
    s.p.position[1][0] = 1.0;
    s.director[0] = ni * (1.0 / norm(ni));
    s.director[1] = nj * (1.0 / norm(nj));
    return s;
}

template <int D> void torques_of(SoftState<D>& s, std::unique_ptr<TorqueTerm<D>> term) {
    Evolver<D> e(s, 0.5);
    e.add_torque(std::move(term));
    e.add_integrator(std::make_unique<BrownianIntegrator<D>>(0.0, 1.0, 1));
    e.compute_forces();
}

TEST(NematicAlign, PairTorqueIsHalfJSinTwiceTheAngle2D) {
    const double J = 0.7;
    for (double delta : {0.3, 1.2, 2.0, -2.8}) {
        auto s = pair_state<2>(Vec<2>{{1.0, 0.0}}, Vec<2>{{std::cos(delta), std::sin(delta)}});
        torques_of<2>(s, std::make_unique<NematicAlign<2>>(J, 2.0));
        EXPECT_NEAR(s.torque[0][0], 0.5 * J * std::sin(2.0 * delta), 1e-14) << delta;
        EXPECT_NEAR(s.torque[1][0], -0.5 * J * std::sin(2.0 * delta), 1e-14) << delta;
    }
    // out of range: nothing
    auto far = pair_state<2>(Vec<2>{{1.0, 0.0}}, Vec<2>{{0.0, 1.0}});
    far.p.position[1][0] = 2.5;
    torques_of<2>(far, std::make_unique<NematicAlign<2>>(J, 2.0));
    EXPECT_EQ(far.torque[0][0], 0.0);
}

TEST(NematicAlign, PairTorque3D) {
    const double J = 1.3;
    auto s = pair_state<3>(Vec<3>{{1.0, 0.2, -0.4}}, Vec<3>{{-0.3, 0.9, 0.5}});
    const Vec<3> ni = s.director[0], nj = s.director[1];
    torques_of<3>(s, std::make_unique<NematicAlign<3>>(J, 2.0));
    const TorqueVec<3> expected = (J * dot(ni, nj)) * cross(ni, nj);
    for (int a = 0; a < 3; ++a) {
        EXPECT_NEAR(s.torque[0][a], expected[a], 1e-14) << a;
        EXPECT_NEAR(s.torque[1][a], -expected[a], 1e-14) << a;
    }
}

// tau_i = J n_i x (u_i + u_j), u the unit velocities; a particle at rest adds nothing.
TEST(VelocityAlign, PairTorqueTurnsTowardsTheVelocities3D) {
    const double J = 0.9;
    auto s = pair_state<3>(Vec<3>{{1.0, 0.0, 0.0}}, Vec<3>{{0.0, 1.0, 0.0}});
    s.p.velocity[0] = Vec<3>{{0.0, 0.0, 2.0}};
    s.p.velocity[1] = Vec<3>{{3.0, 4.0, 0.0}};
    const Vec<3> u0{{0.0, 0.0, 1.0}}, u1{{0.6, 0.8, 0.0}};
    torques_of<3>(s, std::make_unique<VelocityAlign<3>>(J, 2.0));
    const TorqueVec<3> t0 = J * cross(s.director[0], u0 + u1),
                       t1 = J * cross(s.director[1], u0 + u1);
    for (int a = 0; a < 3; ++a) {
        EXPECT_NEAR(s.torque[0][a], t0[a], 1e-14) << a;
        EXPECT_NEAR(s.torque[1][a], t1[a], 1e-14) << a;
    }
    s.p.velocity[1] = Vec<3>{};
    torques_of<3>(s, std::make_unique<VelocityAlign<3>>(J, 2.0));
    const TorqueVec<3> alone = J * cross(s.director[0], u0), to_1 = J * cross(s.director[1], u0);
    for (int a = 0; a < 3; ++a) {
        EXPECT_NEAR(s.torque[0][a], alone[a], 1e-14) << a;
        EXPECT_NEAR(s.torque[1][a], to_1[a], 1e-14) << a;
    }
}

// ---- alignments: collective order ---------------------------------------------------

// S = |<exp(2 i theta)>| (nematic) and P = |<exp(i theta)>| (polar) of 2D vectors.
double order_of(const std::vector<Vec<2>>& v, int m) {
    std::complex<double> sum{};
    for (const Vec<2>& x : v) {
        const double theta = std::atan2(x[1], x[0]);
        sum += std::polar(1.0, m * theta);
    }
    return std::abs(sum) / static_cast<double>(v.size());
}

// Particles at rest (no force, T = 0), about 50 neighbours each within a = 4, weak
// rotational noise: nematic alignment must make S > 0.9 from a random start (S, P < 0.2,
// checked), while the directors split into the two halves they started nearest to, so
// that P stays small (< 0.3): polar alignment would make P > 0.9 too.
TEST(NematicAlign, OrdersNematicallyNotPolarly2D) {
    auto s = test::random_soft_system<2>(400, 20.0, 0.5, 17);
    ASSERT_LT(order_of(s.director, 2), 0.2);
    ASSERT_LT(order_of(s.director, 1), 0.2);
    Evolver<2> e(s, 0.5);
    e.add_torque(std::make_unique<NematicAlign<2>>(0.2, 4.0));
    e.add_integrator(std::make_unique<BrownianIntegrator<2>>(0.0, 1.0, 2));
    e.add_integrator(std::make_unique<BrownianRotationIntegrator<2>>(0.01, 1.0, 2));
    e.run(1000, 0.01);
    const double S = order_of(s.director, 2), P = order_of(s.director, 1);
    EXPECT_GT(S, 0.9);
    EXPECT_LT(P, 0.3);
    std::printf("nematic order %.4f, polar order %.4f at t = %.0f\n", S, P, s.time);
}

// Self-propelled ideal particles (no pair force) with velocity alignment: the polar
// order of their velocities grows from a random start (< 0.2, checked) to above 0.9.
TEST(VelocityAlign, OrdersTheVelocitiesOfSelfPropelledParticles2D) {
    auto s = test::random_soft_system<2>(400, std::sqrt(400 / 0.4), 1.0, 23);
    ASSERT_LT(order_of(s.director, 1), 0.2);
    Evolver<2> e(s, 0.5);
    e.add_force(std::make_unique<SelfPropulsion<2>>(1.0));
    e.add_torque(std::make_unique<VelocityAlign<2>>(1.0, 2.0));
    e.add_integrator(std::make_unique<BrownianIntegrator<2>>(0.0, 1.0, 4));
    e.add_integrator(std::make_unique<BrownianRotationIntegrator<2>>(0.01, 1.0, 4));
    e.run(1, 0.01); // (the first step's velocities are the start's, zero)
    ASSERT_LT(order_of(s.p.velocity, 1), 0.2);
    double order = 0.0;
    for (int block = 0; block < 40 && order <= 0.9; ++block) {
        e.run(500, 0.01);
        order = order_of(s.p.velocity, 1);
    }
    EXPECT_GT(order, 0.9) << "after " << s.time << " time units";
    std::printf("velocity order %.4f at t = %.0f\n", order, s.time);
}

// ---- inertial ABPs ------------------------------------------------------------------

// Inertial ABPs: m dv = (alpha n - gamma v) dt + sqrt(2 gamma T) dW, n diffusing with
// <n(s).n(0)> = e^{-s/tau}, tau = 1/((d-1) D_r). In the stationary state the velocity
// correlation is d (T/m) e^{-s/tau_m} + A (tau e^{-s/tau} - tau_m e^{-s/tau_m}) with
// tau_m = m/gamma, v0 = alpha/gamma and A = v0^2 tau / (tau^2 - tau_m^2) (an
// Ornstein-Uhlenbeck filter of the exponentially correlated drive: A fixed by C'(0) = 0
// and C(0) = v0^2 tau/(tau + tau_m)), so the MSD over a lag L from a stationary start is
// 2 sum over its exponentials c e^{-s/theta} of c [theta L - theta^2 (1 - e^{-L/theta})],
// and the long-time diffusion D_eff = T/gamma + v0^2 tau / d = T/gamma + v0^2/(d (d-1)
// D_r), as without inertia. Checked: the MSD at lags 2, 10, 30 after t0 = 10 (e^{-10/tau}
// of the start left; tolerance 5%, N = 10000), and the slope between lags 10 and 30 (the
// exponentials gone to below 1e-2 of it), which is 2 d D_eff.
template <int D> void check_inertial_abp() {
    const std::size_t n = 10000;
    const double v0 = 1.0, T = 0.1, Tr = 0.5, gamma = 1.0, mass = 0.5, dt = 0.005, t0 = 10.0;
    auto s = test::random_soft_system<D>(n, 200.0, 1.0, 29);
    s.p.species_table = {Species{"A", 1.0, mass}};
    Evolver<D> e(s, 2.0);
    e.add_force(std::make_unique<SelfPropulsion<D>>(v0 * gamma));
    e.add_integrator(std::make_unique<LangevinIntegrator<D>>(T, gamma, 3));
    e.add_integrator(std::make_unique<BrownianRotationIntegrator<D>>(Tr, 1.0, 3));
    e.run(static_cast<std::uint64_t>(std::llround(t0 / dt)), dt);
    const auto start = unwrapped_positions(s);

    const double tau = 1.0 / ((D - 1) * Tr), tm = mass / gamma;
    const double A = v0 * v0 * tau / (tau * tau - tm * tm);
    auto part = [](double c, double theta, double L) {
        return 2.0 * c * (theta * L - theta * theta * (1.0 - std::exp(-L / theta)));
    };
    auto theory = [&](double L) {
        return part(D * T / mass, tm, L) + part(A * tau, tau, L) - part(A * tm, tm, L);
    };
    const double D_eff = T / gamma + v0 * v0 / (D * (D - 1) * Tr);
    std::uint64_t done = 0;
    double msd10 = 0.0;
    for (double lag : {2.0, 10.0, 30.0}) {
        const auto steps = static_cast<std::uint64_t>(std::llround(lag / dt));
        e.run(steps - done, dt);
        done = steps;
        const double msd = msd_of(s, start);
        EXPECT_NEAR(msd / theory(lag), 1.0, 0.05) << "MSD at lag " << lag << " (D = " << D << ")";
        if (lag == 10.0) msd10 = msd;
        if (lag == 30.0) {
            EXPECT_NEAR((msd - msd10) / (2.0 * D * 20.0) / D_eff, 1.0, 0.05)
                << "long-time diffusion (D = " << D << "): D_eff = " << D_eff;
        }
    }
}

TEST(InertialAbp, LongTimeDiffusion2D) {
    check_inertial_abp<2>();
}
TEST(InertialAbp, LongTimeDiffusion3D) {
    check_inertial_abp<3>();
}

// ---- thread-count independence ------------------------------------------------------

// Every new term at once, with repulsion and noise, on 1 and 2 threads: bit-identical
// positions, directors and image counters (1000 steps in 2D, 500 in 3D).
template <int D> SoftState<D> all_terms_run() {
    auto s = test::random_soft_system<D>(D == 2 ? 1000 : 600, D == 2 ? 50.0 : 12.0, 1.0, 7, 1.0);
    Evolver<D> e(s, 0.5);
    e.add_force(std::make_unique<PairForce<D, HarmonicPair>>("harmonic", HarmonicPair{10.0, 2.0}));
    e.add_force(std::make_unique<SelfPropulsion<D>>(1.0));
    e.add_torque(std::make_unique<ActiveTorque<D>>(0.3));
    e.add_torque(std::make_unique<NematicAlign<D>>(0.5, 2.0));
    e.add_torque(std::make_unique<VelocityAlign<D>>(0.5, 2.5));
    e.add_integrator(std::make_unique<BrownianIntegrator<D>>(0.1, 1.0, 3));
    e.add_integrator(std::make_unique<BrownianRotationIntegrator<D>>(0.1, 1.0, 3));
    e.add_integrator(std::make_unique<RunAndTumble<D>>(0.5, 3));
    e.run(D == 2 ? 1000 : 500, 0.01);
    return s;
}

TEST(ActiveModelsReproducibility, OneAndTwoThreadsBitIdentical2D) {
    test::expect_thread_independent<2>(all_terms_run<2>);
}
TEST(ActiveModelsReproducibility, OneAndTwoThreadsBitIdentical3D) {
    test::expect_thread_independent<3>(all_terms_run<3>);
}

} // namespace
