// [transport] from the command line (run/transport_measurement.hpp): the coefficients of a
// dilute hard-sphere gas against Chapman-Enskog (Enskog at n sigma^3 = 0.1, where it is
// within a few per cent of molecular dynamics), the stepped engine against the event
// engine on one system, a restart that continues the measurement bit for bit, and the
// refusals.
#include "cli/cli_support.hpp"

#include <nlohmann/json.hpp>

#include <cmath>
#include <sstream>
#include <string>

namespace pedesis::test {
namespace {

std::string hard_gas(const std::string& dynamics, int dim, double length, int count, double time,
                     const std::string& extra = "", const std::string& box_extra = "",
                     const std::string& stop = "") {
    std::ostringstream c;
    c << "dimension = " << dim << "\ndynamics = \"" << dynamics
      << "\"\nseed = 5\n[box]\nlengths = [";
    for (int a = 0; a < dim; ++a) c << (a ? ", " : "") << length;
    c << "]\n"
      << box_extra << "[[species]]\nname = \"a\"\ncount = " << count << "\nradius = 0.5\n[run]\n";
    if (stop.empty())
        c << "time = " << time;
    else
        c << stop;
    c << "\n[output]\nlog_interval = 100.0\nformats = []\n";
    if (dynamics == "stepped") c << "[stepped]\ndt = 0.01\n";
    c << "[transport]\n" << extra;
    return c.str();
}

class CliTransport : public ScratchDir {
  protected:
    nlohmann::json transport(const std::string& out) {
        return nlohmann::json::parse(read(out + "/summary.json")).at("transport");
    }
};

// |value - reference| within 4 standard errors plus `slack` of the reference
void expect_near_reference(const nlohmann::json& c, double reference, double slack,
                           const char* what) {
    const double v = c.at("value").get<double>(), e = c.at("error").get<double>();
    EXPECT_GT(e, 0.0) << what;
    EXPECT_NEAR(v, reference, 4.0 * e + slack * reference) << what << ": error " << e;
}

TEST_F(CliTransport, DiluteHardSpheresGiveEnskogsCoefficients) {
    // n = 0.1 (400 spheres in 15.874^3), 1600 mean free times: Enskog's D, eta, lambda
    // (../shared/PHYSICS.md) are within about 2 % of molecular dynamics here; tolerance 4
    // standard errors plus 5 %. A factor 2 (V T for 2 V T), a missing 1/T or a wrong
    // dimension of the block sums would fail.
    write("gas.toml", hard_gas("event", 3, 15.874, 400, 2000.0));
    const CliResult r = run_pedesis("run gas.toml --out gas", dir);
    ASSERT_EQ(r.exit_code, 0) << r.output;
    const auto t = transport("gas");
    const double n = 400.0 / std::pow(15.874, 3);
    ASSERT_NEAR(n, 0.1, 1e-4);
    const auto& enskog = t.at("enskog");
    // Enskog at n = 0.1 (phi = 0.0524, chi = 1.146): from the formulas, by hand
    EXPECT_NEAR(enskog.at("diffusion").get<double>(), 1.8839, 2e-3);
    EXPECT_NEAR(enskog.at("shear_viscosity").get<double>(), 0.19341, 2e-4);
    EXPECT_NEAR(enskog.at("thermal_conductivity").get<double>(), 0.78848, 1e-3);
    expect_near_reference(t.at("diffusion"), 1.8839, 0.05, "D");
    expect_near_reference(t.at("shear_viscosity"), 0.19341, 0.05, "eta");
    expect_near_reference(t.at("thermal_conductivity"), 0.78848, 0.05, "lambda");
    // the bulk viscosity is small in a dilute gas (Enskog 0.0090: collisional only)
    expect_near_reference(t.at("bulk_viscosity"), 0.0090145, 0.2, "bulk viscosity");
    // Yeh-Hummer: D + 2.837297 T / (6 pi eta L)
    const double eta = t.at("shear_viscosity").at("value").get<double>();
    EXPECT_NEAR(
        t.at("diffusion_infinite").at("value").get<double>(),
        t.at("diffusion").at("value").get<double>() + 2.837297 / (6.0 * M_PI * eta * 15.874), 1e-9);
    EXPECT_EQ(t.at("blocks").get<int>(), 8);
    EXPECT_NEAR(t.at("fit_window").at("to").get<double>(), t.at("block_time").get<double>() / 10.0,
                1e-9);
    // the printed lines and transport.csv's long format
    EXPECT_NE(r.output.find("shear viscosity"), std::string::npos) << r.output;
    const std::string csv = read("gas/transport.csv");
    EXPECT_EQ(csv.rfind("quantity,lag,correlation,running_coefficient\n", 0), 0u);
    for (const char* q :
         {"\ndiffusion,", "\nshear_viscosity,", "\nbulk_viscosity,", "\nthermal_conductivity,"})
        EXPECT_NE(csv.find(q), std::string::npos) << q;
}

TEST_F(CliTransport, SteppedAndEventEnginesAgreeOnHardDisks) {
    // 480 disks in 40 x 40 (phi = 0.236): the two engines' D and eta within 4 combined errors
    write("event.toml", hard_gas("event", 2, 40.0, 480, 400.0));
    write("stepped.toml", hard_gas("stepped", 2, 40.0, 480, 400.0));
    ASSERT_EQ(run_pedesis("run event.toml --out event", dir).exit_code, 0);
    const CliResult s = run_pedesis("run stepped.toml --out stepped", dir);
    ASSERT_EQ(s.exit_code, 0) << s.output;
    const auto a = transport("event"), b = transport("stepped");
    for (const char* k : {"diffusion", "shear_viscosity", "thermal_conductivity"}) {
        const double va = a.at(k).at("value").get<double>(), vb = b.at(k).at("value").get<double>();
        const double e =
            std::hypot(a.at(k).at("error").get<double>(), b.at(k).at("error").get<double>());
        EXPECT_NEAR(va, vb, 4.0 * e) << k;
    }
    EXPECT_FALSE(b.contains("diffusion_infinite")) << "2D has no Yeh-Hummer correction";
    // the stepped engine samples on whole steps
    const double interval = b.at("interval").get<double>();
    EXPECT_NEAR(interval / 0.01, std::round(interval / 0.01), 1e-9);
}

TEST_F(CliTransport, ARestartContinuesTheMeasurementBitForBit) {
    for (const char* dynamics : {"event", "stepped"}) {
        const std::string d = dynamics;
        write(d + ".toml", hard_gas(d, 2, 30.0, 200, 200.0, "block_time = 50.0\n"));
        write(d + "_half.toml", hard_gas(d, 2, 30.0, 200, 100.0, "block_time = 50.0\n"));
        ASSERT_EQ(run_pedesis("run " + d + ".toml --out whole", dir).exit_code, 0);
        ASSERT_EQ(run_pedesis("run " + d + "_half.toml --out half", dir).exit_code, 0);
        const CliResult r =
            run_pedesis("run " + d + ".toml --restart half/checkpoint.bin --out rest", dir);
        ASSERT_EQ(r.exit_code, 0) << r.output;
        EXPECT_EQ(transport("whole").dump(), transport("rest").dump()) << dynamics;
        EXPECT_EQ(read("whole/transport.csv"), read("rest/transport.csv")) << dynamics;
    }
}

TEST_F(CliTransport, RefusesWhatItCannotMeasure) {
    expect_rejected(hard_gas("event", 2, 30.0, 100, 100.0, "", "boundary = \"wall\"\n"),
                    {"table 'transport'", "periodic box"});
    expect_rejected(hard_gas("event", 2, 30.0, 100, 100.0, "blocks = 0\n"),
                    {"transport.blocks", "1 to 10000"});
    expect_rejected(hard_gas("event", 2, 30.0, 100, 100.0, "interval = -1\n"),
                    {"transport.interval", "positive time"});
    expect_rejected(hard_gas("event", 2, 30.0, 100, 100.0, "lag = 3\n"), {"transport.lag"});
    // positions 10^300 apart: not a conversion out of range, the block's refusal
    expect_rejected(hard_gas("event", 2, 30.0, 100, 100.0, "diffusion_interval = 1e300\n"),
                    {"fewer than 20 samples"});
    // a run of 10^11 samples would never end
    expect_rejected(hard_gas("event", 2, 30.0, 100, 100.0, "interval = 1e-9\n"),
                    {"more than 10^8 samples"});
    // 8 blocks of 1.25 time units hold fewer than 20 samples of the particles
    expect_rejected(hard_gas("event", 2, 30.0, 100, 10.0), {"fewer than 20 samples"});
    // no [run] time: the blocks need a length
    const std::string by_collisions =
        hard_gas("event", 2, 30.0, 100, 100.0, "", "", "collisions_per_particle = 50");
    expect_rejected(by_collisions, {"give block_time"});
}

// A small WCA fluid (n = 0.8) for the soft engine's [transport].
std::string wca(const std::string& dynamics, int steps, const std::string& extra = "") {
    std::ostringstream c;
    c << "dimension = 3\ndynamics = \"" << dynamics << "\"\nseed = 3\n[box]\nlength = 6.2996\n"
      << "[[species]]\nname = \"A\"\ncount = 200\nradius = 0.5\n[initial]\n"
      << "positions = \"random\"\nmin_distance = 0.85\nvelocities = \"maxwell_boltzmann\"\n"
      << "temperature = 1.0\n[[force]]\nname = \"wca\"\nepsilon = 1.0\nsigma = 1.0\n"
      << "[[integrator]]\nname = \"" << dynamics << "\"\n"
      << (dynamics == "nve" ? "" : "T = 1.0\ngamma = 1.0\n") << "[run]\nsteps = " << steps
      << "\ndt = 0.004\n[output]\nlog_every = 500\nformats = []\n[transport]\n"
      << extra;
    return c.str();
}

TEST_F(CliTransport, SoftEngineMeasuresWhatItCanAndSaysWhyNotTheRest) {
    write("langevin.toml", wca("langevin", 10000));
    const CliResult r = run_pedesis("run langevin.toml --out langevin", dir);
    ASSERT_EQ(r.exit_code, 0) << r.output;
    const auto t = transport("langevin");
    // D and eta measured with errors; WCA at n = 0.8, T = 1 with this thermostat: D near
    // 0.066, eta near 1.8 (the NEMD of the same fluid): loose bands of 30 %
    expect_near_reference(t.at("diffusion"), 0.066, 0.3, "D");
    expect_near_reference(t.at("shear_viscosity"), 1.8, 0.3, "eta");
    for (const char* k : {"thermal_conductivity", "bulk_viscosity"}) {
        EXPECT_TRUE(t.at(k).at("value").is_null()) << k;
        EXPECT_FALSE(t.at(k).at("why").get<std::string>().empty()) << k;
    }
    EXPECT_FALSE(t.contains("enskog")) << "Enskog is for hard particles";
    // its samples fall on whole steps: 20 steps of 0.004 by default
    EXPECT_NEAR(t.at("interval").get<double>(), 0.08, 1e-12);
    // nve measures the bulk viscosity and the thermal conductivity too (the heat flux's
    // definition is checked exactly in soft_heat_flux_test; here, that it reaches the
    // summary: WCA's lambda at n = 0.8, T = 1 is of order 5 in its units)
    write("nve.toml", wca("nve", 10000));
    ASSERT_EQ(run_pedesis("run nve.toml --out nve", dir).exit_code, 0);
    const auto nve = transport("nve");
    EXPECT_FALSE(nve.at("bulk_viscosity").at("value").is_null());
    const double lambda = nve.at("thermal_conductivity").at("value").get<double>();
    EXPECT_GT(lambda, 1.0);
    EXPECT_LT(lambda, 20.0);
    // brownian and sheared runs are refused with the way out
    expect_rejected(wca("brownian", 1000), {"table 'transport'", "langevin or nve"});
    std::string sheared = wca("langevin", 1000);
    sheared.insert(sheared.find("[[species]]"), "shear_rate = 0.2\n");
    expect_rejected(sheared, {"table 'transport'", "\"shear\""});
}

TEST_F(CliTransport, SoftRestartContinuesTheMeasurementBitForBit) {
    write("whole.toml", wca("langevin", 5000, "block_time = 5.0\n"));
    write("half.toml", wca("langevin", 2500, "block_time = 5.0\n"));
    ASSERT_EQ(run_pedesis("run whole.toml --out whole", dir).exit_code, 0);
    ASSERT_EQ(run_pedesis("run half.toml --out half", dir).exit_code, 0);
    const CliResult r = run_pedesis("run whole.toml --restart half/checkpoint.bin --out rest", dir);
    ASSERT_EQ(r.exit_code, 0) << r.output;
    EXPECT_EQ(transport("whole").dump(), transport("rest").dump());
    EXPECT_EQ(read("whole/transport.csv"), read("rest/transport.csv"));
}

} // namespace
} // namespace pedesis::test
