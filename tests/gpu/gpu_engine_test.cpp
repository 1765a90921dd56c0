// The soft engine on the GPU against the CPU engine and against theory (label gpu: run by
// scripts/gpu_check.sh on a machine with an NVIDIA GPU; docs/gpu.md).
//
// Equal to the CPU: forces, torques, energy and virial of one configuration to 1e-12 of
// the largest force (the GPU sums each particle's full neighbour row in another order
// than the CPU's half list, and contracts products into FMAs: differences of a few ulp);
// a few hundred steps stay within 1e-9 of the CPU trajectory (the noise is the same
// Philox stream, keyed by seed, stream, tag and step). The physics: free-ABP MSD and
// swim pressure, the Langevin temperature, NVE energy conservation.
#include "cli/cli_support.hpp"
#include "support/free_abp.hpp"
#include "support/soft_builder.hpp"

#include "pedesis/gpu/gpu_stepper.hpp"
#include "pedesis/soft/brownian.hpp"
#include "pedesis/soft/evolver.hpp"
#include "pedesis/soft/langevin.hpp"
#include "pedesis/soft/pair_force.hpp"
#include "pedesis/soft/pair_potentials.hpp"
#include "pedesis/soft/polar_align.hpp"
#include "pedesis/soft/self_propulsion.hpp"
#include "pedesis/soft/velocity_verlet.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <functional>
#include <random>
#include <sstream>

using namespace pedesis;

