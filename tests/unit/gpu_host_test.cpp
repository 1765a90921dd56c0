// The host side of the GPU path, on any machine: the device model read from the
// plug-ins, the per-species coefficients (the CPU integrators' own tables), and the
// refusals of what the GPU does not run.
#include "support/soft_builder.hpp"

#include "pedesis/core/error.hpp"
#include "pedesis/gpu/gpu_stepper.hpp"
#include "pedesis/soft/brownian.hpp"
#include "pedesis/soft/langevin.hpp"
#include "pedesis/soft/pair_force.hpp"
#include "pedesis/soft/plugin_registry.hpp"
#include "pedesis/soft/polar_align.hpp"
#include "pedesis/soft/self_propulsion.hpp"
#include "pedesis/soft/velocity_verlet.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>

using namespace pedesis;

namespace {

template <int D> void add_abp(Evolver<D>& e) {
    e.add_force(std::make_unique<PairForce<D, HarmonicPair>>("harmonic", HarmonicPair{10.0, 2.0}));
    e.add_force(std::make_unique<SelfPropulsion<D>>(PerSpecies(std::vector<double>{1.0, 0.25})));
    e.add_torque(std::make_unique<PolarAlign<D>>(0.5, 1.5));
    e.add_integrator(std::make_unique<BrownianIntegrator<D>>(
        PerSpecies(std::vector<double>{0.1, 0.2}), PerSpecies(std::vector<double>{1.0, 4.0}), 7));
    e.add_integrator(std::make_unique<BrownianRotationIntegrator<D>>(0.3, 2.0, 8));
}

template <int D> SoftState<D> two_species(std::size_t n, double L) {
    auto s = test::random_soft_system<D>(n, L, 1.0, 1);
    s.p.species_table = {Species{"A", 1.0, 1.0}, Species{"B", 0.5, 2.0}};
    for (std::size_t i = 0; i < n; ++i) s.p.species[i] = static_cast<std::uint16_t>(i % 2);
    return s;
}

TEST(GpuModel, ReadsTheTutorialsTerms) {
    auto s = two_species<2>(50, 30.0);
    Evolver<2> e(s, 0.5);
    add_abp(e);
    const gpu::Model m = gpu_model(s, e);
    EXPECT_EQ(m.dim, 2);
    EXPECT_EQ(m.particles, 50u);
    EXPECT_EQ(m.species, 2u);
    EXPECT_EQ(m.pair, gpu::PairKind::harmonic);
    ASSERT_EQ(m.harmonic.size(), 4u);
    EXPECT_EQ(m.harmonic[3], (HarmonicPair{10.0, 2.0}));
    EXPECT_TRUE(m.propulsion);
    EXPECT_TRUE(m.align);
    EXPECT_EQ(m.align_range, 1.5);
    EXPECT_EQ(m.mover, gpu::Mover::brownian);
    EXPECT_TRUE(m.rotation);
    EXPECT_EQ(m.seed, 7u);
    EXPECT_EQ(m.rotation_seed, 8u);
    EXPECT_EQ(m.r_cut, 2.0); // the harmonic range a, above the alignment's 1.5
    EXPECT_EQ(m.skin, 0.5);
    EXPECT_EQ(m.box[0], 30.0);
    EXPECT_EQ(m.box[1], 30.0);
    EXPECT_EQ(m.radius, (std::vector<double>{1.0, 0.5}));
}

TEST(GpuModel, CoefficientsAreTheCpuIntegratorsTables) {
    auto s = two_species<2>(10, 30.0);
    Evolver<2> e(s, 0.5);
    add_abp(e);
    const double dt = 0.01;
    const gpu::StepCoefficients c = gpu_coefficients(s, e, dt, 0.5);
    ASSERT_EQ(c.species.size(), 2u);
    EXPECT_EQ(c.species[0].alpha, 1.0);
    EXPECT_EQ(c.species[1].alpha, 0.25);
    EXPECT_EQ(c.J, 0.5);
    EXPECT_DOUBLE_EQ(c.species[1].drift, dt / 4.0);
    EXPECT_DOUBLE_EQ(c.species[1].kick, std::sqrt(2.0 * 0.2 * dt / 4.0));
    EXPECT_DOUBLE_EQ(c.species[0].rot_drift, dt / 2.0);
    EXPECT_DOUBLE_EQ(c.species[0].rot_kick, std::sqrt(2.0 * 0.3 * dt / 2.0));
    EXPECT_TRUE(c.noisy);
    EXPECT_TRUE(c.rot_noisy);
    EXPECT_EQ(c.max_move, 0.5);
}

TEST(GpuModel, InertialCoefficients) {
    auto s = two_species<3>(10, 30.0);
    s.p.species_table[1].mass = std::numeric_limits<double>::infinity(); // an obstacle
    const double dt = 0.005;
    {
        Evolver<3> e(s, 0.3);
        e.add_force(std::make_unique<PairForce<3, LjPair>>("lj", LjPair{}));
        e.add_integrator(std::make_unique<LangevinIntegrator<3>>(2.0, 0.5, 3));
        const gpu::StepCoefficients c = gpu_coefficients(s, e, dt, 0.3);
        EXPECT_DOUBLE_EQ(c.species[0].half_kick, 0.5 * dt);
        EXPECT_DOUBLE_EQ(c.species[0].half_drift, 0.5 * dt);
        EXPECT_DOUBLE_EQ(c.species[0].damp, std::exp(-0.5 * dt));
        const double noise = std::sqrt((1.0 - std::exp(-dt)) * 2.0); // 1 - c1^2, T / m
        EXPECT_NEAR(c.species[0].noise, noise, 1e-12 * noise);
        EXPECT_EQ(c.species[1].half_drift, 0.0);
        EXPECT_EQ(gpu_model(s, e).mover, gpu::Mover::langevin);
    }
    {
        Evolver<3> e(s, 0.3);
        e.add_force(std::make_unique<PairForce<3, LjPair>>("lj", LjPair{}));
        e.add_integrator(std::make_unique<VelocityVerletIntegrator<3>>());
        const gpu::StepCoefficients c = gpu_coefficients(s, e, dt, 0.3);
        EXPECT_DOUBLE_EQ(c.species[0].half_kick, 0.5 * dt);
        EXPECT_EQ(c.species[0].half_drift, dt);
        EXPECT_EQ(c.species[1].half_drift, 0.0);
        EXPECT_EQ(c.species[1].half_kick, 0.0);
        EXPECT_FALSE(c.noisy);
        EXPECT_EQ(gpu_model(s, e).mover, gpu::Mover::nve);
        EXPECT_EQ(gpu_model(s, e).pair, gpu::PairKind::lj);
    }
}

TEST(GpuModel, RefusesABoxShorterThanTwiceTheListRange) {
    // harmonic range 2 + skin 0.5: the box must be longer than 5 on every axis
    auto s = test::random_soft_system<2>(4, 5.0, 1.0, 1);
    Evolver<2> e(s, 0.5);
    add_abp(e);
    try {
        gpu_model(s, e);
        FAIL() << "a 5 x 5 box was accepted";
    } catch (const InputError& err) {
        EXPECT_NE(std::string(err.what()).find("twice the list's range"), std::string::npos)
            << err.what();
    }
    auto wider = test::random_soft_system<2>(4, 5.01, 1.0, 1);
    Evolver<2> f(wider, 0.5);
    add_abp(f);
    EXPECT_NO_THROW(gpu_model(wider, f));
}

TEST(GpuModel, RefusesTwoPairForcesAndTwoAligners) {
    auto s = test::random_soft_system<2>(4, 30.0, 1.0, 1);
    Evolver<2> e(s, 0.5);
    e.add_force(std::make_unique<PairForce<2, HarmonicPair>>("harmonic", HarmonicPair{}));
    e.add_force(std::make_unique<PairForce<2, WcaPair>>("wca", WcaPair{}));
    EXPECT_THROW(gpu_model(s, e), InputError);
    Evolver<2> f(s, 0.5);
    f.add_torque(std::make_unique<PolarAlign<2>>(1.0, 1.0));
    f.add_torque(std::make_unique<PolarAlign<2>>(1.0, 2.0));
    EXPECT_THROW(gpu_model(s, f), InputError);
}

// The device kernels draw Gaussian noise: a config with uniform_noise is refused, by name.
TEST(GpuModel, RefusesUniformNoise) {
    auto s = test::random_soft_system<2>(4, 30.0, 1.0, 1);
    for (bool langevin : {false, true}) {
        Evolver<2> e(s, 0.5);
        if (langevin)
            e.add_integrator(
                std::make_unique<LangevinIntegrator<2>>(1.0, 1.0, 1, detail::NoiseShape::uniform));
        else
            e.add_integrator(
                std::make_unique<BrownianIntegrator<2>>(1.0, 1.0, 1, detail::NoiseShape::uniform));
        try {
            gpu_model(s, e);
            FAIL() << "uniform noise was accepted";
        } catch (const InputError& err) {
            EXPECT_NE(std::string(err.what()).find("uniform_noise"), std::string::npos)
                << err.what();
        }
        Evolver<2> f(s, 0.5);
        f.add_integrator(std::make_unique<BrownianIntegrator<2>>(1.0, 1.0, 1));
        EXPECT_NO_THROW(gpu_model(s, f));
    }
}

// Without a GPU (or without CUDA in the build) asking for one is an input error that says
// why; with one, the stepper is made.
TEST(GpuStepper, SaysWhyNoGpuCanRun) {
    auto s = test::random_soft_system<2>(20, 30.0, 1.0, 1);
    Evolver<2> e(s, 0.5);
    add_abp(e);
    const std::string why = gpu_unavailable_reason();
    if (why.empty()) {
        EXPECT_NE(make_gpu_stepper<2>(s, e, {}), nullptr);
        return;
    }
    try {
        make_gpu_stepper<2>(s, e, {});
        FAIL() << "a GPU stepper was made where none can run: " << why;
    } catch (const InputError& err) {
        EXPECT_NE(std::string(err.what()).find(why), std::string::npos) << err.what();
    }
}

} // namespace

