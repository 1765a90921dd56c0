// Pair potentials with parameters per pair of species, the shifted Lennard-Jones
// potential, and a published state point of the Lennard-Jones fluid.
//
// - Per-pair values ([[force.pairs]]) reach exactly the pairs they name: forces and
//   energy of a binary Kob-Andersen mixture equal an O(N^2) sum over every pair with the
//   mixture's own table (exact up to summation order: 1e-10 relative), and changing
//   epsilon_AB changes the energy by exactly the cross pairs' share.
// - Mixing rules for pairs not given: geometric for epsilon, geometric or arithmetic for
//   sigma, as LAMMPS' pair_modify mix.
// - With shift the energy goes to 0 at the cutoff (continuous) and the force is unchanged.
// - NIST's Standard Reference Simulation Website (Lennard-Jones fluid, NVT Monte Carlo,
//   mmlapps.nist.gov/srs/LJ_PURE/mc.htm: N = 500, cutoff 3 sigma with the analytic
//   long-range correction) gives U/N = -5.5121 +- 0.0004 at T = 0.85, rho = 0.776.
#include "pedesis/core/rng.hpp"
#include "support/soft_builder.hpp"

#include "pedesis/soft/evolver.hpp"
#include "pedesis/soft/langevin.hpp"
#include "pedesis/soft/pair_force.hpp"
#include "pedesis/soft/pair_potentials.hpp"
#include "pedesis/soft/plugin_registry.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <memory>
#include <numbers>

using namespace pedesis;

namespace {

PluginParam one(double v) {
    PluginParam p;
    p.uniform = v;
    p.where = "test";
    return p;
}

// Kob-Andersen: A-A (1, 1), A-B (epsilon_ab, 0.8), B-B (0.5, 0.88), cut at 2.5 sigma_ab,
// shifted.
PluginSpec kob_andersen(double epsilon_ab) {
    return make_plugin_spec(PluginKind::force, "lj",
                            {{"epsilon", one(1.0)}, {"sigma", one(1.0)}, {"cutoff", one(2.5)}},
                            "test", {{"shift", true}},
                            {PairValues{"A", "B", {{"epsilon", epsilon_ab}, {"sigma", 0.8}}, "t"},
                             PairValues{"B", "B", {{"epsilon", 0.5}, {"sigma", 0.88}}, "t"}});
}

// 6^3 cells of a jittered simple cubic lattice, 80% A and 20% B, at density 1.2 (the
// mixture's usual one). The jitter keeps every pair well apart (no overflow), and leaves
// pairs at all distances up to the cutoffs.
SoftState<3> binary_mixture() {
    const int cells = 6;
    const double a = std::cbrt(1.0 / 1.2), L = cells * a;
    SoftState<3> s;
    s.box = Box<3>(Vec<3>::filled(L), std::array<bool, 3>{true, true, true});
    s.resize(cells * cells * cells);
    s.p.species_table = {Species{"A", 0.5, 1.0}, Species{"B", 0.44, 1.0}};
    std::size_t i = 0;
    for (int x = 0; x < cells; ++x)
        for (int y = 0; y < cells; ++y)
            for (int z = 0; z < cells; ++z, ++i) {
                CounterRng rng(7, RngStream::placement, static_cast<std::uint32_t>(i));
                const int k[3] = {x, y, z};
                for (int d = 0; d < 3; ++d)
                    s.p.position[i][d] = (k[d] + 0.5 + rng.uniform(-0.15, 0.15)) * a - 0.5 * L;
                s.p.tag[i] = static_cast<std::uint32_t>(i);
                s.p.species[i] = static_cast<std::uint16_t>(rng.uniform(0.0, 1.0) < 0.2);
                s.director[i] = Vec<3>{{1.0, 0.0, 0.0}};
            }
    return s;
}

struct BruteForce {
    std::vector<Vec<3>> force;
    double energy = 0.0, energy_ab = 0.0;
};

// Every pair of the mixture with the table written out here, not taken from the code.
BruteForce brute_force(const SoftState<3>& s, double epsilon_ab) {
    const double eps[2][2] = {{1.0, epsilon_ab}, {epsilon_ab, 0.5}};
    const double sig[2][2] = {{1.0, 0.8}, {0.8, 0.88}};
    BruteForce b;
    b.force.assign(s.size(), Vec<3>{});
    for (std::size_t i = 0; i < s.size(); ++i)
        for (std::size_t j = i + 1; j < s.size(); ++j) {
            const int si = s.p.species[i], sj = s.p.species[j];
            const Vec<3> d = s.box.minimum_image(s.p.position[i] - s.p.position[j]);
            const double r = norm(d), rc = 2.5 * sig[si][sj];
            if (r >= rc) continue;
            const double x6 = std::pow(sig[si][sj] / r, 6), c6 = std::pow(sig[si][sj] / rc, 6);
            const double u = 4.0 * eps[si][sj] * ((x6 * x6 - x6) - (c6 * c6 - c6));
            const double f_over_r = 24.0 * eps[si][sj] * (2.0 * x6 * x6 - x6) / (r * r);
            b.force[i] += f_over_r * d;
            b.force[j] -= f_over_r * d;
            b.energy += u;
            if (si != sj) b.energy_ab += u;
        }
    return b;
}

} // namespace