namespace {

template <int D> using Terms = std::function<void(Evolver<D>&)>;

// The same system and terms on the CPU and on the GPU.
template <int D> struct Twins {
    SoftState<D> cpu_state, gpu_state;
    std::unique_ptr<Evolver<D>> cpu, gpu;
    Twins(const SoftState<D>& s, double skin, const Terms<D>& terms) : cpu_state(s), gpu_state(s) {
        cpu = std::make_unique<Evolver<D>>(cpu_state, skin);
        gpu = std::make_unique<Evolver<D>>(gpu_state, skin);
        terms(*cpu);
        terms(*gpu);
        gpu->set_device(make_gpu_stepper<D>(gpu_state, *gpu, {}));
    }
    void run(std::uint64_t steps, double dt) {
        cpu->run(steps, dt);
        gpu->run(steps, dt);
        gpu->sync_host();
    }
};

// Per tag, the largest difference of a per-particle vector between the twins.
template <int K, int D>
double largest_difference(const SoftState<D>& a, const std::vector<Vec<K>>& va,
                          const SoftState<D>& b, const std::vector<Vec<K>>& vb) {
    const auto ia = a.p.index_of_tags(), ib = b.p.index_of_tags();
    double most = 0.0;
    for (std::size_t t = 0; t < ia.size(); ++t) most = std::max(most, norm(va[ia[t]] - vb[ib[t]]));
    return most;
}

template <int K> double largest(const std::vector<Vec<K>>& v) {
    double most = 0.0;
    for (const auto& x : v) most = std::max(most, norm(x));
    return most;
}

template <int D> std::vector<Vec<D>> unwrapped(const SoftState<D>& s) {
    std::vector<Vec<D>> r(s.size());
    for (std::size_t i = 0; i < s.size(); ++i) r[i] = s.unwrapped(i);
    return r;
}

// Two species of radii 1 and 0.6, in alternation.
template <int D> void two_species(SoftState<D>& s) {
    s.p.species_table = {Species{"A", 1.0, 1.0}, Species{"B", 0.6, 2.0}};
    for (std::size_t i = 0; i < s.size(); ++i) s.p.species[i] = static_cast<std::uint16_t>(i % 2);
}

template <int D> void expect_forces_equal(Twins<D>& t) {
    t.cpu->compute_forces();
    t.gpu->compute_forces();
    t.gpu->sync_host();
    const double scale = largest(t.cpu_state.force);
    ASSERT_GT(scale, 0.0);
    EXPECT_LE(largest_difference(t.cpu_state, t.cpu_state.force, t.gpu_state, t.gpu_state.force),
              1e-12 * scale);
    const double torque_scale = largest(t.cpu_state.torque);
    if (torque_scale > 0.0) {
        EXPECT_LE(
            largest_difference(t.cpu_state, t.cpu_state.torque, t.gpu_state, t.gpu_state.torque),
            1e-12 * torque_scale);
    }
    const PairTotals a = t.cpu->pair_totals(), b = t.gpu->pair_totals();
    EXPECT_NEAR(b.energy, a.energy, 1e-12 * std::abs(a.energy) + 1e-300);
    EXPECT_NEAR(b.virial, a.virial, 1e-12 * std::abs(a.virial) + 1e-300);
    for (int c = 0; c < 6; ++c)
        EXPECT_NEAR(b.virial_tensor[c], a.virial_tensor[c], 1e-12 * std::abs(a.virial) + 1e-300)
            << "virial tensor slot " << c;
}

TEST(GpuForces, HarmonicTwoSpeciesActiveAligned2D) {
    auto s = test::random_soft_system<2>(3000, 70.0, 1.0, 3);
    two_species(s);
    Twins<2> t(s, 0.5, [](Evolver<2>& e) {
        e.add_force(std::make_unique<PairForce<2, HarmonicPair>>(
            "harmonic",
            std::vector<HarmonicPair>{{10.0, -1.0}, {15.0, -1.0}, {15.0, -1.0}, {20.0, -1.0}}, 2));
        e.add_force(std::make_unique<SelfPropulsion<2>>(PerSpecies(std::vector<double>{1.0, 0.5})));
        e.add_torque(std::make_unique<PolarAlign<2>>(0.7, 2.0));
    });
    expect_forces_equal(t);
}

TEST(GpuForces, WcaAligned3D) {
    auto s = test::random_soft_system<3>(4000, 20.0, 0.5, 4, 0.8);
    Twins<3> t(s, 0.4, [](Evolver<3>& e) {
        e.add_force(std::make_unique<PairForce<3, WcaPair>>("wca", WcaPair{1.0, -1.0}));
        e.add_torque(std::make_unique<PolarAlign<3>>(1.0, 1.5));
    });
    expect_forces_equal(t);
}

TEST(GpuForces, LennardJonesTwoSpecies3D) {
    auto s = test::random_soft_system<3>(3000, 16.0, 0.5, 5, 0.85);
    two_species(s);
    Twins<3> t(s, 0.3, [](Evolver<3>& e) {
        e.add_force(
            std::make_unique<PairForce<3, LjPair>>("lj",
                                                   std::vector<LjPair>{{1.0, 1.0, 2.5, false},
                                                                       {1.5, 0.8, 2.5, false},
                                                                       {1.5, 0.8, 2.5, false},
                                                                       {0.5, 0.88, 2.5, false}},
                                                   2));
    });
    expect_forces_equal(t);
}

// Positions (unwrapped), directors and velocities after `steps` on both.
template <int D> void expect_same_trajectory(Twins<D>& t, std::uint64_t steps, double dt) {
    t.run(steps, dt);
    EXPECT_EQ(t.gpu_state.step, t.cpu_state.step);
    EXPECT_LE(largest_difference(t.cpu_state, unwrapped(t.cpu_state), t.gpu_state,
                                 unwrapped(t.gpu_state)),
              1e-9);
    EXPECT_LE(
        largest_difference(t.cpu_state, t.cpu_state.director, t.gpu_state, t.gpu_state.director),
        1e-9);
    EXPECT_LE(largest_difference(t.cpu_state, t.cpu_state.p.velocity, t.gpu_state,
                                 t.gpu_state.p.velocity),
              1e-9 * std::max(1.0, largest(t.cpu_state.p.velocity)));
    EXPECT_GT(t.gpu->list_builds(), 1u) << "the run should rebuild its list on the way";
}

template <int D> void abp_terms(Evolver<D>& e) {
    e.add_force(std::make_unique<PairForce<D, HarmonicPair>>("harmonic", HarmonicPair{10.0, 2.0}));
    e.add_force(std::make_unique<SelfPropulsion<D>>(1.0));
    e.add_torque(std::make_unique<PolarAlign<D>>(1.0, 2.0));
    e.add_integrator(std::make_unique<BrownianIntegrator<D>>(0.1, 1.0, 7));
    e.add_integrator(std::make_unique<BrownianRotationIntegrator<D>>(0.1, 1.0, 8));
}

TEST(GpuTrajectory, TutorialAbp2D) {
    const double L = std::sqrt(4000 / 0.4);
    auto s = test::random_soft_system<2>(4000, L, 1.0, 9, 1.0);
    Twins<2> t(s, 1.0, abp_terms<2>);
    expect_same_trajectory(t, 300, 0.01);
}

TEST(GpuTrajectory, TutorialAbp3D) {
    const double L = std::cbrt(4000 / 0.2);
    auto s = test::random_soft_system<3>(4000, L, 1.0, 10, 1.0);
    Twins<3> t(s, 1.0, abp_terms<3>);
    expect_same_trajectory(t, 300, 0.01);
}

TEST(GpuTrajectory, LangevinWcaTwoSpecies3D) {
    auto s = test::random_soft_system<3>(3000, 18.0, 0.5, 11, 0.9);
    two_species(s);
    Twins<3> t(s, 0.4, [](Evolver<3>& e) {
        e.add_force(std::make_unique<PairForce<3, WcaPair>>("wca", WcaPair{1.0, 1.0}));
        e.add_integrator(std::make_unique<LangevinIntegrator<3>>(1.5, 1.0, 12));
    });
    expect_same_trajectory(t, 300, 0.005);
}

SoftState<3> lj_liquid(int cells, double T, std::uint64_t seed) {
    auto s = test::fcc_soft_state(cells, 0.8442);
    Vec<3> mean{};
    for (std::size_t i = 0; i < s.size(); ++i) {
        CounterRng rng(seed, RngStream::velocity, s.p.tag[i]);
        for (int a = 0; a < 3; ++a) s.p.velocity[i][a] = std::sqrt(T) * rng.normal();
        mean += s.p.velocity[i];
    }
    mean *= 1.0 / static_cast<double>(s.size());
    for (auto& v : s.p.velocity) v -= mean;
    return s;
}

TEST(GpuTrajectory, NveLennardJones3D) {
    Twins<3> t(lj_liquid(8, 1.44, 13), 0.3, [](Evolver<3>& e) {
        e.add_force(std::make_unique<PairForce<3, LjPair>>("lj", LjPair{1.0, 1.0, 2.5, false}));
        e.add_integrator(std::make_unique<VelocityVerletIntegrator<3>>());
    });
    expect_same_trajectory(t, 300, 0.005);
}

// tests/physics/abp_dynamics_test.cpp's free ABPs (MSD within 3% of theory, orientation
// correlation within 0.02), on the GPU.
template <int D> void on_gpu(SoftState<D>& s, Evolver<D>& e) {
    e.set_device(make_gpu_stepper<D>(s, e, {}));
}

TEST(GpuPhysics, FreeAbpMsd2D) {
    test::check_free_abp<2>(on_gpu<2>);
}
TEST(GpuPhysics, FreeAbpMsd3D) {
    test::check_free_abp<3>(on_gpu<3>);
}

// Swim pressure of free ABPs in 2D (Takatori, Yan & Brady 2014): sum alpha n.(dr - dR)
// / (d V) tends to n v0 alpha tau / d, tau = 1/D_r, as 1 - e^{-t/tau}. At t = 10 tau the
// remainder is 5e-5. The mean of 20000 particles has a relative standard error of about
// 1% (n.dr of one particle spreads by about 1.5 v0 tau); Euler-Maruyama's error is
// D_r dt = 1%. Tolerance 5%.
TEST(GpuPhysics, SwimPressureOfFreeAbps) {
    const std::size_t n = 20000;
    const double L = 300.0, v0 = 1.0, Dr = 1.0, dt = 0.01;
    auto s = test::random_soft_system<2>(n, L, 1.0, 21);
    Evolver<2> e(s, 2.0);
    e.add_force(std::make_unique<SelfPropulsion<2>>(v0));
    e.add_integrator(std::make_unique<BrownianIntegrator<2>>(0.1, 1.0, 22));
    e.add_integrator(std::make_unique<BrownianRotationIntegrator<2>>(Dr, 1.0, 22));
    e.set_device(make_gpu_stepper<2>(s, e, {}));
    std::vector<Vec<2>> start(n);
    for (std::size_t i = 0; i < n; ++i) start[s.p.tag[i]] = s.unwrapped(i);
    e.run(1000, dt);
    e.sync_host();
    const double measured = active_pressure(s, start, std::vector<double>{v0});
    const double theory = (n / (L * L)) * v0 * v0 / (2.0 * Dr);
    EXPECT_NEAR(measured / theory, 1.0, 0.05);
}

double kinetic_temperature(const SoftState<3>& s) {
    double twice_k = 0.0;
    for (std::size_t i = 0; i < s.size(); ++i) twice_k += s.p.mass(i) * norm2(s.p.velocity[i]);
    return twice_k / (3.0 * static_cast<double>(s.size()));
}

// BAOAB holds a WCA fluid at the bath temperature: the kinetic temperature averaged over
// 100 samples 0.5 apart (each of 4000 particles: a relative spread of sqrt(2/(3N)) = 1.3%,
// over about 25 independent samples 0.3%) within 1.5% of T = 1.5.
TEST(GpuPhysics, LangevinHoldsTheTemperature) {
    auto s = test::random_soft_system<3>(4000, 20.0, 0.5, 31, 0.9);
    Evolver<3> e(s, 0.4);
    e.add_force(std::make_unique<PairForce<3, WcaPair>>("wca", WcaPair{1.0, 1.0}));
    e.add_integrator(std::make_unique<LangevinIntegrator<3>>(1.5, 1.0, 32));
    e.set_device(make_gpu_stepper<3>(s, e, {}));
    e.run(2000, 0.005);
    double sum = 0.0;
    for (int k = 0; k < 100; ++k) {
        e.run(100, 0.005);
        e.sync_host();
        sum += kinetic_temperature(s);
    }
    EXPECT_NEAR(sum / 100.0 / 1.5, 1.0, 0.015);
}

// Velocity Verlet conserves the energy of the (shifted) LJ liquid at in.lj's state: over
// 2000 steps of dt = 0.005 the total energy per particle stays within 2e-3 of its start
// (the O(dt^2) fluctuation is about 1e-4), and it does on the CPU within the same bound.
TEST(GpuPhysics, NveConservesEnergy) {
    auto energy = [](SoftState<3>& s, Evolver<3>& e) {
        const PairTotals p = e.pair_totals();
        e.sync_host();
        return (p.energy + 1.5 * kinetic_temperature(s) * static_cast<double>(s.size())) /
               static_cast<double>(s.size());
    };
    auto s = lj_liquid(8, 1.44, 41);
    Evolver<3> e(s, 0.3);
    e.add_force(std::make_unique<PairForce<3, LjPair>>("lj", LjPair{1.0, 1.0, 2.5, true}));
    e.add_integrator(std::make_unique<VelocityVerletIntegrator<3>>());
    e.set_device(make_gpu_stepper<3>(s, e, {}));
    e.compute_forces();
    const double e0 = energy(s, e);
    double worst = 0.0;
    for (int k = 0; k < 20; ++k) {
        e.run(100, 0.005);
        worst = std::max(worst, std::abs(energy(s, e) - e0));
    }
    EXPECT_LT(worst, 2e-3) << "E0 per particle " << e0;
}

// ---- through the binary: --device gpu, checkpoints between CPU and GPU ----

class GpuCli : public test::ScratchDir {
  protected:
    // A dilute 2D ABP system (area fraction 0.2), noise on both integrators.
    std::string config(std::uint64_t steps) const {
        std::ostringstream c;
        c << "dimension = 2\ndynamics = \"brownian\"\nseed = 3\n"
             "[box]\nlength = 60.0\nboundary = \"periodic\"\n"
             "[[species]]\nname = \"A\"\ncount = 1000\nradius = 0.9\n"
             "[initial]\npositions = \"random\"\nmin_distance = 1.0\n"
             "[[force]]\nname = \"harmonic\"\nk = 10.0\n"
             "[[force]]\nname = \"self_propulsion\"\nalpha = 1.0\n"
             "[[torque]]\nname = \"polar_align\"\nJ = 0.5\na = 2.0\n"
             "[[integrator]]\nname = \"brownian\"\nT = 0.05\ngamma = 1.0\n"
             "[[integrator]]\nname = \"brownian_rotation\"\nT = 0.2\ngamma = 1.0\n"
             "[run]\nsteps = "
          << steps << "\ndt = 0.01\n[output]\nlog_every = 100\ncheckpoint_every = 200\n";
        return c.str();
    }
    // The last row of a run's log.csv, by column.
    std::map<std::string, double> last_row(const std::string& run) const {
        std::ifstream in(dir / run / "log.csv");
        std::string header, line, row;
        std::getline(in, header);
        while (std::getline(in, line))
            if (!line.empty()) row = line;
        std::map<std::string, double> out;
        std::stringstream h(header), r(row);
        std::string name, value;
        while (std::getline(h, name, ',') && std::getline(r, value, ','))
            out[name] = std::stod(value);
        return out;
    }
    void expect_close(const std::string& a, const std::string& b, double tolerance) const {
        const auto x = last_row(a), y = last_row(b);
        ASSERT_FALSE(x.empty());
        for (const char* q : {"step", "polar_order", "msd", "potential_energy", "pressure"})
            EXPECT_NEAR(y.at(q), x.at(q), tolerance * std::max(1.0, std::abs(x.at(q))))
                << q << " of " << b << " against " << a;
    }
};

TEST_F(GpuCli, RunsOnTheGpuAndSaysSo) {
    write("abp.toml", config(400));
    const auto r = test::run_pedesis("run abp.toml --device gpu --out g", dir, 120);
    ASSERT_EQ(r.exit_code, 0) << r.output;
    EXPECT_NE(r.output.find("on the GPU: "), std::string::npos) << r.output;
    EXPECT_NE(read("g/summary.json").find("\"device\": \"gpu\""), std::string::npos);
    ASSERT_EQ(test::run_pedesis("run abp.toml --out c", dir, 120).exit_code, 0);
    // 400 steps of a dilute system: the two stay together
    expect_close("c", "g", 1e-7);
}

TEST_F(GpuCli, CheckpointsMoveBetweenCpuAndGpu) {
    write("first.toml", config(200));
    write("longer.toml", config(400));
    ASSERT_EQ(test::run_pedesis("run first.toml --out cpu200", dir, 120).exit_code, 0);
    ASSERT_EQ(test::run_pedesis("run first.toml --device gpu --out gpu200", dir, 120).exit_code, 0);
    ASSERT_EQ(test::run_pedesis("run longer.toml --out cpu400", dir, 120).exit_code, 0);
    // CPU checkpoint continued on the GPU, GPU checkpoint continued on the CPU
    auto r = test::run_pedesis(
        "run longer.toml --device gpu --restart cpu200/checkpoint.bin --out cpu_then_gpu", dir,
        120);
    ASSERT_EQ(r.exit_code, 0) << r.output;
    r = test::run_pedesis("run longer.toml --restart gpu200/checkpoint.bin --out gpu_then_cpu", dir,
                          120);
    ASSERT_EQ(r.exit_code, 0) << r.output;
    r = test::run_pedesis(
        "run longer.toml --device gpu --restart gpu200/checkpoint.bin --out gpu_then_gpu", dir,
        120);
    ASSERT_EQ(r.exit_code, 0) << r.output;
    expect_close("cpu400", "cpu_then_gpu", 1e-7);
    expect_close("cpu400", "gpu_then_cpu", 1e-7);
    expect_close("cpu400", "gpu_then_gpu", 1e-7);
}

TEST_F(GpuCli, BlowUpStopsTheRunWithTheCpusMessage) {
    std::string c = config(400);
    c.replace(c.find("k = 10.0"), 8, "k = 1e6");
    write("hard.toml", c);
    const auto r = test::run_pedesis("run hard.toml --device gpu --out b", dir, 120);
    EXPECT_EQ(r.exit_code, 3) << r.output;
    EXPECT_NE(r.output.find("in one step (the neighbour-list skin)"), std::string::npos)
        << r.output;
}

} // namespace
