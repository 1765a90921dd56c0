// The mistakes a newcomer makes, each answered with its cause and its fix (issue 49): a
// key of the other engine says whose it is, a misspelt placement names its line, a
// crowded random placement names min_distance when that is what crowds it, an overfull
// box says how large a box would do, and a blow-up names an overlapping start or an
// absurd density instead of always "reduce dt".
#include "cli/cli_support.hpp"

#include <cmath>

namespace pedesis::test {
namespace {

// A soft run of `count` WCA particles in a square or cube of edge `length`, placed at
// random `min_distance` apart, stepped with dt.
std::string wca(int dim, int count, double length, double min_distance, double dt,
                const std::string& pair = "wca", const std::string& extra = "") {
    return "dimension = " + std::to_string(dim) + "\ndynamics = \"brownian\"\nseed = 4\n" +
           "[box]\nlength = " + std::to_string(length) + "\n" +
           "[[species]]\nname = \"A\"\ncount = " + std::to_string(count) + "\nradius = 0.5\n" +
           "[initial]\nmin_distance = " + std::to_string(min_distance) + "\n" +
           "[[force]]\nname = \"" + pair + "\"\nepsilon = 1.0\nsigma = 1.0\n" + extra +
           "[[integrator]]\nname = \"brownian\"\nT = 1.0\ngamma = 1.0\n" +
           "[run]\nsteps = 50\ndt = " + std::to_string(dt) + "\n[output]\nprogress = false\n";
}

class Messages : public ScratchDir {
  protected:
    CliResult run(const std::string& config) {
        write("cfg.toml", config);
        return run_pedesis("run cfg.toml --out out", dir, 120);
    }
    static void expect_in(const CliResult& r, std::initializer_list<std::string> fragments) {
        for (const auto& f : fragments)
            EXPECT_NE(r.output.find(f), std::string::npos)
                << "missing '" << f << "' in: " << r.output;
    }
};

TEST_F(Messages, ASoftConfigWithAnEventKeySaysWhoseKeyItIs) {
    std::string c = wca(2, 10, 10.0, 1.0, 0.001);
    c.replace(c.find("steps = 50"), 10, "steps = 50\ntime = 5.0");
    const CliResult r = run(c);
    EXPECT_EQ(r.exit_code, 2) << r.output;
    expect_in(r, {"cfg.toml:22:8: unknown key 'run.time'", "read by dynamics = event and stepped",
                  "this config runs \"brownian\"", "run.steps x run.dt"});
    // time instead of steps: the missing key, and why time does not do
    c.replace(c.find("steps = 50\n"), 11, "");
    const CliResult alone = run(c);
    EXPECT_EQ(alone.exit_code, 2) << alone.output;
    expect_in(alone, {"key 'run.steps': is required (run.time: it is read by dynamics = event "
                      "and stepped",
                      "run.steps x run.dt"});
}

TEST_F(Messages, AnEventConfigWithAForceSaysWhoseTableItIs) {
    const CliResult r = run(small_config("") + "[[force]]\nname = \"wca\"\nepsilon = 1.0\n");
    EXPECT_EQ(r.exit_code, 2) << r.output;
    expect_in(r, {"cfg.toml:", "unknown key 'force'", "brownian, langevin and nve",
                  "this config runs \"event\"", "contact alone"});
    // a key no engine reads keeps the plain message
    const CliResult plain = run(small_config("colour = \"red\"\n"));
    EXPECT_EQ(plain.exit_code, 2) << plain.output;
    expect_in(plain, {"unknown key 'species[0].colour' (see docs/config.md for the keys)"});
}

TEST_F(Messages, AMisspeltPlacementNamesItsLine) {
    std::string c = wca(2, 10, 10.0, 1.0, 0.001);
    c.replace(c.find("radius = 0.5\n"), 13, "radius = 0.5\npositions = \"randm\"\n");
    const CliResult r = run(c);
    EXPECT_EQ(r.exit_code, 2) << r.output;
    // the [[species]] table starts on line 6: positions is its fourth key, line 10
    expect_in(r, {"cfg.toml:10:", "'randm' is not a placement", "random", "hexagonal"});
    std::string i = wca(3, 10, 10.0, 1.0, 0.001);
    i.replace(i.find("[initial]\n"), 10, "[initial]\npositions = \"hexagonal\"\n");
    const CliResult r3 = run(i);
    EXPECT_EQ(r3.exit_code, 2) << r3.output;
    expect_in(r3, {"cfg.toml:11:", "'hexagonal' is not a placement", "sc or fcc in 3D"});
}

TEST_F(Messages, ACrowdedRandomPlacementNamesMinDistance) {
    // phi = 0.65 of unit disks, centres kept 0.95 apart: min_distance crowds them (the
    // disks it keeps free would cover 0.59, beyond random placement's 0.547)
    const double length = std::sqrt(400 * 0.7853981633974483 / 0.65);
    const CliResult r = run(wca(2, 400, length, 0.95, 0.001));
    EXPECT_EQ(r.exit_code, 2) << r.output;
    expect_in(r, {"cfg.toml:6:1: species 'A': could not place particle", "diameter 0.95",
                  "([initial] min_distance)", "would cover 0.587 of the region",
                  "positions = \"hexagonal\"", "lower [initial] min_distance to about 0.82"});
    // 800 of them in 12 x 12 do not fit however they are placed: no min_distance helps
    const CliResult overfull = run(wca(2, 800, 12.0, 0.95, 0.001));
    EXPECT_EQ(overfull.exit_code, 2) << overfull.output;
    expect_in(overfull, {"the particles themselves, disks of diameter 1", "would fill 4.36",
                         "give a larger box or fewer particles"});
    EXPECT_EQ(overfull.output.find("min_distance to about"), std::string::npos) << overfull.output;
}

TEST_F(Messages, AnOverfullBoxSaysWhichBoxWouldDo) {
    // 800 hard disks of radius 0.5 in a 10 x 10 box: 6.28 times its area
    std::string c = small_config("", "length = 10.0");
    c.replace(c.find("count = 50"), 10, "count = 800");
    const CliResult r = run(c);
    EXPECT_EQ(r.exit_code, 2) << r.output;
    expect_in(r, {"cfg.toml:8:9: key 'species[0].count': the particles would fill 6.283 of the box",
                  "packing fraction", "close packing", "Give a box of at least 26.32 x 26.32"});
}

TEST_F(Messages, ABlowUpFromAnOverlappingStartSaysSo) {
    // WCA particles started 0.3 sigma apart: the first step throws them out
    const CliResult r = run(wca(2, 200, 20.0, 0.3, 0.01));
    EXPECT_EQ(r.exit_code, 3) << r.output;
    expect_in(r, {"moved", "Likely cause: the start", "inside wca's core (1)",
                  "[initial] min_distance = 1"});
    EXPECT_EQ(r.output.find("reduce dt"), std::string::npos) << r.output;
}

TEST_F(Messages, ABlowUpInAnAbsurdDensitySaysSo) {
    // 5,000 LJ particles in 8.55^3 (rho = 8, ten times a liquid's), as the issue met
    const CliResult r = run(wca(3, 5000, 8.55, 0.0, 0.005, "lj"));
    EXPECT_EQ(r.exit_code, 3) << r.output;
    expect_in(r, {"Likely cause: the density", "fill 4.19 of the box", "close packing (0.7405)",
                  "larger box or fewer particles"});
}

TEST_F(Messages, AHarmonicBlowUpIsNotBlamedOnTheDensity) {
    // the ABP tutorial's harmonic disks overlap by design (they fill 1.26 of the box as
    // disks of diameter a = 2), and its force is bounded: a blow-up there is dt's
    const CliResult r = run_pedesis(std::string("run '") + PEDESIS_SOURCE_DIR +
                                        "/examples/abp_tutorial.toml' --set run.dt=0.5 --out out",
                                    dir, 120);
    EXPECT_EQ(r.exit_code, 3) << r.output;
    expect_in(r, {"moved", "reduce dt (now 0.5)"});
    EXPECT_EQ(r.output.find("Likely cause"), std::string::npos) << r.output;
}

TEST_F(Messages, SetUpRefusalsNameTheirLine) {
    // a velocity distribution misspelt in [initial]: its line, not a species
    std::string v = small_config();
    v.replace(v.find("[run]"), 5, "[initial]\nvelocities = \"maxwell\"\n[run]");
    const CliResult velocities = run(v);
    EXPECT_EQ(velocities.exit_code, 2) << velocities.output;
    expect_in(velocities, {"cfg.toml:12:14: key 'initial.velocities': unknown velocity "
                           "distribution 'maxwell'"});
    // a periodic box too short for the event engine's lists: box.length's line
    std::string e = small_config("", "length = 2.1");
    e.replace(e.find("boundary = \"wall\"\n"), 18, "");
    e.replace(e.find("count = 50"), 10, "count = 1");
    const CliResult edge = run(e);
    EXPECT_EQ(edge.exit_code, 2) << edge.output;
    expect_in(edge, {"cfg.toml:4:10: key 'box.length': periodic length 2.1 must be at least 2.2 "
                     "times the largest contact distance (1)"});
    // a logged quantity this engine does not measure: log.quantities' line
    const CliResult log = run(small_config() + "[log]\nquantities = [\"time\", \"polar_order\"]\n");
    EXPECT_EQ(log.exit_code, 2) << log.output;
    expect_in(log, {"cfg.toml:17:14: key 'log.quantities': 'polar_order' is not measured"});
}

TEST_F(Messages, ABlowUpOfAGoodStartStillSaysReduceDt) {
    // well-separated WCA particles, but dt far too long for their forces at T = 1
    const CliResult r = run(wca(2, 100, 14.0, 1.1, 0.5));
    EXPECT_EQ(r.exit_code, 3) << r.output;
    expect_in(r, {"moved", "reduce dt (now 0.5)"});
    EXPECT_EQ(r.output.find("Likely cause"), std::string::npos) << r.output;
}

} // namespace
} // namespace pedesis::test