TEST(PairParameters, KobAndersenMixtureEqualsTheSumOverEveryPair) {
    SoftState<3> s = binary_mixture();
    Evolver<3> e(s, 0.3);
    add_plugin(e, kob_andersen(1.5), s.p.species_table, 1);
    const BruteForce b = brute_force(s, 1.5);
    const PairTotals totals = e.pair_totals();
    EXPECT_NEAR(totals.energy / b.energy, 1.0, 1e-10);
    std::fill(s.force.begin(), s.force.end(), Vec<3>{});
    e.forces()[0]->add_forces(s, e.neighbor_list());
    double scale = 0.0;
    for (const auto& f : b.force) scale = std::max(scale, norm(f));
    for (std::size_t i = 0; i < s.size(); ++i)
        EXPECT_LT(norm(s.force[i] - b.force[i]), 1e-10 * scale) << "particle " << i;
}

TEST(PairParameters, EpsilonAbChangesOnlyTheCrossPairs) {
    SoftState<3> s = binary_mixture();
    Evolver<3> e1(s, 0.3), e2(s, 0.3);
    add_plugin(e1, kob_andersen(1.5), s.p.species_table, 1);
    add_plugin(e2, kob_andersen(2.0), s.p.species_table, 1);
    const double cross = brute_force(s, 1.5).energy_ab;
    ASSERT_GT(std::abs(cross), 1.0); // the test is not vacuous: there are A-B pairs
    // the energy is linear in epsilon_AB, so 1.5 -> 2.0 adds a third of the cross part
    EXPECT_NEAR(e2.pair_totals().energy - e1.pair_totals().energy, cross / 3.0,
                1e-10 * std::abs(cross));
}

TEST(PairParameters, MixingRulesForPairsNotGiven) {
    std::vector<Species> table = {Species{"A", 0.5, 1.0}, Species{"B", 0.5, 1.0}};
    for (const char* rule : {"geometric", "arithmetic"}) {
        PluginParam eps, sig;
        eps.by_species = {{"A", 1.0}, {"B", 0.25}};
        sig.by_species = {{"A", 1.0}, {"B", 0.8}};
        eps.where = sig.where = "test";
        const PluginSpec spec = make_plugin_spec(
            PluginKind::force, "lj", {{"epsilon", eps}, {"sigma", sig}}, "test", {}, {}, rule);
        SoftState<3> s = binary_mixture();
        Evolver<3> e(s, 0.3);
        add_plugin(e, spec, table, 1);
        const auto& f = dynamic_cast<const PairForce<3, LjPair>&>(*e.forces()[0]);
        EXPECT_DOUBLE_EQ(f.pair(0, 1).epsilon, 0.5) << rule;
        EXPECT_DOUBLE_EQ(f.pair(1, 0).epsilon, 0.5) << rule;
        EXPECT_DOUBLE_EQ(f.pair(1, 1).sigma, 0.8) << rule;
        EXPECT_DOUBLE_EQ(f.pair(0, 1).sigma,
                         std::string(rule) == "geometric" ? std::sqrt(0.8) : 0.9)
            << rule;
    }
}

