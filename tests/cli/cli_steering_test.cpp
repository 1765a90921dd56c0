// `pedesis run --steering RECORD`: a record that cannot be replayed is refused before
// anything runs, with the file and line or the parameter named, exit 2.
#include "cli/cli_support.hpp"

namespace pedesis::test {
namespace {

class CliSteering : public ScratchDir {};

const std::string brownian =
    "dimension = 2\ndynamics = \"brownian\"\nseed = 1\n[box]\nlength = 12.0\n"
    "[[species]]\nname = \"A\"\ncount = 20\nradius = 0.5\n[initial]\npositions = \"random\"\n"
    "[[force]]\nname = \"harmonic\"\nk = 10.0\n"
    "[[integrator]]\nname = \"brownian\"\nT = 0.1\ngamma = 1.0\n"
    "[run]\nsteps = 100\ndt = 0.005\n[output]\nlog_every = 50\nprogress = false\n";

TEST_F(CliSteering, AMalformedRecordNamesItsLine) {
    write("a.toml", brownian);
    write("bad.csv", "step,time,parameter,value\n10,0.05,temperature,0.2\n20,zero,temperature,1\n");
    const CliResult r = run_pedesis("run a.toml --out out --steering bad.csv", dir);
    EXPECT_EQ(r.exit_code, 2) << r.output;
    EXPECT_NE(r.output.find("bad.csv:3: expected step,time,parameter,value"), std::string::npos)
        << r.output;
    EXPECT_FALSE(std::filesystem::exists(dir / "out" / "log.csv"));
}

TEST_F(CliSteering, ARecordOfAParameterTheRunLacksIsRefused) {
    write("a.toml", brownian);
    write("j.csv", "step,time,parameter,value\n10,0.05,J,2\n");
    const CliResult r = run_pedesis("run a.toml --out out --steering j.csv", dir);
    EXPECT_EQ(r.exit_code, 2) << r.output;
    EXPECT_NE(r.output.find("this run has no parameter 'J'"), std::string::npos) << r.output;
}

TEST_F(CliSteering, StepsMustNotDecreaseAndValuesMustBeFinite) {
    write("a.toml", brownian);
    write("back.csv", "step,time,parameter,value\n20,0.1,temperature,0.2\n10,0.05,temperature,1\n");
    CliResult r = run_pedesis("run a.toml --out out --steering back.csv", dir);
    EXPECT_EQ(r.exit_code, 2) << r.output;
    EXPECT_NE(r.output.find("back.csv:3: steps must not decrease"), std::string::npos) << r.output;
    write("nan.csv", "step,time,parameter,value\n20,0.1,temperature,nan\n");
    r = run_pedesis("run a.toml --out out --steering nan.csv", dir);
    EXPECT_EQ(r.exit_code, 2) << r.output;
    EXPECT_NE(r.output.find("nan.csv:2: a change needs a parameter and a finite value"),
              std::string::npos)
        << r.output;
}

// A replayed change holds from its step on: the ideal pressure n T of the log row at
// step 50 has the new temperature (the change at step 20), to the log's 10 digits.
TEST_F(CliSteering, AReplayedChangeHoldsFromItsStep) {
    write("a.toml", brownian);
    write("t.csv", "step,time,parameter,value\n20,0.1,temperature,0.4\n");
    const CliResult r = run_pedesis("run a.toml --out out --steering t.csv", dir);
    ASSERT_EQ(r.exit_code, 0) << r.output;
    const CsvColumns log = csv_columns(read("out/log.csv"));
    EXPECT_NEAR(std::stod(log.cells.at("pressure_ideal").at(0)), 0.1 * 20 / 144.0, 1e-9);
    EXPECT_NEAR(std::stod(log.cells.at("pressure_ideal").at(1)), 0.4 * 20 / 144.0, 1e-9);
    EXPECT_EQ(read("out/steering.csv"), read("t.csv"));
}

// A run restarted from a checkpoint with its record applies the changes before the
// checkpoint at once and the rest at their steps: its log after the checkpoint is the
// run in one go's, byte for byte (soft restarts are bit-exact), with the whole record.
TEST_F(CliSteering, ARestartWithTheRecordEndsAsTheRunInOneGo) {
    std::string config = brownian;
    config.replace(config.find("log_every = 50"), 14, "log_every = 10\ncheckpoint_every = 50");
    write("a.toml", config);
    write("t.csv", "step,time,parameter,value\n20,0.1,temperature,0.4\n70,0.35,temperature,0.02\n");
    const CliResult whole = run_pedesis("run a.toml --out whole --steering t.csv", dir);
    ASSERT_EQ(whole.exit_code, 0) << whole.output;
    std::string first = config;
    first.replace(first.find("steps = 100"), 11, "steps = 50");
    write("first.toml", first);
    const CliResult half = run_pedesis("run first.toml --out first --steering t.csv", dir);
    ASSERT_EQ(half.exit_code, 0) << half.output;
    const CliResult rest =
        run_pedesis("run a.toml --out rest --restart first/checkpoint.bin --steering t.csv", dir);
    ASSERT_EQ(rest.exit_code, 0) << rest.output;
    EXPECT_EQ(read("rest/steering.csv"), read("t.csv"));
    // every row after the checkpoint, every column (the MSD and pressures follow the
    // positions to the log's 10 digits; the ideal pressure shows each temperature)
    const std::string whole_log = read("whole/log.csv"), rest_log = read("rest/log.csv");
    const std::string after = whole_log.substr(whole_log.find("\n60,"));
    EXPECT_EQ(rest_log.substr(rest_log.find("\n60,")), after);
    const CsvColumns log = csv_columns(rest_log);
    EXPECT_NEAR(std::stod(log.cells.at("pressure_ideal").back()), 0.02 * 20 / 144.0, 1e-9);
}

} // namespace
} // namespace pedesis::test
