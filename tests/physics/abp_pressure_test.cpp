// Pressure of soft / active systems: the pair virial is the volume derivative of the
// energy, and the swim pressure of free ABPs approaches its exact transient and steady
// state (Takatori, Yan & Brady 2014).
#include "support/soft_builder.hpp"

#include "pedesis/observe/soft_observables.hpp"
#include "pedesis/soft/brownian.hpp"
#include "pedesis/soft/evolver.hpp"
#include "pedesis/soft/pair_force.hpp"
#include "pedesis/soft/pair_potentials.hpp"
#include "pedesis/soft/self_propulsion.hpp"

#include <gtest/gtest.h>

using namespace pedesis;

namespace {

// U of the state with every length (box and positions) scaled by lambda.
template <int D, class Pair> double scaled_energy(SoftState<D> s, const Pair& pair, double lambda) {
    std::array<bool, D> periodic;
    periodic.fill(true);
    s.box = Box<D>(s.box.lengths() * lambda, periodic);
    for (auto& r : s.p.position) r *= lambda;
    Evolver<D> e(s, 0.3);
    e.add_force(std::make_unique<PairForce<D, Pair>>("pair", pair));
    return e.pair_totals().energy;
}

// Under r -> lambda r, dU/dlambda = -sum_pairs r_ij . F_ij, so the virial sum equals
// -dU/dlambda at lambda = 1. Central difference with eps = 1e-6: truncation error
// O(eps^2 U''') ~ 1e-12 relative, rounding ~ 1e-16 U / eps = 1e-10 relative; 1e-6 is a
// tolerance far above both and far below any real error (a factor or a sign).
template <int D, class Pair> void check_virial(const Pair& pair, double L) {
    const auto s = test::random_soft_system<D>(D == 2 ? 400 : 300, L, 0.5, 21);
    SoftState<D> copy = s;
    Evolver<D> e(copy, 0.3);
    e.add_force(std::make_unique<PairForce<D, Pair>>("pair", pair));
    const double virial = e.pair_totals().virial;
    ASSERT_GT(std::abs(virial), 1.0); // the system is dense enough to have many pairs
    const double eps = 1e-6;
    const double dU =
        (scaled_energy(s, pair, 1.0 + eps) - scaled_energy(s, pair, 1.0 - eps)) / (2.0 * eps);
    EXPECT_NEAR(virial / -dU, 1.0, 1e-6);
}

TEST(PairVirial, IsMinusTheVolumeDerivativeOfTheEnergy) {
    check_virial<2>(HarmonicPair{10.0, -1.0}, 14.0);
    check_virial<3>(HarmonicPair{10.0, 1.2}, 8.0);
    check_virial<2>(WcaPair{1.0, -1.0}, 18.0);
    check_virial<3>(WcaPair{1.0, 1.0}, 9.0);
    check_virial<3>(LjPair{1.0, 1.0, 2.5}, 9.0);
}

// Free ABPs: <alpha n(t) . (r(t) - r(0))> = alpha v0 tau (1 - e^{-t/tau}), tau = 1/((d-1) D_r),
// because the displacement is v0 int n ds plus noise independent of n. The swim pressure
// is that times N / (d V), and at long times n alpha^2 / (gamma d (d-1) D_r).
//
// Statistics: N = 10000. n . dr has a spread of about sqrt(MSD / d), which at t = 5 tau is
// about 1.6 v0 tau in 2D against a mean of ~v0 tau: a relative standard error of
// 1.6 / sqrt(N) ~ 1.6%; tolerance 7% (4 standard errors plus the Euler-Maruyama bias,
// O(D_r dt) = 1%).
template <int D> void check_swim_pressure() {
    const std::size_t n = 10000;
    const double alpha = 1.5, gamma = 2.0, T = 0.05, Tr = 1.0, dt = 0.01;
    auto s = test::random_soft_system<D>(n, 300.0, 1.0, 17);
    Evolver<D> e(s, 2.0);
    e.add_force(std::make_unique<SelfPropulsion<D>>(alpha));
    e.add_integrator(std::make_unique<BrownianIntegrator<D>>(T, gamma, 8));
    e.add_integrator(std::make_unique<BrownianRotationIntegrator<D>>(Tr, gamma, 8));
    std::vector<Vec<D>> start(n);
    for (std::size_t i = 0; i < n; ++i) start[s.p.tag[i]] = s.unwrapped(i);
    const double v0 = alpha / gamma, Dr = Tr / gamma, tau = 1.0 / ((D - 1) * Dr);
    const double density = static_cast<double>(n) / s.box.volume();
    const std::vector<double> alpha_of_species = {alpha};
    std::uint64_t done = 0;
    for (double t : {0.5 * tau, 5.0 * tau}) {
        const auto steps = static_cast<std::uint64_t>(std::llround(t / dt));
        e.run(steps - done, dt);
        done = steps;
        const double theory = density * alpha * v0 * tau * (1.0 - std::exp(-t / tau)) / D;
        EXPECT_NEAR(active_pressure(s, start, alpha_of_species) / theory, 1.0, 0.07)
            << "t = " << t << " (D = " << D << ")";
    }
    const double steady = density * alpha * alpha / (gamma * D * (D - 1) * Dr);
    // e^{-5} = 0.7% short of the steady state: within the same tolerance
    EXPECT_NEAR(active_pressure(s, start, alpha_of_species) / steady, 1.0, 0.07);
}

TEST(SwimPressure, FreeAbpApproachTheSteadyState2D) {
    check_swim_pressure<2>();
}
TEST(SwimPressure, FreeAbpApproachTheSteadyState3D) {
    check_swim_pressure<3>();
}

} // namespace

namespace {

// A perfectly ordered flock without noise translates rigidly: every displacement equals
// the mean, so the swim pressure is zero (to rounding), not n alpha v0 t / d, which a
// sum over displacements from the start would give.
TEST(SwimPressure, RigidlyDriftingFlockHasNone) {
    auto s = test::random_soft_system<2>(500, 40.0, 1.0, 3);
    for (auto& n : s.director) n = Vec<2>{{0.6, 0.8}};
    Evolver<2> e(s, 1.0);
    e.add_force(std::make_unique<SelfPropulsion<2>>(1.0));
    e.add_integrator(std::make_unique<BrownianIntegrator<2>>(0.0, 1.0, 1));
    std::vector<Vec<2>> start(s.size());
    for (std::size_t i = 0; i < s.size(); ++i) start[s.p.tag[i]] = s.unwrapped(i);
    e.run(1000, 0.01);
    const double scale = 500.0 / s.box.volume() * 1.0 * 10.0 / 2.0; // n alpha v0 t / d
    EXPECT_LT(std::abs(active_pressure(s, start, {1.0})), 1e-12 * scale);
}

} // namespace