TEST(PairParameters, BadPairEntriesAreRefused) {
    const auto with_pairs = [](std::vector<PairValues> pairs, const std::string& mixing) {
        return make_plugin_spec(PluginKind::force, "lj", {{"epsilon", one(1.0)}}, "test", {},
                                std::move(pairs), mixing);
    };
    EXPECT_THROW(with_pairs({}, "lorentz"), InputError);
    EXPECT_THROW(with_pairs({PairValues{"A", "B", {}, "t"}}, "geometric"), InputError);
    EXPECT_THROW(with_pairs({PairValues{"A", "B", {{"k", 1.0}}, "t"}}, "geometric"), InputError);
    EXPECT_THROW(with_pairs({PairValues{"A", "B", {{"sigma", -1.0}}, "t"}}, "geometric"),
                 InputError);
    EXPECT_THROW(with_pairs({PairValues{"A", "B", {{"sigma", 1.0}}, "t"},
                             PairValues{"B", "A", {{"sigma", 1.0}}, "u"}},
                            "geometric"),
                 InputError);
    // a pair naming a species the system does not have
    SoftState<3> s = binary_mixture();
    Evolver<3> e(s, 0.3);
    EXPECT_THROW(add_plugin(e,
                            with_pairs({PairValues{"A", "C", {{"sigma", 1.0}}, "t"}}, "geometric"),
                            s.p.species_table, 1),
                 InputError);
    // a potential that is not a pair potential takes no pairs
    EXPECT_THROW(make_plugin_spec(PluginKind::force, "self_propulsion", {{"alpha", one(1.0)}},
                                  "test", {}, {PairValues{"A", "B", {{"alpha", 1.0}}, "t"}}),
                 InputError);
}

TEST(PairParameters, ShiftMakesTheEnergyContinuousAtTheCutoff) {
    const LjPair plain{1.5, 0.9, 2.5, false}, shifted{1.5, 0.9, 2.5, true};
    const double rc = 2.5 * 0.9;
    double f1, u1, f2, u2;
    ASSERT_TRUE(plain.eval(rc * rc * (1.0 - 1e-12), -1.0, f1, u1));
    ASSERT_TRUE(shifted.eval(rc * rc * (1.0 - 1e-12), -1.0, f2, u2));
    EXPECT_EQ(f1, f2);
    // U(r_c) = 4 eps (2.5^-12 - 2.5^-6) = -0.0245 eps: the jump the shift removes
    EXPECT_NEAR(u1, 4.0 * 1.5 * (std::pow(2.5, -12) - std::pow(2.5, -6)), 1e-12);
    EXPECT_NEAR(u2, 0.0, 1e-12);
    ASSERT_TRUE(plain.eval(1.0, -1.0, f1, u1));
    ASSERT_TRUE(shifted.eval(1.0, -1.0, f2, u2));
    EXPECT_NEAR(u1 - u2, 4.0 * 1.5 * (std::pow(2.5, -12) - std::pow(2.5, -6)), 1e-15);
}

// NVT (Langevin, T = 0.85, gamma = 1) from an fcc lattice at rho = 0.776, N = 500, the
// potential cut (not shifted) at 3 sigma; the mean potential energy per particle plus the
// analytic tail (8/3) pi rho (rc^-9 / 3 - rc^-3) against NIST's -5.5121. 2000 steps of
// dt = 0.005 melt the lattice and equilibrate (the energy settles within ~300); 6000 more
// are sampled every 20. Samples are correlated over ~0.5 time units, so the ~60
// independent ones give a standard error near 0.003 (0.05%); BAOAB's configurational
// bias at this dt is of order 1e-4. A tolerance of 0.5% is ten standard errors, and a
// wrong potential, cutoff, tail or temperature moves U/N by several per cent.
TEST(LennardJonesFluid, NistStatePointEnergy) {
    const double rho = 0.776, T = 0.85, rc = 3.0;
    SoftState<3> s = test::fcc_soft_state(5, rho);
    Evolver<3> e(s, 0.3);
    e.add_force(std::make_unique<PairForce<3, LjPair>>("lj", LjPair{1.0, 1.0, rc}));
    e.add_integrator(std::make_unique<LangevinIntegrator<3>>(PerSpecies(T), PerSpecies(1.0), 11));
    const double dt = 0.005;
    for (int k = 0; k < 2000; ++k) e.evolve(dt);
    double sum = 0.0;
    int samples = 0;
    for (int k = 1; k <= 6000; ++k) {
        e.evolve(dt);
        if (k % 20 == 0) {
            sum += e.pair_totals().energy / static_cast<double>(s.size());
            ++samples;
        }
    }
    const double tail =
        8.0 / 3.0 * std::numbers::pi * rho * (std::pow(rc, -9) / 3.0 - std::pow(rc, -3));
    const double u = sum / samples + tail;
    EXPECT_NEAR(u / -5.5121, 1.0, 0.005) << "U/N = " << u;
    std::printf("U/N = %.5f (NIST -5.5121)\n", u);
}
