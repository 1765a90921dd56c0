// The kinetic degrees of freedom (observe/thermo.hpp) for every engine and boundary:
// d (N - 1) when every axis is periodic and the dynamics conserves momentum, one fewer
// than d N per periodic axis with walls on the others, d N with walls everywhere, a
// fixed obstacle, a thermostat or self-propulsion; the temperature in the
// centre-of-mass frame; species sharing the conserved components by mass; and
// Maxwell-Boltzmann starts scaled to the requested temperature under that rule. The
// expected numbers are computed here by hand from the definitions in docs/engines.md.
#include "pedesis/observe/pressure.hpp"
#include "pedesis/observe/thermo.hpp"
#include "pedesis/setup/build_system.hpp"
#include "pedesis/setup/run_config.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <string>

using namespace pedesis;

namespace {

// Two species (masses 1 and 3), velocities that are not momentum-free, and optionally a
// fixed obstacle.
template <int D> ParticleStore<D> mixture(std::size_t n, bool obstacle = false) {
    ParticleStore<D> p;
    p.species_table = {Species{"a", 0.5, 1.0}, Species{"b", 0.5, 3.0},
                       Species{"rock", 1.0, INFINITY}};
    p.resize(n);
    for (std::size_t i = 0; i < n; ++i) {
        p.tag[i] = static_cast<std::uint32_t>(i);
        p.species[i] = static_cast<std::uint16_t>(i % 3 == 0 ? 1 : 0);
        for (int a = 0; a < D; ++a)
            p.velocity[i][a] = std::sin(1.7 * static_cast<double>(i) + a) + 0.3 * (a + 1);
    }
    if (obstacle) {
        p.species[n - 1] = 2;
        p.velocity[n - 1] = Vec<D>{};
    }
    return p;
}

template <int D> Box<D> box_with(std::array<bool, D> periodic) {
    return Box<D>(Vec<D>::filled(10.0), periodic);
}

template <int D> Box<D> periodic_box() {
    std::array<bool, D> periodic;
    periodic.fill(true);
    return box_with<D>(periodic);
}

// Twice the kinetic energy, and the mass, of species s (all mobile species when s < 0).
template <int D> std::pair<double, double> twice_kinetic(const ParticleStore<D>& p, int s) {
    double e = 0.0, m = 0.0;
    for (std::size_t i = 0; i < p.size(); ++i) {
        if (std::isinf(p.mass(i)) || (s >= 0 && p.species[i] != s)) continue;
        e += p.mass(i) * norm2(p.velocity[i]);
        m += p.mass(i);
    }
    return {e, m};
}

template <int D> void fully_periodic_case() {
    auto p = mixture<D>(12);
    const auto box = periodic_box<D>();
    const auto k = measure_kinetics(p, box, Momentum::conserving);
    EXPECT_EQ(k.conserved_components, D);
    EXPECT_DOUBLE_EQ(k.total_freedom, D * 12.0 - D);

    // temperature in the centre-of-mass frame: 2 (K - P^2 / 2M) / (d (N - 1))
    Vec<D> P{};
    double M = 0.0;
    for (std::size_t i = 0; i < p.size(); ++i) {
        P += p.mass(i) * p.velocity[i];
        M += p.mass(i);
    }
    ASSERT_GT(norm(P), 1.0); // the case has a drift to remove
    const double twice_K = twice_kinetic(p, -1).first;
    EXPECT_NEAR(k.temperature(), (twice_K - norm2(P) / M) / (D * 11.0), 1e-12);
    EXPECT_NEAR(2.0 * k.total_kinetic, twice_K, 1e-12); // lab-frame energy unchanged

    // species: f_s = d N_s - d M_s / M, adding up to f
    double sum_f = 0.0;
    for (int s = 0; s < 2; ++s) {
        const double n_s = static_cast<double>(k.mobile[s]);
        const double m_s = twice_kinetic(p, s).second;
        EXPECT_NEAR(k.freedom[s], D * n_s - D * m_s / M, 1e-12);
        sum_f += k.freedom[s];
    }
    EXPECT_NEAR(sum_f, k.total_freedom, 1e-12);

    // Galilean invariance: a common drift changes neither T nor any T_s
    const double T = k.temperature(), T0 = k.temperature(0), T1 = k.temperature(1);
    for (auto& v : p.velocity) v += Vec<D>::filled(5.0);
    const auto moved = measure_kinetics(p, box, Momentum::conserving);
    EXPECT_NEAR(moved.temperature(), T, 1e-12 * T);
    EXPECT_NEAR(moved.temperature(0), T0, 1e-12 * T0);
    EXPECT_NEAR(moved.temperature(1), T1, 1e-12 * T1);
}

// Walls everywhere, a thermostat or a fixed obstacle: T = 2 K / (d N_mobile) bit for
// bit, as before the rule existed.
template <int D> void nothing_conserved_case() {
    const auto p = mixture<D>(10);
    const auto walled = box_with<D>(std::array<bool, D>{});
    const auto periodic = periodic_box<D>();
    const auto with_rock = mixture<D>(11, true);
    for (const auto& k : {measure_kinetics(p, walled, Momentum::conserving),
                          measure_kinetics(p, periodic, Momentum::not_conserving)}) {
        EXPECT_EQ(k.conserved_components, 0);
        EXPECT_EQ(k.total_freedom, D * 10.0);
        EXPECT_EQ(k.temperature(), twice_kinetic(p, -1).first / (D * 10.0));
        for (int s = 0; s < 2; ++s)
            EXPECT_EQ(k.temperature(static_cast<std::size_t>(s)),
                      twice_kinetic(p, s).first / (D * static_cast<double>(k.mobile[s])));
    }
    const auto k = measure_kinetics(with_rock, periodic, Momentum::conserving);
    EXPECT_EQ(k.conserved_components, 0) << "a fixed obstacle takes momentum";
    EXPECT_EQ(k.total_mobile, 10u);
    EXPECT_EQ(k.total_freedom, D * 10.0);
    EXPECT_EQ(k.temperature(2), 0.0);
}

} // namespace

