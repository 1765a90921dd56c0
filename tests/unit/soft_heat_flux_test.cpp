// The soft engine's heat flux ([transport]'s thermal conductivity), against its defining
// identity: for particles that do not cross the box, the Helfand moment M = Σ_i r_i e_i
// (e_i = m v_i²/2 + half of each pair energy, computed here by brute force) changes by
// exactly ∫ J dt, J = Σ_i v_i e_i + (1/2) Σ_pairs r_ij (F_ij . (v_i + v_j)). A WCA
// cluster flying apart under velocity Verlet; the trapezoid over the steps and the
// integrator's error are O(dt^2) (in 3D: 0.05 of |dM| = 440 at dt = 2e-4, 0.004 at 5e-5;
// the bound below is 0.044 at dt = 1e-4). A system with a field has no pair heat flux.
#include "support/soft_builder.hpp"

#include "pedesis/soft/evolver.hpp"
#include "pedesis/soft/external_fields.hpp"
#include "pedesis/soft/pair_force.hpp"
#include "pedesis/soft/pair_potentials.hpp"
#include "pedesis/soft/velocity_verlet.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <memory>
#include <random>
#include <vector>

using namespace pedesis;

namespace {

// Σ_i r_i e_i with the WCA pair energies (sigma 1, epsilon 1) split half and half.
template <int D> Vec<D> helfand_heat_moment(const SoftState<D>& s) {
    std::vector<double> e(s.size(), 0.0);
    for (std::size_t i = 0; i < s.size(); ++i) {
        e[i] += 0.5 * norm2(s.p.velocity[i]);
        for (std::size_t j = i + 1; j < s.size(); ++j) {
            const double r2 = norm2(s.p.position[i] - s.p.position[j]);
            if (r2 >= std::pow(2.0, 1.0 / 3.0)) continue;
            const double x6 = 1.0 / (r2 * r2 * r2);
            const double u = 4.0 * (x6 * x6 - x6) + 1.0;
            e[i] += 0.5 * u;
            e[j] += 0.5 * u;
        }
    }
    Vec<D> m{};
    for (std::size_t i = 0; i < s.size(); ++i) m += s.p.position[i] * e[i];
    return m;
}

template <int D> void expect_moment_follows_flux() {
    // 4^D particles 1.05 apart (compressed: the cluster's pair energy drives the flux)
    // near the middle of a box too large for any to cross it in the run
    SoftState<D> s = test::random_soft_system<D>(D == 2 ? 16 : 64, 60.0, 0.5, 3);
    std::mt19937_64 rng(5);
    std::normal_distribution<double> gauss;
    for (std::size_t i = 0; i < s.size(); ++i) {
        std::size_t rest = i;
        for (int a = 0; a < D; ++a) {
            s.p.position[i][a] = 1.05 * static_cast<double>(rest % 4) + 0.1 * gauss(rng);
            rest /= 4;
            s.p.velocity[i][a] = gauss(rng);
        }
    }
    Evolver<D> e(s, 0.3);
    e.add_force(std::make_unique<PairForce<D, WcaPair>>("wca", WcaPair{1.0, 1.0}));
    e.add_integrator(std::make_unique<VelocityVerletIntegrator<D>>());
    std::vector<double> scratch;
    Vec<D> flux{}, next{};
    const double dt = 1e-4;
    const int steps = 10000;
    ASSERT_TRUE(e.heat_flux(scratch, flux));
    const Vec<D> m0 = helfand_heat_moment(s);
    Vec<D> integral{};
    double pair_part = 0.0; // how much of J the pairs carry (the test must exercise them)
    for (int k = 0; k < steps; ++k) {
        e.evolve(dt);
        ASSERT_TRUE(e.heat_flux(scratch, next));
        integral += (flux + next) * (0.5 * dt);
        Vec<D> kinetic{};
        for (std::size_t i = 0; i < s.size(); ++i)
            kinetic += s.p.velocity[i] * (0.5 * norm2(s.p.velocity[i]) + scratch[i]);
        pair_part = std::max(pair_part, norm(next - kinetic));
        flux = next;
    }
    // the same pass gives pair_totals' virial tensor, bit for bit
    SymTensor virial{};
    ASSERT_TRUE(e.heat_flux(scratch, next, &virial));
    const SymTensor totals = e.pair_totals().virial_tensor;
    for (int c = 0; c < 6; ++c) EXPECT_EQ(virial[c], totals[c]) << c;
    const Vec<D> change = helfand_heat_moment(s) - m0;
    EXPECT_GT(norm(change), 1.0);
    EXPECT_GT(pair_part, 1.0);
    for (int a = 0; a < D; ++a) EXPECT_NEAR(integral[a], change[a], 1e-4 * norm(change)) << a;
}

TEST(SoftHeatFlux, TheHelfandMomentChangesByTheIntegralOfTheFlux2D) {
    expect_moment_follows_flux<2>();
}

TEST(SoftHeatFlux, TheHelfandMomentChangesByTheIntegralOfTheFlux3D) {
    expect_moment_follows_flux<3>();
}

TEST(SoftHeatFlux, AFieldHasNoPairHeatFlux) {
    SoftState<2> s = test::random_soft_system<2>(10, 20.0, 0.5, 1, 1.0);
    Evolver<2> e(s, 0.3);
    e.add_force(std::make_unique<PairForce<2, WcaPair>>("wca", WcaPair{1.0, 1.0}));
    e.add_force(
        std::make_unique<HarmonicTrap<2>>(PerSpecies(1.0), std::vector<double>{}, Vec<2>{}));
    std::vector<double> scratch;
    Vec<2> flux{};
    EXPECT_FALSE(e.heat_flux(scratch, flux));
}

} // namespace
