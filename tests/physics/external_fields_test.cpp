// External fields for soft particles (soft/external_fields.hpp) against exact results:
//
//  * ideal ABPs in an isotropic harmonic trap (stiffness k, mobility 1/gamma, kappa =
//    k/gamma): the stationary <r^2> = d D_t/kappa + v0^2/(kappa (kappa + (d-1) D_r))
//    (../shared/PHYSICS.md), in 2D and 3D;
//  * passive Brownian particles in a trap with one stiffness per axis: <x_a^2> = T/k_a;
//  * passive particles under gravity w along an axis with a trap k along it: a Gaussian
//    of mean -w/k and variance T/k (the barometric profile itself needs a floor);
//  * the energies gravity_energy and trap_energy and the forces on a small state, against
//    their definitions, with the nearest image of the trap's centre.
//
// Statistics: N = 1000 independent particles, sampled every 0.5/kappa over 40/kappa of
// the stationary state after 8/kappa from a small cloud: about 4 x 10^4 independent
// values of r^2 (relative spread ~1), a relative standard error of ~0.5%; tolerances
// 3-4%. Discretisation: Euler-Maruyama of a linear drift gives the stationary variance
// D/kappa / (1 - kappa dt / 2) exactly, which the passive checks take into account; the
// ABP check's bias is O(kappa dt, D_r dt) = 0.5% (3D), below its tolerance.
#include "support/soft_builder.hpp"

#include "pedesis/soft/brownian.hpp"
#include "pedesis/soft/evolver.hpp"
#include "pedesis/soft/external_fields.hpp"
#include "pedesis/soft/self_propulsion.hpp"

#include <gtest/gtest.h>

#include <cmath>

using namespace pedesis;

