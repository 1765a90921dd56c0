// Walls of the soft engine through the command line: a walled box runs with a wall force
// and logs its wall_pressure columns; a walled axis without one, a planes wall in a
// periodic box, a particle outside a container, a wall's misplaced key and two walls of
// one shape are refused with exit 2 before any output; a run with walls continues from
// its checkpoint bit for bit.
#include "cli/cli_support.hpp"

#include "pedesis/io/xyz_reader.hpp"

#include <algorithm>
#include <cmath>
#include <string>

namespace pedesis::test {
namespace {

// ABPs in a 2D box walled along x; `wall` is the wall's [[force]] table's extra lines.
std::string channel(const std::string& wall, const std::string& run = "steps = 400",
                    const std::string& boundary = "[\"wall\", \"periodic\"]") {
    return "dimension = 2\ndynamics = \"brownian\"\nseed = 4\n[initial]\nmin_distance = 1.0\n"
           "[box]\nlengths = [16.0, 10.0]\nboundary = " +
           boundary +
           "\n[[species]]\nname = \"A\"\ncount = 60\nradius = 0.5\n"
           "[[force]]\nname = \"wca\"\nepsilon = 1.0\n"
           "[[force]]\nname = \"self_propulsion\"\nalpha = 1.0\n" +
           wall +
           "[[integrator]]\nname = \"brownian\"\nT = 0.1\ngamma = 1.0\n"
           "[[integrator]]\nname = \"brownian_rotation\"\nT = 0.5\ngamma = 1.0\n"
           "[run]\n" +
           run + "\ndt = 0.002\n[output]\nlog_every = 50\ncheckpoint_every = 200\n";
}

const std::string harmonic_wall =
    "[[force]]\nname = \"wall\"\npotential = \"harmonic\"\nk = 50.0\n";

class SoftWalls : public ScratchDir {};

TEST_F(SoftWalls, AWalledChannelRunsAndLogsThePressureOnItsWalls) {
    write("run.toml", channel(harmonic_wall, "steps = 3000"));
    const CliResult r = run_pedesis("run run.toml --out out", dir, 120);
    ASSERT_EQ(r.exit_code, 0) << r.output;
    const CsvColumns log = csv_columns(read("out/log.csv"));
    const auto p = log.numbers("wall_pressure_x");
    ASSERT_EQ(p.size(), 61u);
    // particles placed off the walls: nothing pushes at step 0; swimmers reach them later
    EXPECT_EQ(p.front(), 0.0);
    EXPECT_GT(p.back(), 0.0);
    EXPECT_EQ(std::count(log.names.begin(), log.names.end(), "wall_pressure_y"), 0);
}

TEST_F(SoftWalls, AWalledAxisNeedsAWallForce) {
    expect_rejected(channel(""), {"axis x is a wall", "[[force]] name = \"wall\""});
}

TEST_F(SoftWalls, PlanesNeedAWalledAxis) {
    expect_rejected(channel(harmonic_wall, "steps = 400", "\"periodic\""),
                    {"every axis is periodic", "shape = \"sphere\""});
}

TEST_F(SoftWalls, AParticleOutsideAWcaContainerIsRefused) {
    // (random starts keep inside containers; a lattice fills the box)
    std::string lattice = channel("[[force]]\nname = \"wall\"\nshape = \"sphere\"\nradius = 3.0\n",
                                  "steps = 400", "\"periodic\"");
    lattice.replace(lattice.find("radius = 0.5\n"), 13, "radius = 0.5\npositions = \"square\"\n");
    expect_rejected(lattice, {"starts on or beyond a wall", "region"});
}

TEST_F(SoftWalls, MisplacedKeysAreNamed) {
    expect_rejected(channel("[[force]]\nname = \"wall\"\npotential = \"soft\"\n"),
                    {"bad.toml:", "'soft' is not one of wca, lj93, harmonic"});
    expect_rejected(channel("[[force]]\nname = \"wall\"\npotential = \"harmonic\"\n"),
                    {"a harmonic wall needs k"});
    expect_rejected(channel("[[force]]\nname = \"wall\"\nk = 3.0\n"), {"k is the harmonic wall's"});
    expect_rejected(channel(harmonic_wall + "radius = 3.0\n"), {"no radius"});
    expect_rejected(channel("[[force]]\nname = \"wall\"\nshape = \"cylinder\"\nradius = 3.0\n"),
                    {"a cylinder needs a 3D box"});
    expect_rejected(channel(harmonic_wall + harmonic_wall), {"would both log wall_pressure_x"});
}

// A start from a file may put a particle deep in a wca wall's repulsion (0.6 from the
// wall, sigma 1.5): the blow-up says so, and what to change.
TEST_F(SoftWalls, ABlowUpFromAStartInsideTheWallSaysSo) {
    write("start.json", "{\"system\":{\"box\":{\"Lx\":16.0,\"Ly\":10.0},\"particles\":["
                        "{\"id\":0,\"r\":[-7.4,0.0],\"n\":[1.0,0.0],\"radius\":0.5,\"type\":0},"
                        "{\"id\":1,\"r\":[3.0,1.0],\"n\":[0.0,1.0],\"radius\":0.5,\"type\":0}]}}");
    std::string config = channel("[[force]]\nname = \"wall\"\nsigma = 1.5\n");
    config.replace(config.find("[initial]\n"), 10, "[initial]\nfile = \"start.json\"\n");
    config.erase(config.find("[[species]]"), config.find("[[force]]") - config.find("[[species]]"));
    write("run.toml", config);
    const CliResult r = run_pedesis("run run.toml --out out", dir, 120);
    EXPECT_EQ(r.exit_code, 3) << r.output;
    EXPECT_NE(r.output.find("Likely cause: the start. Particle 0 began 0.6 from a wall, inside "
                            "the wca wall's core (1.5)"),
              std::string::npos)
        << r.output;
    EXPECT_NE(r.output.find("give the wall a smaller sigma"), std::string::npos) << r.output;
}

// A random start keeps centres a wca wall's sigma from walled faces (not just a radius)
// and inside a container by as much: the runs start without a blow-up, and the start
// frame has every centre where it should be.
TEST_F(SoftWalls, RandomStartsKeepOutOfTheWallsCores) {
    write("planes.toml", channel("[[force]]\nname = \"wall\"\nsigma = 1.5\n", "steps = 100") +
                             "snapshot_every = 100\nformats = [\"xyz\"]\n");
    const CliResult r = run_pedesis("run planes.toml --out planes", dir, 120);
    ASSERT_EQ(r.exit_code, 0) << r.output;
    const XyzReader planes(dir / "planes/trajectory.xyz");
    const XyzFrame start = planes.frame(0);
    ASSERT_EQ(start.size(), 60u);
    for (std::size_t i = 0; i < start.size(); ++i)
        EXPECT_LE(std::abs(start.position[i][0]), 8.0 - 1.5) << i;

    std::string sphere = channel("[[force]]\nname = \"wall\"\nshape = \"sphere\"\n"
                                 "radius = 4.9\nsigma = 1.0\n",
                                 "steps = 100", "\"periodic\"") +
                         "snapshot_every = 100\nformats = [\"xyz\"]\n";
    sphere.replace(sphere.find("count = 60"), 10, "count = 20");
    write("sphere.toml", sphere);
    const CliResult c = run_pedesis("run sphere.toml --out sphere", dir, 120);
    ASSERT_EQ(c.exit_code, 0) << c.output;
    const XyzFrame inside = XyzReader(dir / "sphere/trajectory.xyz").frame(0);
    for (std::size_t i = 0; i < inside.size(); ++i)
        EXPECT_LE(std::hypot(inside.position[i][0], inside.position[i][1]), 4.9 - 1.0) << i;
}

TEST_F(SoftWalls, ARunWithWallsContinuesFromItsCheckpointBitForBit) {
    write("full.toml", channel(harmonic_wall, "steps = 400"));
    write("half.toml", channel(harmonic_wall, "steps = 200"));
    ASSERT_EQ(run_pedesis("run full.toml --out full", dir, 120).exit_code, 0);
    ASSERT_EQ(run_pedesis("run half.toml --out half", dir, 120).exit_code, 0);
    const CliResult cont =
        run_pedesis("run full.toml --out cont --restart half/checkpoint.bin", dir, 120);
    ASSERT_EQ(cont.exit_code, 0) << cont.output;
    const std::string full = read("full/log.csv"), rest = read("cont/log.csv");
    const std::string rows = rest.substr(rest.find('\n') + 1);
    ASSERT_GT(rows.size(), 20u);
    EXPECT_NE(full.find(rows), std::string::npos) << "continued:\n" << rest << "\nfull:\n" << full;
}

} // namespace
} // namespace pedesis::test
