// FIRE energy minimisation (dynamics = "minimize", soft/fire.hpp), set up as `pedesis run`
// sets it up (tests/support/fire_system.hpp):
//
//  * a harmonic bidisperse (1:1.4) disk packing at phi = 0.90, well above jamming
//    (phi_J ~ 0.84, O'Hern et al., Phys. Rev. E 68, 011306 (2003)), and a 3D one at
//    phi = 0.72 (phi_J ~ 0.64), reach the force tolerance, and the state is a local
//    minimum: the energy's gradient by central differences (the energy alone, not the
//    force code) is near zero, and 40 random displacements of size 1e-4 and 1e-3 sigma,
//    each with its opposite, all raise the energy;
//  * one particle per species in a harmonic trap under gravity ends at the analytic
//    minimum c - w/k of each species, and a particle under gravity on a harmonic wall at
//    h = sigma - w/k from the wall;
//  * long FIRE steps (dt_max 100 times a step that moves particles by more than the
//    skin) move no particle further than max_move in one step, and every step's forces
//    equal a brute-force sum over all pairs (no pair missed by the neighbour list).
#include "support/fire_system.hpp"

#include <fmt/format.h>
#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <string>

using namespace pedesis;
using test::FireSystem;

namespace {

// N/2 small (radius 0.5) and N/2 large (0.7) harmonic particles (k = 1) in a periodic
// cube (square) at packing fraction phi.
std::string bidisperse(int dimension, int n, double phi, double tolerance, int seed,
                       const std::string& extra = "", double dt = 0.1) {
    const double r1 = 0.5, r2 = 0.7;
    const double ball = dimension == 2 ? M_PI : 4.0 * M_PI / 3.0;
    const double filled = 0.5 * n * ball * (std::pow(r1, dimension) + std::pow(r2, dimension));
    const double length = std::pow(filled / phi, 1.0 / dimension);
    return fmt::format("dimension = {}\ndynamics = \"minimize\"\nseed = {}\n[box]\nlength = "
                       "{}\n[[species]]\nname = \"small\"\ncount = {}\nradius = {}\n"
                       "[[species]]\nname = \"large\"\ncount = {}\nradius = {}\n[[force]]\n"
                       "name = \"harmonic\"\nk = 1.0\n[neighbor_list]\nskin = 0.3\n"
                       "[minimize]\nforce_tolerance = {}\n{}[run]\nsteps = 1\ndt = {}\n",
                       dimension, seed, length, n / 2, r1, n - n / 2, r2, tolerance, extra, dt);
}

// FIRE steps until the force tolerance, which must come before 10^5 steps.
template <int D> void minimise_to_tolerance(FireSystem<D>& f) {
    const std::uint64_t steps = f.minimise(100000);
    ASSERT_TRUE(f.fire().forces_converged()) << "after " << steps << " steps";
}

// The largest force on a particle, computed anew from the positions.
template <int D> double fresh_max_force(FireSystem<D>& f) {
    f.evolver->compute_forces();
    double most = 0.0;
    for (const auto& F : f.state.force) most = std::max(most, norm(F));
    return most;
}

template <int D> void expect_local_minimum(FireSystem<D>& f) {
    const std::vector<Vec<D>> x0 = f.state.p.position;
    const double e0 = f.energy();
    ASSERT_GT(e0, 0.0) << "above jamming the minimum has overlaps";
    // the energy's gradient by central differences, h = 1e-6: rounding of e0 (~1e-16 e0)
    // over 2h and the O(h^2) error leave ~1e-10; the force tolerance is 1e-12
    const double h = 1e-6;
    double largest = 0.0;
    for (std::size_t i = 0; i < x0.size(); i += 7)
        for (int a = 0; a < D; ++a) {
            f.state.p.position[i][a] = x0[i][a] + h;
            const double up = f.energy();
            f.state.p.position[i][a] = x0[i][a] - h;
            const double down = f.energy();
            f.state.p.position[i][a] = x0[i][a];
            largest = std::max(largest, std::abs(up - down) / (2.0 * h));
        }
    EXPECT_LT(largest, 1e-8) << "the energy's gradient at the minimum";
    std::mt19937_64 rng(11);
    std::normal_distribution<double> normal;
    for (const double size : {1e-4, 1e-3})
        for (int trial = 0; trial < 20; ++trial) {
            std::vector<Vec<D>> d(x0.size());
            for (auto& v : d)
                for (int a = 0; a < D; ++a) v[a] = size * normal(rng);
            for (const double sign : {1.0, -1.0}) {
                for (std::size_t i = 0; i < x0.size(); ++i)
                    f.state.p.position[i] = x0[i] + sign * d[i];
                EXPECT_GT(f.energy(), e0) << "displacement " << size << ", trial " << trial;
            }
        }
    f.state.p.position = x0;
}

// N = 128 from random overlapping positions to the force tolerance 1e-12.
template <int D> void packing_ends_at_a_local_minimum(double phi, int seed) {
    FireSystem<D> f(bidisperse(D, 128, phi, 1e-12, seed));
    ASSERT_NO_FATAL_FAILURE(minimise_to_tolerance(f));
    EXPECT_LT(fresh_max_force(f), 1e-12);
    expect_local_minimum(f);
}

TEST(FireMinimisation, A2DPackingAboveJammingReachesTheToleranceAtALocalMinimum) {
    packing_ends_at_a_local_minimum<2>(0.90, 7);
}

TEST(FireMinimisation, A3DPackingAboveJammingReachesTheToleranceAtALocalMinimum) {
    packing_ends_at_a_local_minimum<3>(0.72, 8);
}

TEST(FireMinimisation, ParticlesInATrapUnderGravityEndAtTheAnalyticMinimum) {
    // a mixture: each species its stiffness and weight; the minimum is c - w / k along y
    FireSystem<2> f("dimension = 2\ndynamics = \"minimize\"\n[box]\nlength = 20.0\n"
                    "[[species]]\nname = \"A\"\ncount = 1\nmass = 3.0\npositions = \"point\"\n"
                    "position = [4.0, -3.0]\n"
                    "[[species]]\nname = \"B\"\ncount = 1\npositions = \"point\"\n"
                    "position = [-5.0, 6.0]\n"
                    "[[force]]\nname = \"harmonic_trap\"\nk = { A = 2.0, B = 0.5 }\n"
                    "centre = [1.0, 2.0]\n"
                    "[[force]]\nname = \"gravity\"\nforce = { A = 1.0, B = 0.25 }\n"
                    "[minimize]\nforce_tolerance = 1e-12\n[run]\nsteps = 1\ndt = 0.05\n");
    ASSERT_NO_FATAL_FAILURE(minimise_to_tolerance(f));
    for (std::size_t i = 0; i < 2; ++i) {
        const bool a = f.state.p.tag[i] == 0;
        const double k = a ? 2.0 : 0.5, w = a ? 1.0 : 0.25;
        // |x - x*| = |F| / k < 1e-12 / k
        EXPECT_NEAR(f.state.p.position[i][0], 1.0, 1e-11) << (a ? "A" : "B");
        EXPECT_NEAR(f.state.p.position[i][1], 2.0 - w / k, 1e-11) << (a ? "A" : "B");
    }
}

TEST(FireMinimisation, AParticleUnderGravityRestsOnAHarmonicWallWhereTheForcesBalance) {
    // the wall's push k (sigma - h) balances the weight w at h = sigma - w / k
    FireSystem<2> f("dimension = 2\ndynamics = \"minimize\"\n[box]\nlength = 10.0\n"
                    "boundary = [\"periodic\", \"wall\"]\n"
                    "[[species]]\nname = \"A\"\ncount = 1\nradius = 0.5\npositions = \"point\"\n"
                    "position = [0.0, 3.0]\n"
                    "[[force]]\nname = \"wall\"\npotential = \"harmonic\"\nk = 100.0\n"
                    "[[force]]\nname = \"gravity\"\nforce = 2.0\n"
                    "[minimize]\nforce_tolerance = 1e-12\n[run]\nsteps = 1\ndt = 0.02\n");
    ASSERT_NO_FATAL_FAILURE(minimise_to_tolerance(f));
    EXPECT_NEAR(f.state.p.position[0][1], -5.0 + 0.5 - 2.0 / 100.0, 1e-12);
    EXPECT_NEAR(f.state.p.position[0][0], 0.0, 1e-12);
}

// The harmonic forces of every pair, by brute force over the nearest images.
Vec<2> brute_force_on(const SoftState<2>& s, std::size_t i) {
    Vec<2> total{};
    const double ri = s.p.species_table[s.p.species[i]].radius;
    for (std::size_t j = 0; j < s.size(); ++j) {
        if (j == i) continue;
        const Vec<2> d = s.box.minimum_image(s.p.position[i] - s.p.position[j]);
        const double r = norm(d), a = ri + s.p.species_table[s.p.species[j]].radius;
        if (r < a) total += d * ((a - r) / r);
    }
    return total;
}

TEST(FireMinimisation, LongStepsMoveNoParticleBeyondMaxMoveNorPastTheNeighbourList) {
    // dt = 1 moves the overlapping start's particles by ~1 a step, three times the skin;
    // dt_max = 100
    FireSystem<2> f(bidisperse(2, 96, 0.88, 1e-10, 3, "dt_max = 100.0\nmax_move = 0.12\n", 1.0));
    double largest_step = 0.0, largest_error = 0.0;
    std::uint64_t steps = 0;
    for (; steps < 20000 && !f.fire().forces_converged(); ++steps) {
        const std::vector<Vec<2>> before = f.state.p.position;
        f.evolver->evolve(f.config.dt);
        for (std::size_t i = 0; i < f.state.size(); ++i) {
            const Vec<2> d = f.state.box.minimum_image(f.state.p.position[i] - before[i]);
            largest_step = std::max(largest_step, norm(d));
            largest_error =
                std::max(largest_error, norm(f.state.force[i] - brute_force_on(f.state, i)));
        }
    }
    EXPECT_TRUE(f.fire().forces_converged()) << "after " << steps << " steps";
    EXPECT_LE(largest_step, 0.12 * (1.0 + 1e-12));
    EXPECT_GT(largest_step, 0.11) << "the cap was never met: the test tests nothing";
    EXPECT_LT(largest_error, 1e-12);
    EXPECT_GT(f.evolver->list_builds(), 2u);
}

} // namespace
