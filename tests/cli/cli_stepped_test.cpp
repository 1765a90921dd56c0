// The stepped engine through the command line: the examples run; the run directory has
// the event engine's files and columns plus the notebook's; a restart continues bit for
// bit; a time step too large for the starting speeds is bad input (exit 2, naming
// [stepped] dt and suggesting one), and a particle that gets too fast during the run
// stops it (exit 3, naming the step and the particle) with the outputs so far kept.
#include "cli_support.hpp"

#include <nlohmann/json.hpp>

#include <cmath>
#include <regex>

using namespace pedesis::test;

namespace {

// expect_rejected (cli_support.hpp): exit 2, the fragments, no output that looks complete
class CliStepped : public ScratchDir {};

std::string gas(const std::string& dynamics_and_engine, const std::string& run = "time = 4.0") {
    return "dimension = 2\nseed = 7\n" + dynamics_and_engine +
           "\n[box]\nlength = 30.0\nboundary = [\"wall\", \"periodic\"]\n"
           "[[species]]\nname = \"A\"\ncount = 150\nradius = 0.5\n"
           "[[species]]\nname = \"B\"\ncount = 50\nradius = 0.7\nmass = 3.0\n"
           "[initial]\nvelocities = \"normal\"\nsigma = 1.0\n"
           "[run]\n" +
           run +
           "\n[output]\nlog_interval = 0.5\nsnapshot_interval = 1.0\nformats = [\"xyz\", "
           "\"json\"]\n";
}

const std::string stepped = "dynamics = \"stepped\"\n[stepped]\ndt = 0.02";

} // namespace

TEST_F(CliStepped, ExamplesRun) {
    // The summary's Z = P V / (N T) uses the box; the centres reach an edge L - 2r = L - 1
    // shorter, so the force on a wall per unit area of the centres' wall is P L / (L - 1)
    // and their volume V ((L - 1) / L)^d: that gas must follow the equation of state
    // at its own packing fraction. Tolerance 3%: the examples are short (a few thousand
    // wall hits, ~2% if independent); measured within 0.5%.
    const struct {
        const char* name;
        int dim;
        double L;
    } examples[] = {{"kinetic_gas_2d", 2, 100.0}, {"kinetic_gas_3d", 3, 30.0}};
    for (const auto& ex : examples) {
        const std::string name = ex.name;
        const std::string src = std::string(PEDESIS_SOURCE_DIR) + "/examples/" + name + ".toml";
        const CliResult r = run_pedesis("run '" + src + "' --out " + name, dir);
        ASSERT_EQ(r.exit_code, 0) << r.output;
        const auto s = nlohmann::json::parse(read(name + "/summary.json"));
        const double shrink = (ex.L - 1.0) / ex.L;
        const double z = s["compressibility"].get<double>() * shrink;
        const double eta = s["packing_fraction"].get<double>() / std::pow(shrink, ex.dim);
        const double z_eos =
            ex.dim == 2 ? (1.0 + eta * eta / 8.0) / ((1.0 - eta) * (1.0 - eta))
                        : (1.0 + eta + eta * eta - eta * eta * eta) / std::pow(1.0 - eta, 3);
        EXPECT_NEAR(z / z_eos, 1.0, 0.03) << name;
        EXPECT_GT(s["collisions_per_particle"].get<double>(), 3.0) << name;
        EXPECT_NE(r.output.find("Iteration:"), std::string::npos);
        EXPECT_NE(r.output.find("Wall Pressure:"), std::string::npos);
        EXPECT_NE(r.output.find("ideal gas N T / V"), std::string::npos);
    }
}