TEST(DegreesOfFreedom, FullyPeriodic2D) {
    fully_periodic_case<2>();
}
TEST(DegreesOfFreedom, FullyPeriodic3D) {
    fully_periodic_case<3>();
}
TEST(DegreesOfFreedom, NothingConserved2D) {
    nothing_conserved_case<2>();
}
TEST(DegreesOfFreedom, NothingConserved3D) {
    nothing_conserved_case<3>();
}

TEST(DegreesOfFreedom, WallsOnOneAxisLeaveTheOthersConserved) {
    const auto p = mixture<3>(9);
    const auto box = box_with<3>({false, true, true});
    const auto k = measure_kinetics(p, box, Momentum::conserving);
    EXPECT_EQ(k.conserved_components, 2);
    EXPECT_DOUBLE_EQ(k.total_freedom, 3.0 * 9 - 2.0);
    // only the y and z drifts are removed
    Vec<3> P{};
    double M = 0.0;
    for (std::size_t i = 0; i < p.size(); ++i) {
        P += p.mass(i) * p.velocity[i];
        M += p.mass(i);
    }
    const double thermal = twice_kinetic(p, -1).first - (P[1] * P[1] + P[2] * P[2]) / M;
    EXPECT_NEAR(k.temperature(), thermal / 25.0, 1e-12);
}

TEST(DegreesOfFreedom, SingleParticleInAPeriodicBoxHasNone) {
    ParticleStore<2> p;
    p.species_table = {Species{"a", 0.5, 1.0}};
    p.resize(1);
    p.velocity[0] = Vec<2>{{1.0, 2.0}};
    const auto k =
        measure_kinetics(p, Box<2>(Vec<2>::filled(5.0), {true, true}), Momentum::conserving);
    EXPECT_EQ(k.total_freedom, 0.0);
    EXPECT_EQ(k.temperature(), 0.0); // not a division by zero
}

// The kinetic part of the periodic virial pressure is 2 K / (d V) in the centre-of-mass
// frame, whatever the number of degrees of freedom.
TEST(DegreesOfFreedom, KineticPressureIsTwiceTheThermalEnergyOverDV) {
    const auto p = mixture<2>(12);
    const Box<2> box(Vec<2>::filled(10.0), {true, true});
    const auto k = measure_kinetics(p, box, Momentum::conserving);
    const EventCounters<2> none{};
    const double P = interval_pressure(box, none, none, 1.0, k.thermal_tensor);
    EXPECT_NEAR(P, 2.0 * k.total_thermal / (2.0 * box.volume()), 1e-12 * P);
    // the tensor's trace is 2 K_thermal, and its off-diagonal part sum m u_x u_y
    EXPECT_NEAR(k.thermal_tensor[0] + k.thermal_tensor[1], 2.0 * k.total_thermal,
                1e-12 * k.total_thermal);
    Vec<2> momentum{};
    double mass = 0.0, xy = 0.0;
    for (std::size_t i = 0; i < p.size(); ++i) {
        momentum += p.mass(i) * p.velocity[i];
        mass += p.mass(i);
    }
    for (std::size_t i = 0; i < p.size(); ++i) {
        const Vec<2> u = p.velocity[i] - momentum * (1.0 / mass);
        xy += p.mass(i) * u[0] * u[1];
    }
    EXPECT_NEAR(k.thermal_tensor[sym_slot(0, 1)], xy, 1e-12 * k.total_thermal);
}

