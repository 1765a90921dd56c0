// The NVT thermostats (`bussi`, `nose_hoover`) through the command line: a restart
// continues bit for bit (the thermostat's state is in the checkpoint: Bussi's bath
// energy, the Nose-Hoover chain), the log's conserved_energy is there only for them and
// stays flat, and bad parameters are refused with exit 2 and one message.
#include "cli/cli_support.hpp"

#include <cmath>
#include <regex>
#include <string>

namespace pedesis::test {
namespace {

// A 2D WCA fluid of 100 particles under the named thermostat, with storage sorts and list
// rebuilds on both sides of step 100.
std::string config(const std::string& thermostat, int steps,
                   const std::string& keys = "T = 1.0\ntau = 0.1") {
    return R"(dimension = 2
dynamics = ")" +
           thermostat +
           R"("
seed = 4

[box]
length = 12.0

[[species]]
name = "A"
count = 100
radius = 0.5

[initial]
positions = "square"
velocities = "maxwell_boltzmann"
temperature = 1.5

[[force]]
name = "wca"
epsilon = 1.0

[[integrator]]
name = ")" +
           thermostat + "\"\n" + keys + R"(

[neighbor_list]
skin = 0.3
sort_every = 30

[run]
steps = )" +
           std::to_string(steps) +
           R"(
dt = 0.005

[output]
log_every = 25
snapshot_every = 100
formats = ["json"]
progress = false
)";
}

class Thermostats : public ScratchDir {
  protected:
    // 100 steps, then a restart to 200, equal 200 steps in one go: the last frame and the log
    // rows after the checkpoint (conserved_energy among them) byte for byte.
    void expect_restart_exact(const std::string& thermostat) {
        write("full.toml", config(thermostat, 200));
        write("half.toml", config(thermostat, 100));
        const auto full = run_pedesis("run full.toml --out full", dir, 60);
        ASSERT_EQ(full.exit_code, 0) << full.output;
        ASSERT_EQ(run_pedesis("run half.toml --out half", dir, 60).exit_code, 0);
        const auto cont =
            run_pedesis("run full.toml --out cont --restart half/checkpoint.bin", dir, 60);
        ASSERT_EQ(cont.exit_code, 0) << cont.output;
        const std::string a = read("full/snapshots/frame_000002.json");
        ASSERT_FALSE(a.empty());
        EXPECT_TRUE(a == read("cont/snapshots/frame_000002.json"))
            << thermostat << ": the restarted run differs from the continuous one";
        const std::string la = read("full/log.csv"), lb = read("cont/log.csv");
        ASSERT_NE(lb.find("conserved_energy"), std::string::npos) << lb;
        EXPECT_NE(la.find(lb.substr(lb.find('\n') + 1)), std::string::npos) << la << "\n" << lb;
    }
};

TEST_F(Thermostats, BussiRestartEqualsContinuousRun) {
    expect_restart_exact("bussi");
}

TEST_F(Thermostats, NoseHooverRestartEqualsContinuousRun) {
    expect_restart_exact("nose_hoover");
}

TEST_F(Thermostats, ConservedEnergyIsLoggedForThermostatsOnlyAndStaysFlat) {
    for (const std::string thermostat : {"bussi", "nose_hoover"}) {
        write("run.toml", config(thermostat, 400));
        const auto r = run_pedesis("run run.toml --out " + thermostat, dir, 60);
        ASSERT_EQ(r.exit_code, 0) << r.output;
        const CsvColumns log = csv_columns(read(thermostat + "/log.csv"));
        const auto h = log.numbers("conserved_energy"), e = log.numbers("total_energy");
        // the start at T = 1.5 is cooled to T = 1: the bath takes about 40 from K + U,
        // and conserved_energy moves by less than a hundredth of that (velocity Verlet's
        // bounded error, ~1e-3 per particle here; a bath left out or counted with the
        // wrong sign would move it by all of it or twice)
        double moved = 0.0, exchanged = 0.0;
        for (std::size_t k = 0; k < h.size(); ++k) {
            moved = std::max(moved, std::abs(h[k] - h[0]));
            exchanged = std::max(exchanged, std::abs(e[k] - e[0]));
        }
        EXPECT_GT(exchanged, 20.0) << thermostat;
        EXPECT_LT(moved, 0.01 * exchanged)
            << thermostat << ": moved " << moved << " of " << exchanged;
    }
    write("nve.toml", config("nve", 50, ""));
    const auto r = run_pedesis("run nve.toml --out nve", dir, 60);
    ASSERT_EQ(r.exit_code, 0) << r.output;
    EXPECT_EQ(read("nve/log.csv").find("conserved_energy"), std::string::npos);
}

TEST_F(Thermostats, BadParametersAreRefused) {
    expect_rejected(config("bussi", 10, "T = -1.0\ntau = 0.1"), {"integrator[0].T", ">= 0"});
    expect_rejected(config("bussi", 10, "T = 1.0\ntau = 0.0"), {"integrator[0].tau", "positive"});
    expect_rejected(config("bussi", 10, "T = 1.0"), {"'bussi' needs tau"});
    expect_rejected(config("nose_hoover", 10, "T = -1.0\ntau = 0.1"),
                    {"integrator[0].T", "positive"});
    expect_rejected(config("nose_hoover", 10, "T = 0.0\ntau = 0.1"),
                    {"integrator[0].T", "positive"});
    expect_rejected(config("nose_hoover", 10, "T = 1.0\ntau = -2.0"),
                    {"integrator[0].tau", "positive"});
    expect_rejected(config("nose_hoover", 10, "T = 1.0\ntau = 0.1\nchain = 2.5"),
                    {"integrator[0].chain", "whole number"});
    expect_rejected(config("nose_hoover", 10, "T = 1.0\ntau = 0.1\nchain = 0"),
                    {"integrator[0].chain", "positive"});
    // the position integrator is the one dynamics names
    std::string mixed = config("bussi", 10);
    mixed = std::regex_replace(mixed, std::regex("name = \"bussi\""), "name = \"nose_hoover\"");
    expect_rejected(mixed, {"dynamics", "'bussi'", "'nose_hoover'"});
}

TEST_F(Thermostats, ABlowUpNamesTheThermostat) {
    // T = 1e6 (mean speed ~1000) moves the particles far beyond the skin in a step
    for (const std::string thermostat : {"bussi", "nose_hoover"}) {
        write("boom.toml", config(thermostat, 50, "T = 1e6\ntau = 0.01"));
        const auto r = run_pedesis("run boom.toml --out " + thermostat, dir, 60);
        EXPECT_EQ(r.exit_code, 3) << r.output;
        EXPECT_NE(r.output.find(thermostat + ": at step"), std::string::npos) << r.output;
    }
}

TEST_F(Thermostats, ARestartWithAnotherChainLengthIsRefused) {
    write("half.toml", config("nose_hoover", 100));
    ASSERT_EQ(run_pedesis("run half.toml --out half", dir, 60).exit_code, 0);
    write("more.toml", config("nose_hoover", 200, "T = 1.0\ntau = 0.1\nchain = 4"));
    const auto r = run_pedesis("run more.toml --out more --restart half/checkpoint.bin", dir, 60);
    EXPECT_EQ(r.exit_code, 2) << r.output;
    EXPECT_NE(r.output.find("chain has 3 thermostats, and the config's chain = 4"),
              std::string::npos)
        << r.output;
}

} // namespace
} // namespace pedesis::test