namespace {

// N ideal particles of one species within a ball of radius 1 about the origin.
template <int D> SoftState<D> small_cloud(std::size_t n, std::uint64_t seed) {
    const double L = 60.0;
    auto s = test::random_soft_system<D>(n, L, 0.5, seed);
    for (auto& r : s.p.position) r *= 2.0 / L;
    return s;
}

// Per-axis means of x_a and x_a^2 over particles and samples: every `every` steps for
// `samples` samples after `settle` steps.
template <int D> struct AxisMoments { Vec<D> mean{}, square{}; };

template <int D>
AxisMoments<D> sample_moments(SoftState<D>& s, Evolver<D>& e, double dt, std::uint64_t settle,
                              std::uint64_t every, int samples) {
    e.run(settle, dt);
    AxisMoments<D> m;
    for (int k = 0; k < samples; ++k) {
        e.run(every, dt);
        for (std::size_t i = 0; i < s.size(); ++i)
            for (int a = 0; a < D; ++a) {
                m.mean[a] += s.p.position[i][a];
                m.square[a] += s.p.position[i][a] * s.p.position[i][a];
            }
    }
    const double count = static_cast<double>(samples) * static_cast<double>(s.size());
    m.mean *= 1.0 / count;
    m.square *= 1.0 / count;
    return m;
}

template <int D> void check_abp_in_trap() {
    const double k = 1.0, gamma = 1.0, T = 0.2, v0 = 1.0, Tr = 1.0, dt = 0.005;
    auto s = small_cloud<D>(1000, 41);
    // a skin larger than the cloud's motion between builds: almost no rebuilds of a list
    // that has no pair term to serve
    Evolver<D> e(s, 3.0);
    e.add_force(std::make_unique<HarmonicTrap<D>>(k, std::vector<double>{}, Vec<D>{}));
    e.add_force(std::make_unique<SelfPropulsion<D>>(v0 * gamma));
    e.add_integrator(std::make_unique<BrownianIntegrator<D>>(T, gamma, 43));
    e.add_integrator(std::make_unique<BrownianRotationIntegrator<D>>(Tr, 1.0, 47));
    const double kappa = k / gamma, Dt = T / gamma, Dr = Tr;
    const AxisMoments<D> m = sample_moments(s, e, dt, 1600, 100, 80);
    double r2 = 0.0;
    for (int a = 0; a < D; ++a) r2 += m.square[a];
    const double theory = D * Dt / kappa + v0 * v0 / (kappa * (kappa + (D - 1) * Dr));
    EXPECT_NEAR(r2 / theory, 1.0, 0.03) << "<r^2> = " << r2 << ", theory " << theory;
}

TEST(HarmonicTrap, AbpStationaryMeanSquareRadius2D) {
    check_abp_in_trap<2>();
}
TEST(HarmonicTrap, AbpStationaryMeanSquareRadius3D) {
    check_abp_in_trap<3>();
}

template <int D> void check_axis_stiffness(const std::vector<double>& k) {
    const double T = 0.5, gamma = 1.0, dt = 0.004;
    auto s = small_cloud<D>(1000, 53);
    Evolver<D> e(s, 3.0);
    e.add_force(std::make_unique<HarmonicTrap<D>>(1.0, k, Vec<D>{}));
    e.add_integrator(std::make_unique<BrownianIntegrator<D>>(T, gamma, 59));
    // the slowest axis sets the time scale (k = 0.5: 1/kappa = 2)
    const AxisMoments<D> m = sample_moments(s, e, dt, 4000, 250, 80);
    for (int a = 0; a < D; ++a) {
        const double kappa = k[static_cast<std::size_t>(a)] / gamma;
        const double theory = T / k[static_cast<std::size_t>(a)] / (1.0 - 0.5 * kappa * dt);
        EXPECT_NEAR(m.square[a] / theory, 1.0, 0.04) << "axis " << a << " (D = " << D << ")";
    }
}

TEST(HarmonicTrap, PerAxisStiffnessGivesTOverKOnEachAxis) {
    check_axis_stiffness<2>({1.0, 4.0});
    check_axis_stiffness<3>({0.5, 1.0, 4.0});
}

// Along the gravity's axis the equilibrium is at -w/k (exact for Euler-Maruyama too),
// with the variance of the trap alone; the other axes do not feel it. Mean: standard
// error sqrt(T/k / 4 10^4) = 0.0025; tolerance 0.02.
TEST(Gravity, ShiftsATrappedGaussianByWeightOverStiffness) {
    const double T = 0.5, gamma = 1.0, k = 2.0, w = 0.5, dt = 0.004;
    auto s = small_cloud<2>(1000, 61);
    Evolver<2> e(s, 3.0);
    e.add_force(std::make_unique<HarmonicTrap<2>>(k, std::vector<double>{}, Vec<2>{}));
    e.add_force(std::make_unique<Gravity<2>>(w, 1));
    e.add_integrator(std::make_unique<BrownianIntegrator<2>>(T, gamma, 67));
    const AxisMoments<2> m = sample_moments(s, e, dt, 2000, 125, 80);
    EXPECT_NEAR(m.mean[1], -w / k, 0.02);
    EXPECT_NEAR(m.mean[0], 0.0, 0.02);
    const double variance = T / k / (1.0 - 0.5 * (k / gamma) * dt);
    EXPECT_NEAR((m.square[1] - m.mean[1] * m.mean[1]) / variance, 1.0, 0.04);
    EXPECT_NEAR(m.square[0] / variance, 1.0, 0.04);
}

// Three particles of two species in a periodic 10 x 10 x 10 box, by hand.
SoftState<3> three_particles() {
    SoftState<3> s;
    s.box = Box<3>(Vec<3>::filled(10.0), {true, true, true});
    s.resize(3);
    s.p.species_table = {Species{"A", 0.5, 1.0}, Species{"B", 0.5, 1.0}};
    s.p.position = {Vec<3>{{1.0, 2.0, 3.0}}, Vec<3>{{-4.0, 0.5, -2.0}}, Vec<3>{{4.5, -4.5, 0.0}}};
    s.p.species = {0, 1, 1};
    for (std::uint32_t i = 0; i < 3; ++i) s.p.tag[i] = i;
    return s;
}

template <class Term> std::vector<double> logged(const Term& term, const SoftState<3>& s) {
    std::vector<double> out;
    term.log_values(s, out);
    return out;
}

TEST(Gravity, EnergyAndForceAreTheirDefinitions) {
    auto s = three_particles();
    const Gravity<3> g(PerSpecies(std::vector<double>{2.0, -0.5}), 0); // along x
    EXPECT_EQ(g.log_columns(s), std::vector<std::string>{"gravity_energy"});
    // sum w x: 2 * 1 - 0.5 * (-4) - 0.5 * 4.5
    const double u = 2.0 + 2.0 - 2.25;
    ASSERT_EQ(logged(g, s).size(), 1u);
    EXPECT_DOUBLE_EQ(logged(g, s)[0], u);
    NeighborList<3> nl(s.box, 1.0, 0.5);
    PairTotals t;
    g.add_totals(s, nl, t);
    EXPECT_DOUBLE_EQ(t.energy, u);
    EXPECT_EQ(t.virial, 0.0);
    for (auto& f : s.force) f = Vec<3>{};
    g.add_forces(s, nl);
    EXPECT_EQ(s.force[0][0], -2.0);
    EXPECT_EQ(s.force[1][0], 0.5);
    EXPECT_EQ(s.force[2][1], 0.0);
}

TEST(HarmonicTrap, EnergyAndForceTakeTheNearestImageOfTheCentre) {
    auto s = three_particles();
    // centre (4, 0, 0): particle 1 at x = -4 is 2 from its image at -6, particle 2 at
    // y = -4.5 is 4.5 from it; per-axis stiffness 1, 2, 3
    const HarmonicTrap<3> trap(1.0, {1.0, 2.0, 3.0}, Vec<3>{{4.0, 0.0, 0.0}});
    const Vec<3> d[3] = {Vec<3>{{-3.0, 2.0, 3.0}}, Vec<3>{{2.0, 0.5, -2.0}},
                         Vec<3>{{0.5, -4.5, 0.0}}};
    const double k[3] = {1.0, 2.0, 3.0};
    double u = 0.0;
    for (const auto& di : d)
        for (int a = 0; a < 3; ++a) u += 0.5 * k[a] * di[a] * di[a];
    EXPECT_EQ(trap.log_columns(s), std::vector<std::string>{"trap_energy"});
    EXPECT_NEAR(logged(trap, s)[0], u, 1e-12 * u);
    NeighborList<3> nl(s.box, 1.0, 0.5);
    PairTotals t;
    trap.add_totals(s, nl, t);
    EXPECT_NEAR(t.energy, u, 1e-12 * u);
    for (auto& f : s.force) f = Vec<3>{};
    trap.add_forces(s, nl);
    for (int i = 0; i < 3; ++i)
        for (int a = 0; a < 3; ++a)
            EXPECT_NEAR(s.force[i][a], -k[a] * d[i][a], 1e-12) << "particle " << i << " axis " << a;
    // per species, isotropic: species B's stiffness on every axis
    const HarmonicTrap<3> by_species(PerSpecies(std::vector<double>{1.0, 3.0}), {}, Vec<3>{});
    EXPECT_EQ(by_species.stiffness(1, 2, 0), 3.0);
    EXPECT_EQ(by_species.stiffness(0, 2, 2), 1.0);
}

} // namespace
