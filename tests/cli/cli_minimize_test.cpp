// dynamics = "minimize" (FIRE) through the command line: a harmonic packing above jamming
// stops at the force tolerance, too few steps stop at run.steps, and a relative energy
// change at energy_tolerance, each with exit 0 and the reason in summary.json's
// stopped_by and on the console; a particle under gravity ends on a harmonic wall where
// the forces balance (the final frame); the log has FIRE's columns and no kinetic
// pressure; bad [minimize] keys and what FIRE does not run with are refused with exit 2
// before any output.
#include "cli/cli_support.hpp"

#include "pedesis/io/xyz_reader.hpp"

#include <nlohmann/json.hpp>

#include <algorithm>
#include <string>

namespace pedesis::test {
namespace {

// 32 + 32 bidisperse (radii 0.5 and 0.7) harmonic disks at phi = 0.90 (box 9.092); `minimize`
// is the [minimize] table's lines, `more` anything after [run].
std::string packing(const std::string& minimize = "force_tolerance = 1e-12\n",
                    const std::string& steps = "100000", const std::string& more = "") {
    return "dimension = 2\ndynamics = \"minimize\"\nseed = 5\n[box]\nlength = 9.0917\n"
           "[[species]]\nname = \"small\"\ncount = 32\nradius = 0.5\n"
           "[[species]]\nname = \"large\"\ncount = 32\nradius = 0.7\n"
           "[[force]]\nname = \"harmonic\"\nk = 1.0\n[neighbor_list]\nskin = 0.3\n"
           "[minimize]\n" +
           minimize + "[run]\nsteps = " + steps +
           "\ndt = 0.1\n[output]\nlog_every = 100\nprogress = false\nformats = [\"xyz\"]\n" + more;
}

class Minimize : public ScratchDir {
  protected:
    nlohmann::json summary(const std::string& out) {
        return nlohmann::json::parse(read(out + "/summary.json"));
    }
};

TEST_F(Minimize, APackingAboveJammingStopsAtTheForceTolerance) {
    write("run.toml", packing());
    const CliResult r = run_pedesis("run run.toml --out out", dir, 120);
    ASSERT_EQ(r.exit_code, 0) << r.output;
    const nlohmann::json j = summary("out");
    EXPECT_EQ(j["stopped_by"], "force_tolerance");
    EXPECT_TRUE(j["minimize"]["converged"].get<bool>());
    EXPECT_LT(j["minimize"]["max_force"].get<double>(), 1e-12);
    EXPECT_LT(j["steps"].get<std::uint64_t>(), 100000u);
    EXPECT_NE(r.output.find("minimised (FIRE) at step"), std::string::npos) << r.output;
    EXPECT_NE(r.output.find("< force_tolerance 1e-12"), std::string::npos) << r.output;

    const CsvColumns log = csv_columns(read("out/log.csv"));
    for (const char* column : {"max_force", "force_norm", "fire_dt"})
        EXPECT_EQ(std::count(log.names.begin(), log.names.end(), column), 1) << column;
    // the descent's velocities are no temperature
    EXPECT_EQ(std::count(log.names.begin(), log.names.end(), "temperature"), 0);
    for (double p : log.numbers("pressure_ideal")) EXPECT_EQ(p, 0.0);
    const auto energy = log.numbers("potential_energy");
    const auto force = log.numbers("max_force");
    EXPECT_LT(energy.back(), energy.front());
    EXPECT_LT(force.back(), 1e-12);
    EXPECT_GT(force.front(), 0.1) << "the start overlaps";
    EXPECT_GT(log.numbers("pressure").back(), 0.0) << "above jamming";
    // (the final frame is the minimum)
    EXPECT_EQ(XyzReader(dir / "out/trajectory.xyz").frame(1).size(), 64u);
}

TEST_F(Minimize, TooFewStepsStopAtTheStepLimitWithExit0) {
    write("run.toml", packing("force_tolerance = 1e-12\n", "20"));
    const CliResult r = run_pedesis("run run.toml --out out", dir, 120);
    ASSERT_EQ(r.exit_code, 0) << r.output;
    const nlohmann::json j = summary("out");
    EXPECT_EQ(j["stopped_by"], "steps");
    EXPECT_FALSE(j["minimize"]["converged"].get<bool>());
    EXPECT_GT(j["minimize"]["max_force"].get<double>(), 1e-12);
    EXPECT_EQ(j["steps"].get<std::uint64_t>(), 20u);
    EXPECT_NE(r.output.find("not minimised: run.steps = 20 reached"), std::string::npos)
        << r.output;
    EXPECT_NE(r.output.find("[initial] file = \"out/trajectory.xyz\""), std::string::npos)
        << r.output;
}

TEST_F(Minimize, ARelativeEnergyChangeBelowEnergyToleranceStopsTheRun) {
    write("run.toml", packing("force_tolerance = 1e-14\nenergy_tolerance = 1e-6\n"));
    const CliResult r = run_pedesis("run run.toml --out out", dir, 120);
    ASSERT_EQ(r.exit_code, 0) << r.output;
    const nlohmann::json j = summary("out");
    EXPECT_EQ(j["stopped_by"], "energy_tolerance");
    EXPECT_GT(j["minimize"]["max_force"].get<double>(), 1e-14);
    EXPECT_NE(r.output.find("less than energy_tolerance 1e-06"), std::string::npos) << r.output;
}

TEST_F(Minimize, AParticleUnderGravityEndsOnAHarmonicWallWhereTheForcesBalance) {
    // the wall's push k (sigma - h) balances the weight w at h = sigma - w / k = 0.48
    write("run.toml", "dimension = 2\ndynamics = \"minimize\"\n[box]\nlength = 10.0\n"
                      "boundary = [\"periodic\", \"wall\"]\n"
                      "[[species]]\nname = \"A\"\ncount = 1\nradius = 0.5\nmass = 7.0\npositions = "
                      "\"point\"\nposition = [1.0, 3.0]\n"
                      "[[force]]\nname = \"wall\"\npotential = \"harmonic\"\nk = 100.0\n"
                      "[[force]]\nname = \"gravity\"\nforce = 2.0\n"
                      "[minimize]\nforce_tolerance = 1e-10\n[run]\nsteps = 100000\ndt = 0.02\n"
                      "[output]\nprogress = false\nformats = [\"xyz\"]\n");
    const CliResult r = run_pedesis("run run.toml --out out", dir, 120);
    ASSERT_EQ(r.exit_code, 0) << r.output;
    EXPECT_EQ(summary("out")["stopped_by"], "force_tolerance");
    const XyzReader xyz(dir / "out/trajectory.xyz");
    const XyzFrame last = xyz.frame(xyz.frames() - 1);
    EXPECT_NEAR(last.position[0][1], -5.0 + 0.48, 1e-9);
    EXPECT_NEAR(last.position[0][0], 1.0, 1e-9);
}

TEST_F(Minimize, BadMinimizeKeysAreNamed) {
    expect_rejected(packing("f_dec = 1.5\n"), {"bad.toml:", "minimize.f_dec", "(0, 1)"});
    expect_rejected(packing("ftol = 1e-8\n"), {"minimize.ftol"});
    expect_rejected(packing("force_tolerance = 0.0\n"), {"force_tolerance", "positive"});
    expect_rejected(packing("max_move = 0.5\n"), {"max_move", "skin (0.3)"});
    expect_rejected(packing("dt_min = 0.5\n"), {"dt_min", "at most run.dt"});
    expect_rejected(packing("dt_max = 0.05\n"), {"dt_max", "at least run.dt"});
    expect_rejected(packing("n_delay = -1\n"), {"n_delay"});
    expect_rejected(packing("energy_tolerance = 2.0\n"), {"energy_tolerance", "[0, 1)"});
}

TEST_F(Minimize, WhatFireDoesNotRunWithIsRefused) {
    expect_rejected(packing("", "100", "[[integrator]]\nname = \"nve\"\n"),
                    {"takes no [[integrator]]"});
    expect_rejected(packing("", "100", "[[force]]\nname = \"self_propulsion\"\nalpha = 1.0\n"),
                    {"self_propulsion is an active force"});
    expect_rejected(packing("", "100", "[[torque]]\nname = \"polar_align\"\nJ = 1.0\na = 1.0\n"),
                    {"remove the [[torque]]"});
    std::string sheared = packing();
    sheared.replace(sheared.find("length = 9.0917\n"), 16, "length = 9.0917\nshear_rate = 0.1\n");
    expect_rejected(sheared, {"minimises in a fixed box"});
    // [minimize] belongs to dynamics = "minimize"
    std::string nve = packing();
    nve.replace(nve.find("\"minimize\""), 10, "\"nve\"");
    nve += "[[integrator]]\nname = \"nve\"\n";
    expect_rejected(nve, {"minimize", "dynamics = minimize", "\"nve\""});
}

TEST_F(Minimize, ARestartIsRefusedAndAFinishedMinimisationHasNothingToResume) {
    write("run.toml", packing("force_tolerance = 1e-12\n", "20"));
    ASSERT_EQ(run_pedesis("run run.toml --out out", dir, 120).exit_code, 0);
    write("more.toml", packing("force_tolerance = 1e-12\n", "40"));
    const CliResult r = run_pedesis("run more.toml --out more --restart out/checkpoint.bin", dir);
    EXPECT_EQ(r.exit_code, 2) << r.output;
    EXPECT_NE(r.output.find("does not continue from a checkpoint"), std::string::npos) << r.output;
    EXPECT_FALSE(std::filesystem::exists(dir / "more" / "summary.json"));
    // a minimisation that met its tolerance is a finished run for --resume
    write("done.toml", packing());
    ASSERT_EQ(run_pedesis("run done.toml --out done", dir, 120).exit_code, 0);
    const CliResult again = run_pedesis("run done.toml --out done --resume", dir, 120);
    EXPECT_EQ(again.exit_code, 0) << again.output;
    EXPECT_NE(again.output.find("stopped by force_tolerance): nothing to do"), std::string::npos)
        << again.output;
}

} // namespace
} // namespace pedesis::test