namespace {

// The terms of issue 50 (walls, fields, the active models beyond ABPs) have no device
// kernels: each is refused by name, built as a config builds it; a walled box too.
TEST(GpuModel, RefusesTheTermsItHasNoKernelsFor) {
    const auto number = [](double v) {
        PluginParam p;
        p.uniform = v;
        p.where = "test";
        return p;
    };
    struct Case {
        PluginKind kind;
        const char* name;
        std::map<std::string, PluginParam> params;
        std::map<std::string, std::string> choices;
    };
    const std::vector<Case> cases = {
        {PluginKind::force,
         "wall",
         {{"radius", number(12.0)}, {"k", number(1.0)}},
         {{"shape", "sphere"}, {"potential", "harmonic"}}},
        {PluginKind::force, "gravity", {{"force", number(0.1)}}, {}},
        {PluginKind::force, "harmonic_trap", {{"k", number(0.1)}}, {}},
        {PluginKind::force, "active_ou", {{"tau", number(1.0)}, {"D_a", number(1.0)}}, {}},
        {PluginKind::torque, "active_torque", {{"torque", number(1.0)}}, {}},
        {PluginKind::torque, "nematic_align", {{"J", number(1.0)}, {"a", number(1.0)}}, {}},
        {PluginKind::torque, "velocity_align", {{"J", number(1.0)}, {"a", number(1.0)}}, {}},
        {PluginKind::integrator, "run_and_tumble", {{"rate", number(1.0)}}, {}},
    };
    for (const Case& c : cases) {
        auto s = test::random_soft_system<2>(4, 30.0, 0.5, 1);
        Evolver<2> e(s, 0.5);
        e.add_integrator(std::make_unique<BrownianIntegrator<2>>(0.1, 1.0, 1));
        add_plugin(
            e, make_plugin_spec(c.kind, c.name, c.params, "test", {}, {}, "geometric", c.choices),
            s.p.species_table, 1);
        try {
            gpu_model(s, e);
            ADD_FAILURE() << c.name << " was accepted";
        } catch (const InputError& err) {
            EXPECT_NE(std::string(err.what()).find(std::string("'") + c.name + "'"),
                      std::string::npos)
                << err.what();
        }
    }
    auto walled = test::random_soft_system<2>(4, 30.0, 0.5, 1);
    walled.box = Box<2>(Vec<2>{{30.0, 30.0}}, {false, true});
    Evolver<2> e(walled, 0.5);
    e.add_integrator(std::make_unique<BrownianIntegrator<2>>(0.1, 1.0, 1));
    try {
        gpu_model(walled, e);
        ADD_FAILURE() << "a walled box was accepted";
    } catch (const InputError& err) {
        EXPECT_NE(std::string(err.what()).find("periodic boxes only"), std::string::npos)
            << err.what();
    }
}

} // namespace
