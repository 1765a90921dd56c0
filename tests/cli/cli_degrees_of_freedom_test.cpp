// Every engine reports the temperature with the degrees of freedom of
// docs/engines.md ("Temperature and degrees of freedom"), through the real program:
// summary.json's degrees_of_freedom, and log.csv's temperature at step 0 of a
// Maxwell-Boltzmann start at T = 1.5, which must be exactly 1.5 in each case (the start
// is scaled to the same rule). The kinetic energy at step 0 then tells which count was
// used: K = f T / 2.
#include "cli_support.hpp"

#include <nlohmann/json.hpp>

#include <map>
#include <sstream>

using namespace pedesis::test;

namespace {

class CliDegreesOfFreedom : public ScratchDir {
  protected:
    // The first data row of log.csv, by column name.
    std::map<std::string, double> first_row(const std::string& run) {
        std::istringstream log(read(run + "/log.csv"));
        std::string header, row;
        std::getline(log, header);
        std::getline(log, row);
        std::istringstream h(header), r(row);
        std::map<std::string, double> out;
        std::string name, value;
        while (std::getline(h, name, ',') && std::getline(r, value, ','))
            out[name] = std::stod(value);
        return out;
    }

    // Runs `config` and checks f, T(0) = 1.5 and K(0) = f T / 2.
    void expect_freedom(const std::string& name, const std::string& config, double f) {
        SCOPED_TRACE(name);
        write(name + ".toml", config);
        const CliResult r = run_pedesis("run " + name + ".toml --out " + name, dir);
        ASSERT_EQ(r.exit_code, 0) << r.output;
        const auto summary = nlohmann::json::parse(read(name + "/summary.json"));
        EXPECT_EQ(summary["degrees_of_freedom"].get<double>(), f);
        const auto row = first_row(name);
        ASSERT_TRUE(row.count("temperature")) << read(name + "/log.csv");
        EXPECT_NEAR(row.at("temperature"), 1.5, 1e-7);
        EXPECT_NEAR(row.at("kinetic_energy"), f * 1.5 / 2.0, 1e-7 * f);
    }
};

std::string hard(const std::string& dynamics, const std::string& boundary, int dim) {
    return "dimension = " + std::to_string(dim) + "\nseed = 2\n" + dynamics +
           "[box]\nlength = 12.0\nboundary = " + boundary +
           "\n[[species]]\nname = \"A\"\ncount = 40\ntemperature = 1.5\n"
           "[run]\ntime = 0.5\n[output]\nlog_interval = 0.25\nprogress = false\n";
}

std::string soft(const std::string& integrator, const std::string& forces = "") {
    return "dimension = 2\nseed = 2\ndynamics = \"" + integrator +
           "\"\n[box]\nlength = 20.0\n[[species]]\nname = \"A\"\ncount = 36\n"
           "positions = \"square\"\nvelocities = \"maxwell_boltzmann\"\ntemperature = 1.5\n"
           "[[force]]\nname = \"wca\"\nepsilon = 1.0\n" +
           forces + "[[integrator]]\nname = \"" + integrator + "\"\n" +
           (integrator == "langevin" ? "T = 1.5\ngamma = 1.0\n" : "") +
           "[run]\nsteps = 20\ndt = 0.001\n[output]\nlog_every = 10\nprogress = false\n"
           "formats = []\n";
}

} // namespace

TEST_F(CliDegreesOfFreedom, EventEngine) {
    expect_freedom("periodic2d", hard("", "\"periodic\"", 2), 2 * 39);
    expect_freedom("periodic3d", hard("", "\"periodic\"", 3), 3 * 39);
    expect_freedom("walled", hard("", "\"wall\"", 2), 2 * 40);
    expect_freedom("mixed", hard("", "[\"wall\", \"periodic\"]", 2), 2 * 40 - 1);
}

TEST_F(CliDegreesOfFreedom, SteppedEngine) {
    const std::string stepped = "dynamics = \"stepped\"\n[stepped]\ndt = 0.002\n";
    expect_freedom("periodic", hard(stepped, "\"periodic\"", 2), 2 * 39);
    expect_freedom("walled", hard(stepped, "\"wall\"", 2), 2 * 40);
}

TEST_F(CliDegreesOfFreedom, SoftEngine) {
    expect_freedom("nve", soft("nve"), 2 * 35);
    expect_freedom("langevin", soft("langevin"), 2 * 36);
    expect_freedom("nve_active",
                   soft("nve", "[[force]]\nname = \"self_propulsion\"\nalpha = 1.0\n"), 2 * 36);
    // a trap, gravity or a container holds no momentum constant; walls on one axis leave
    // the other's
    expect_freedom("nve_trap", soft("nve", "[[force]]\nname = \"harmonic_trap\"\nk = 0.1\n"),
                   2 * 36);
    expect_freedom("nve_gravity", soft("nve", "[[force]]\nname = \"gravity\"\nforce = 0.1\n"),
                   2 * 36);
    expect_freedom("nve_container",
                   soft("nve", "[[force]]\nname = \"wall\"\nshape = \"sphere\"\n"
                               "potential = \"harmonic\"\nk = 10.0\nradius = 15.0\n"),
                   2 * 36);
    std::string channel = soft("nve", "[[force]]\nname = \"wall\"\npotential = \"harmonic\"\n"
                                      "k = 10.0\n");
    channel.replace(channel.find("length = 20.0"), 13,
                    "length = 20.0\nboundary = [\"wall\", \"periodic\"]");
    expect_freedom("nve_channel", channel, 2 * 36 - 1);
}

TEST_F(CliDegreesOfFreedom, SummaryPrintsTheCount) {
    write("run.toml", hard("", "\"periodic\"", 2));
    const CliResult r = run_pedesis("run run.toml --out out", dir);
    ASSERT_EQ(r.exit_code, 0) << r.output;
    EXPECT_NE(r.output.find("78 degrees of freedom"), std::string::npos) << r.output;
}