TEST_F(CliStepped, RunDirectoryHasTheEventFilesAndTheNotebookColumns) {
    write("s.toml", gas(stepped));
    const CliResult r = run_pedesis("run s.toml --out out", dir);
    ASSERT_EQ(r.exit_code, 0) << r.output;
    for (const char* f :
         {"config.toml", "log.csv", "trajectory.xyz", "speed_histogram.csv", "checkpoint.bin",
          "summary.json", "snapshots/frame_000000.json", "snapshots/frame_000004.json"})
        EXPECT_TRUE(std::filesystem::exists(dir / "out" / f)) << f;
    EXPECT_FALSE(std::filesystem::exists(dir / "out" / "log.csv.part"));
    // the event engine's columns first, in its order, then the stepped engine's own
    write("e.toml", gas("dynamics = \"event\""));
    ASSERT_EQ(run_pedesis("run e.toml --out ev", dir).exit_code, 0);
    const std::string log = read("out/log.csv"), event_log = read("ev/log.csv");
    const std::string header = log.substr(0, log.find('\n'));
    const std::string event_header = event_log.substr(0, event_log.find('\n'));
    const std::string shared = event_header.substr(0, event_header.rfind(",list_rebuilds"));
    EXPECT_EQ(header, shared + ",step,v_rms,mean_speed,pressure_running");
    // 9 rows: t = 0, 0.5, ..., 4; the last at step 200
    int rows = 0;
    for (char ch : log) rows += ch == '\n';
    EXPECT_EQ(rows, 1 + 9);
    EXPECT_NE(log.find("\n4,"), std::string::npos) << log;
    EXPECT_NE(log.find(",200,"), std::string::npos) << log;
    // the same initial state as the event run: frame 0 is identical
    EXPECT_EQ(read("out/snapshots/frame_000000.json"), read("ev/snapshots/frame_000000.json"));
    const auto s = nlohmann::json::parse(read("out/summary.json"));
    EXPECT_EQ(s["dynamics"], "stepped");
    EXPECT_EQ(s["steps"], 200);
    EXPECT_EQ(s["stopped_by"], "time");
    EXPECT_DOUBLE_EQ(s["time"].get<double>(), 4.0);
    EXPECT_NEAR(s["energy_fraction"].get<double>(), 1.0, 1e-12);
    for (const char* k : {"pressure", "pressure_ideal_gas", "compressibility",
                          "compressibility_equation_of_state", "late_collisions", "dt"})
        EXPECT_TRUE(s.contains(k)) << k;
}

TEST_F(CliStepped, StepsAndCollisionStopConditions) {
    write("s.toml", gas(stepped, "steps = 37"));
    ASSERT_EQ(run_pedesis("run s.toml --out a", dir).exit_code, 0);
    auto s = nlohmann::json::parse(read("a/summary.json"));
    EXPECT_EQ(s["steps"], 37);
    EXPECT_EQ(s["stopped_by"], "steps");
    write("c.toml", gas(stepped, "collisions_per_particle = 0.5\ntime = 100.0"));
    ASSERT_EQ(run_pedesis("run c.toml --out c", dir).exit_code, 0);
    s = nlohmann::json::parse(read("c/summary.json"));
    EXPECT_EQ(s["stopped_by"], "collisions_per_particle");
    EXPECT_GE(s["collisions_per_particle"].get<double>(), 0.5);
}

TEST_F(CliStepped, RestartContinuesBitForBit) {
    write("full.toml", gas(stepped, "time = 4.0"));
    write("half.toml", gas(stepped, "time = 2.0"));
    ASSERT_EQ(run_pedesis("run full.toml --out full", dir).exit_code, 0);
    ASSERT_EQ(run_pedesis("run half.toml --out half", dir).exit_code, 0);
    const CliResult r = run_pedesis("run full.toml --restart half/checkpoint.bin --out cont", dir);
    ASSERT_EQ(r.exit_code, 0) << r.output;
    const auto full = nlohmann::json::parse(read("full/summary.json"));
    const auto cont = nlohmann::json::parse(read("cont/summary.json"));
    EXPECT_EQ(full, cont);
    // frames 0..4 in the full run; the half run wrote 0..2, so the restart ends at 4 too
    EXPECT_EQ(read("full/snapshots/frame_000004.json"), read("cont/snapshots/frame_000004.json"));
    EXPECT_EQ(read("full/speed_histogram.csv"), read("cont/speed_histogram.csv"));
    // a checkpoint that already meets the stop condition has nothing to run
    const CliResult done = run_pedesis("run half.toml --restart half/checkpoint.bin --out d", dir);
    EXPECT_EQ(done.exit_code, 2);
    EXPECT_NE(done.output.find("already meets the stop condition (time)"), std::string::npos)
        << done.output;
    // an event checkpoint is refused
    write("e.toml", gas("dynamics = \"event\""));
    ASSERT_EQ(run_pedesis("run e.toml --out ev", dir).exit_code, 0);
    const CliResult wrong = run_pedesis("run full.toml --restart ev/checkpoint.bin --out x", dir);
    EXPECT_EQ(wrong.exit_code, 2);
    EXPECT_NE(wrong.output.find("a checkpoint of the event engine"), std::string::npos)
        << wrong.output;
}

TEST_F(CliStepped, TimeStepTooLargeForTheStartIsBadInputWithASuggestion) {
    // each component normal with sigma = 1: the fastest of 200 starts at about 3 and would
    // move about 3 radii in a step of 0.5
    const std::string big = "dynamics = \"stepped\"\n[stepped]\ndt = 0.5";
    expect_rejected(gas(big), {"bad.toml:5:", "stepped.dt", "is too large", "particle",
                               "radii in one step", "use dt ="});
    // the suggested dt is accepted and runs
    write("bad.toml", gas(big));
    const std::string msg = run_pedesis("run bad.toml --out out", dir).output;
    std::smatch m;
    ASSERT_TRUE(std::regex_search(msg, m, std::regex("use dt = ([0-9.e-]+) or less"))) << msg;
    write("ok.toml", gas("dynamics = \"stepped\"\n[stepped]\ndt = " + m[1].str()));
    const CliResult ok = run_pedesis("run ok.toml --out ok", dir);
    EXPECT_EQ(ok.exit_code, 0) << ok.output;
    EXPECT_EQ(ok.output.find("note: dt is above"), std::string::npos) << ok.output;
}

