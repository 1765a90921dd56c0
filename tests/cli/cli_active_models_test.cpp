// The active models beyond ABPs from a config (issue 50): active_torque, nematic_align,
// velocity_align and run_and_tumble run in 2D and 3D, self_propulsion runs with langevin
// (inertial ABPs), and a bad parameter is one message naming the file, line and key,
// exit 2.
#include "cli/cli_support.hpp"

#include <algorithm>
#include <string>

namespace pedesis::test {
namespace {

// Every new term at once: chiral ABPs with both alignments, tumbling and diffusing.
std::string active_config(int dimension = 2) {
    return "dimension = " + std::to_string(dimension) + R"(
dynamics = "brownian"
seed = 3
[box]
length = )" +
           (dimension == 2 ? "20" : "10") +
           R"(
[[species]]
name = "A"
count = 40
radius = 1.0
[[force]]
name = "harmonic"
k = 10.0
a = 2.0
[[force]]
name = "self_propulsion"
alpha = 1.0
[[torque]]
name = "active_torque"
torque = { A = 0.5 }
[[torque]]
name = "nematic_align"
J = 1.0
a = 2.0
[[torque]]
name = "velocity_align"
J = 0.5
a = 2.5
[[integrator]]
name = "brownian"
T = 0.1
gamma = 1.0
[[integrator]]
name = "run_and_tumble"
rate = { A = 0.5 }
[[integrator]]
name = "brownian_rotation"
T = 0.1
gamma = 1.0
[run]
steps = 20
dt = 0.01
[output]
progress = false
)";
}

std::string replaced(std::string config, const std::string& from, const std::string& to) {
    const auto at = config.find(from);
    EXPECT_NE(at, std::string::npos) << from;
    if (at != std::string::npos) config.replace(at, from.size(), to);
    return config;
}

// "bad.toml:N:" for the line of `text` in `config` (1-based).
std::string line_of(const std::string& config, const std::string& text) {
    const auto at = config.find(text);
    EXPECT_NE(at, std::string::npos) << text;
    const auto n = std::count(config.begin(), config.begin() + static_cast<long>(at), '\n') + 1;
    return "bad.toml:" + std::to_string(n) + ":";
}

class CliActiveModels : public ScratchDir {
  protected:
    void expect_runs(const std::string& config) {
        write("run.toml", config);
        const CliResult r = run_pedesis("run run.toml --out out", dir);
        EXPECT_EQ(r.exit_code, 0) << config << "\n" << r.output;
        EXPECT_TRUE(std::filesystem::exists(dir / "out" / "log.csv")) << r.output;
        std::filesystem::remove_all(dir / "out");
    }
};

TEST_F(CliActiveModels, EveryNewTermRuns2D) {
    expect_runs(active_config(2));
}

TEST_F(CliActiveModels, EveryNewTermRuns3DWithALabFrameTorque) {
    expect_runs(active_config(3));
    expect_runs(replaced(active_config(3), "torque = { A = 0.5 }", "torque = [0.0, 0.3, 1.0]"));
}

// run_and_tumble is a director integrator of its own: without brownian_rotation (and so
// without torques) it runs beside the position integrator.
TEST_F(CliActiveModels, RunAndTumbleWithoutRotationalDiffusion) {
    std::string c = active_config(2);
    for (const char* table :
         {"[[torque]]\nname = \"active_torque\"\ntorque = { A = 0.5 }\n",
          "[[torque]]\nname = \"nematic_align\"\nJ = 1.0\na = 2.0\n",
          "[[torque]]\nname = \"velocity_align\"\nJ = 0.5\na = 2.5\n",
          "[[integrator]]\nname = \"brownian_rotation\"\nT = 0.1\ngamma = 1.0\n"})
        c = replaced(c, table, "");
    expect_runs(c);
}

// Inertial ABPs: self_propulsion with langevin and brownian_rotation.
TEST_F(CliActiveModels, InertialAbpsRun) {
    std::string c =
        replaced(active_config(2), "dynamics = \"brownian\"", "dynamics = \"langevin\"");
    c = replaced(c, "name = \"brownian\"\n", "name = \"langevin\"\n");
    expect_runs(c);
}

TEST_F(CliActiveModels, BadParametersNameFileLineAndKey) {
    const std::string c = active_config(2);
    std::string bad = replaced(c, "rate = { A = 0.5 }", "rate = -1.0");
    expect_rejected(bad, {line_of(bad, "rate ="), "integrator[1].rate", "must be >= 0"});
    bad = replaced(c, "torque = { A = 0.5 }", "torque = [0.0, 0.0, 1.0]");
    expect_rejected(bad, {line_of(bad, "torque = ["), "torque[0].torque",
                          "a 2D torque is one number (about z), not a list"});
    bad = replaced(active_config(3), "torque = { A = 0.5 }", "torque = [0.0, 1.0]");
    expect_rejected(bad, {line_of(bad, "torque = ["), "torque[0].torque",
                          "or a list of three (a lab-frame vector), not a list of 2"});
    bad = replaced(c, "J = 0.5\na = 2.5", "J = 0.5\na = 0.0");
    expect_rejected(bad, {line_of(bad, "a = 0.0"), "torque[2].a", "must be positive"});
    bad = replaced(c, "J = 1.0\na = 2.0", "a = 2.0");
    expect_rejected(bad, {line_of(bad, "name = \"nematic_align\""), "needs J"});
    bad = replaced(c, "torque = { A = 0.5 }", "torque = { B = 0.5 }");
    expect_rejected(bad, {line_of(bad, "torque = {"), "torque[0].torque", "species 'A'"});
}

TEST_F(CliActiveModels, IntegratorRules) {
    const std::string tumble = "[[integrator]]\nname = \"run_and_tumble\"\nrate = { A = 0.5 }\n";
    std::string bad = replaced(active_config(2), tumble, tumble + tumble);
    expect_rejected(bad, {"a second 'run_and_tumble' integrator",
                          "the particles would tumble at the sum of the rates"});
    // run_and_tumble turns no torque: a torque still needs brownian_rotation
    bad = replaced(active_config(2),
                   "[[integrator]]\nname = \"brownian_rotation\"\nT = 0.1\ngamma = 1.0\n", "");
    expect_rejected(bad, {line_of(bad, "name = \"active_torque\""),
                          "a torque turns nothing without a 'brownian_rotation' integrator"});
}

} // namespace
} // namespace pedesis::test