namespace {

RunConfig config(const std::string& dynamics_and_more, const std::string& boundary,
                 const std::string& species) {
    const std::string text = "dimension = 2\nseed = 7\n" + dynamics_and_more +
                             "[box]\nlength = 30.0\nboundary = \"" + boundary + "\"\n" + species;
    return parse_run_config(text, "test.toml", true);
}

const std::string two_species = R"([[species]]
name = "light"
count = 12
mass = 1.0
temperature = 2.0
velocities = "maxwell_boltzmann"
[[species]]
name = "heavy"
count = 8
mass = 5.0
temperature = 0.5
velocities = "maxwell_boltzmann"
)";

const std::string soft_tail = R"(
[run]
steps = 10
dt = 0.001
)";

} // namespace

TEST(DegreesOfFreedom, WhichDynamicsConserveMomentum) {
    const std::string species = "[[species]]\nname = \"A\"\ncount = 4\npositions = \"square\"\n";
    EXPECT_EQ(momentum_of(config("", "periodic", species)), Momentum::conserving);
    EXPECT_EQ(
        momentum_of(config("dynamics = \"stepped\"\n[stepped]\ndt = 0.01\n", "periodic", species)),
        Momentum::conserving);
    const std::string nve = "dynamics = \"nve\"\n";
    const std::string nve_plugin = "[[integrator]]\nname = \"nve\"\n";
    EXPECT_EQ(momentum_of(config(nve, "periodic", species + nve_plugin + soft_tail)),
              Momentum::conserving);
    const std::string propulsion = "[[force]]\nname = \"self_propulsion\"\nalpha = ";
    EXPECT_EQ(momentum_of(
                  config(nve, "periodic", species + propulsion + "1.0\n" + nve_plugin + soft_tail)),
              Momentum::not_conserving);
    EXPECT_EQ(momentum_of(
                  config(nve, "periodic", species + propulsion + "0.0\n" + nve_plugin + soft_tail)),
              Momentum::conserving)
        << "alpha = 0 pushes nothing";
    EXPECT_EQ(momentum_of(config("dynamics = \"langevin\"\n", "periodic",
                                 species + "[[integrator]]\nname = \"langevin\"\nT = 1.0\n" +
                                     "gamma = 1.0\n" + soft_tail)),
              Momentum::not_conserving);
    EXPECT_EQ(momentum_of(config("dynamics = \"brownian\"\n", "periodic",
                                 species + "[[integrator]]\nname = \"brownian\"\nT = 1.0\n" +
                                     "gamma = 1.0\n" + soft_tail)),
              Momentum::not_conserving);
}

// A Maxwell-Boltzmann start with zero momentum has exactly the requested temperatures
// as the runs measure them: in a periodic box each species' T_s = 2 K_s / f_s; in a
// walled one (nothing conserved) 2 K_s / (d N_s), as before.
TEST(DegreesOfFreedom, MaxwellBoltzmannStartHasTheRequestedTemperature) {
    for (const std::string boundary : {"periodic", "wall"}) {
        SCOPED_TRACE(boundary);
        const RunConfig c = config("", boundary, two_species);
        const Box<2> box = build_box<2>(c);
        const ParticleStore<2> p = build_particles<2>(c, box);
        const auto k = measure_kinetics(p, box, momentum_of(c));
        EXPECT_EQ(k.conserved_components, boundary == "periodic" ? 2 : 0);
        EXPECT_NEAR(k.temperature(0), 2.0, 1e-12);
        EXPECT_NEAR(k.temperature(1), 0.5, 1e-12);
        if (boundary == "wall") {
            EXPECT_NEAR(twice_kinetic(p, 0).first, 2.0 * 2 * 12, 1e-10);
            EXPECT_NEAR(twice_kinetic(p, 1).first, 0.5 * 2 * 8, 1e-10);
        } else {
            // f_light = 2 x 12 - 2 x 12 / 52, f_heavy = 2 x 8 - 2 x 40 / 52
            EXPECT_NEAR(twice_kinetic(p, 0).first, 2.0 * (24.0 - 24.0 / 52.0), 1e-10);
            EXPECT_NEAR(twice_kinetic(p, 1).first, 0.5 * (16.0 - 80.0 / 52.0), 1e-10);
        }
    }
}