TEST_F(CliStepped, ParticleTooFastMidRunStopsNamingStepAndParticle) {
    // a heavy disk moving 0.4 radii per step of 0.2 hits a light one at rest at t = 1.1
    // (in step 5); the light one leaves at about 2, 0.8 radii per step: the check at the
    // start of step 6 stops the run
    write("fast.toml",
          "dimension = 2\ndynamics = \"stepped\"\n[box]\nlength = 20.0\nboundary = \"wall\"\n"
          "[[species]]\nname = \"heavy\"\nmass = 1000.0\nposition = [-2.1, 0.0]\n"
          "velocity = [1.0, 0.0]\n"
          "[[species]]\nname = \"light\"\nposition = [0.0, 0.0]\nvelocity = [0.0, 0.0]\n"
          "[stepped]\ndt = 0.2\n[run]\ntime = 10.0\n[output]\nlog_interval = 0.4\n");
    const CliResult r = run_pedesis("run fast.toml --out out", dir);
    EXPECT_EQ(r.exit_code, 3) << r.output;
    // no checkpoint was due before the stop, and the message names none
    for (const char* f :
         {"at step 6 particle 1 (species 'light')", "radii in one step", "reduce [stepped] dt to",
          "it and the log are in out; no checkpoint was written before the failure)"})
        EXPECT_NE(r.output.find(f), std::string::npos) << "missing '" << f << "' in " << r.output;
    // the log and frames up to the stop are kept, complete; no summary
    EXPECT_TRUE(std::filesystem::exists(dir / "out" / "log.csv"));
    EXPECT_TRUE(std::filesystem::exists(dir / "out" / "trajectory.gsd"));
    EXPECT_FALSE(std::filesystem::exists(dir / "out" / "summary.json"));
    EXPECT_FALSE(std::filesystem::exists(dir / "out" / "checkpoint.bin"));

    // with checkpoints every 0.4 the last one (t = 0.8) is there, and named
    std::string with = read("fast.toml");
    with += "checkpoint_interval = 0.4\n";
    write("checkpointed.toml", with);
    const CliResult c = run_pedesis("run checkpointed.toml --out cp", dir);
    EXPECT_EQ(c.exit_code, 3) << c.output;
    EXPECT_NE(c.output.find("it, the log and the last checkpoint are in cp)"), std::string::npos)
        << c.output;
    EXPECT_TRUE(std::filesystem::exists(dir / "cp" / "checkpoint.bin"));
}

TEST_F(CliStepped, BadConfigs) {
    expect_rejected(gas("dynamics = \"stepped\""), {"bad.toml", "needs a [stepped] table"});
    expect_rejected(gas("dynamics = \"stepped\"\n[stepped]\nmax_move = 0.3"),
                    {"stepped.dt", "is required"});
    expect_rejected(gas("dynamics = \"stepped\"\n[stepped]\ndt = -0.1"),
                    {"bad.toml:5", "stepped.dt", "positive"});
    expect_rejected(gas("dynamics = \"stepped\"\n[stepped]\ndt = nan"), {"stepped.dt", "NaN"});
    expect_rejected(gas("dynamics = \"stepped\"\n[stepped]\ndt = 0.01\nmax_move = 1.5"),
                    {"stepped.max_move", "(0, 1]"});
    expect_rejected(gas("dynamics = \"stepped\"\n[stepped]\ndt = 0.01\nrestitution = 0.9"),
                    {"unknown key 'stepped.restitution'"});
    expect_rejected(gas(stepped + "\n[event]\nrestitution = 1.0"), {"[event] is for"});
    expect_rejected(gas("dynamics = \"event\"\n[stepped]\ndt = 0.01"), {"[stepped] is for"});
    expect_rejected(gas(stepped, "energy_fraction = 0.5"), {"run.energy_fraction", "elastic"});
    expect_rejected(gas(stepped, "steps = 0"), {"run.steps", "positive"});
    expect_rejected(gas(stepped, "steps = 2.5"), {"run.steps"});
    expect_rejected(gas("dynamics = \"event\"", "time = 1.0\nsteps = 10"),
                    {"unknown key 'run.steps'"});
    expect_rejected(gas("dynamics = \"stoped\""), {"'stoped' is not available", "stepped"});
}
