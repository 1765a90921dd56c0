// What a new user sees of a run (issue 28, item 7): the end-of-run summary of a soft run
// names what the system has (no polar order without directors that move or push), and
// a run directory has a snapshots/ folder only when a format writes files there.
#include "cli/cli_support.hpp"

#include <nlohmann/json.hpp>

#include <filesystem>
#include <fstream>
#include <string>

namespace pedesis::test {
namespace {

namespace fs = std::filesystem;

// 30 soft particles on random sites, a pair force and position integrator chosen by the
// test, and `extra` (more terms) after them.
std::string soft_config(const std::string& dynamics, const std::string& terms,
                        const std::string& output = "formats = []",
                        const std::string& progress = "false") {
    return "dimension = 2\ndynamics = \"" + dynamics +
           "\"\nseed = 7\n[box]\nlength = 12.0\n[[species]]\nname = \"A\"\ncount = 30\n"
           "radius = 0.5\n[initial]\nmin_distance = 0.9\n" +
           terms + "[run]\nsteps = 40\ndt = 0.001\n[output]\nprogress = " + progress + "\n" +
           output + "\n";
}

const std::string lj = "[[force]]\nname = \"lj\"\nepsilon = 1.0\nsigma = 1.0\n";
const std::string wca = "[[force]]\nname = \"wca\"\nepsilon = 1.0\nsigma = 1.0\n";
const std::string langevin = "[[integrator]]\nname = \"langevin\"\nT = 1.0\ngamma = 1.0\n";
const std::string brownian = "[[integrator]]\nname = \"brownian\"\nT = 1.0\ngamma = 1.0\n";

class RunSummary : public ScratchDir {
  protected:
    std::string run(const std::string& config) {
        write("run.toml", config);
        const CliResult r = run_pedesis("run run.toml --out out", dir, 120);
        EXPECT_EQ(r.exit_code, 0) << r.output;
        return r.output;
    }
};

bool has(const std::string& text, const std::string& part) {
    return text.find(part) != std::string::npos;
}

TEST_F(RunSummary, PassiveLennardJonesShowsTemperatureAndEnergyNotPolarOrder) {
    const std::string out = run(soft_config("langevin", lj + langevin));
    EXPECT_FALSE(has(out, "polar order")) << out;
    EXPECT_TRUE(has(out, "  temperature ")) << out;
    EXPECT_TRUE(has(out, "potential energy ")) << out;
    EXPECT_TRUE(has(out, "total energy ")) << out;
    EXPECT_TRUE(has(out, "mean pressure ")) << out;
}

TEST_F(RunSummary, PassiveOverdampedWcaShowsEnergyAndDisplacementNotPolarOrder) {
    const std::string out = run(soft_config("brownian", wca + brownian));
    EXPECT_FALSE(has(out, "polar order")) << out;
    EXPECT_FALSE(has(out, "temperature")) << out; // overdamped: no velocities to measure
    EXPECT_TRUE(has(out, "potential energy ")) << out;
    EXPECT_TRUE(has(out, "MSD ")) << out;
}

TEST_F(RunSummary, ProgressLinesOfAPassiveRunShowNoPolarOrder) {
    const std::string out = run(soft_config("langevin", lj + langevin, "formats = []", "true"));
    EXPECT_FALSE(has(out, "polar order")) << out;
    EXPECT_TRUE(has(out, "  step 0 ")) << out; // the first log row is always shown
    EXPECT_TRUE(has(out, " T = ")) << out;
}

TEST_F(RunSummary, ActiveRunsKeepThePolarOrder) {
    // self-propulsion alone (directors fixed, but they push), and rotational diffusion
    // alone (the directors move): both have an order to report
    const std::string active = run(soft_config(
        "brownian", wca + "[[force]]\nname = \"self_propulsion\"\nalpha = 1.0\n" + brownian));
    EXPECT_TRUE(has(active, "polar order")) << active;
    const std::string rotating = run(soft_config(
        "brownian",
        wca + brownian + "[[integrator]]\nname = \"brownian_rotation\"\nT = 0.1\ngamma = 1.0\n",
        "formats = []", "true"));
    EXPECT_TRUE(has(rotating, "\n  polar order ")) << rotating; // the summary
    EXPECT_TRUE(has(rotating, "(run mean")) << rotating;
    EXPECT_TRUE(has(rotating, "polar order = ")) << rotating;
}

// Benchmark scripts (docs/bench/lammps_side_by_side.sh) check one against the other: the
// rate must be the timed steps over the very window wall_seconds reports. (It was read
// from the clock again after the summary's O(N) measurements: 0.5% apart in a 50-step
// run of 36,000 particles.)
TEST_F(RunSummary, RateIsTheStepsOverTheReportedWallTime) {
    std::string config = soft_config("langevin", lj + langevin);
    config.replace(config.find("count = 30"), 10, "count = 60");
    config.replace(config.find("steps = 40"), 10, "steps = 400");
    run(config);
    std::ifstream in(dir / "out" / "summary.json");
    const auto j = nlohmann::json::parse(in, nullptr, false);
    ASSERT_FALSE(j.is_discarded());
    const double wall = j.at("wall_seconds").get<double>();
    ASSERT_GT(wall, 0.0);
    const double expected = j.at("steps").get<double>() * j.at("particles").get<double>() / wall;
    EXPECT_NEAR(j.at("particle_steps_per_second").get<double>(), expected, 1e-12 * expected);
}

class RunDirectory : public ScratchDir {};

TEST_F(RunDirectory, NoFormatsMakesNoSnapshotFolder) {
    write("soft.toml", soft_config("langevin", lj + langevin, "formats = []"));
    write("hard.toml", small_config("", "length = 20.0", "time = 1.0") + "formats = []\n");
    write("gsd.toml", small_config("", "length = 20.0", "time = 1.0") + "formats = [\"gsd\"]\n");
    for (const std::string name : {"soft", "hard", "gsd"}) {
        const CliResult r = run_pedesis("run " + name + ".toml --out " + name, dir, 120);
        ASSERT_EQ(r.exit_code, 0) << r.output;
        EXPECT_TRUE(fs::exists(dir / name / "summary.json")) << name;
        EXPECT_FALSE(fs::exists(dir / name / "snapshots")) << name;
    }
    EXPECT_TRUE(fs::exists(dir / "gsd" / "trajectory.gsd"));
}

TEST_F(RunDirectory, SnapshotFormatsStillWriteIntoSnapshots) {
    for (const std::string format : {"vtp", "json", "table"}) {
        write(format + ".toml",
              small_config("", "length = 20.0", "time = 1.0") + "formats = [\"" + format + "\"]\n");
        const CliResult r = run_pedesis("run " + format + ".toml --out " + format, dir, 120);
        ASSERT_EQ(r.exit_code, 0) << r.output;
        const std::string ext = format == "table" ? "txt" : format;
        EXPECT_TRUE(fs::exists(dir / format / "snapshots" / ("frame_000000." + ext))) << format;
    }
}

} // namespace
} // namespace pedesis::test
