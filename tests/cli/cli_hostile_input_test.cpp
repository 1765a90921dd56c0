// Inputs a hostile tester tried (issue 14) that used to run for minutes, crash, hang or
// start a run that could only fail later: each is refused up front with exit 2, a
// message naming the file and key, within seconds, and before any output exists.
#include "cli_support.hpp"

using namespace pedesis::test;

namespace {

class HostileInput : public ScratchDir {
  protected:
    // expect_rejected with a time limit: a refusal must come at once, not after a run
    void expect_refused_quickly(const std::string& config,
                                std::initializer_list<std::string> fragments) {
        write("bad.toml", config);
        const CliResult r = run_pedesis("run bad.toml --out out", dir, 20);
        EXPECT_EQ(r.exit_code, 2) << r.output;
        for (const auto& f : fragments)
            EXPECT_NE(r.output.find(f), std::string::npos)
                << "missing '" << f << "' in " << r.output;
        EXPECT_FALSE(std::filesystem::exists(dir / "out")) << r.output;
    }
};

std::string gas(const std::string& species) {
    return "dimension = 2\n[box]\nlength = 150.0\n[[species]]\nname = \"A\"\nradius = 0.5\n" +
           species + "\n[run]\ntime = 1.0\n[output]\nprogress = false\n";
}

} // namespace

// 3.9 GB for 76 s, then std::bad_alloc (exit 1), before: now an estimate of the memory
// (or of the packing: 10^9 disks cannot fit in 150 x 150) at once.
TEST_F(HostileInput, ImpossibleParticleCounts) {
    expect_refused_quickly(gas("count = 1000000000"), {"bad.toml", "N = 1000000000"});
    expect_refused_quickly(gas("count = 9223372036854775807"),
                           {"bad.toml", "species[0].count", "more particles than"});
    // fits in memory, not in the box
    expect_refused_quickly(gas("count = 30000"),
                           {"would fill 1.047", "cannot fill more than 0.9069"});
}

// A speed of 1e200 made an event run that never ended, with inf and nan in its log.
TEST_F(HostileInput, AbsurdSpeedsAndSizes) {
    expect_refused_quickly(gas("count = 10\nvelocities = \"given\"\nvelocity = [1e200, 0.0]"),
                           {"species[0].velocity", "at most 1e100"});
    expect_refused_quickly(gas("count = 10\nvelocities = \"maxwell_boltzmann\"\n"
                               "temperature = 1e250"),
                           {"species[0].temperature", "at most 1e100"});
    expect_refused_quickly(
        "dimension = 3\n[box]\nlength = 1e120\n[[species]]\ncount = 1\n[run]\ntime = 1.0\n",
        {"box.length", "too large"});
}

// The same through an initial file, which the config's checks do not see: the engine
// refuses it, naming the file and the particle.
TEST_F(HostileInput, AbsurdSpeedInAnInitialFile) {
    write("fast.json", R"({"system": {"box": {"Lx": 20, "Ly": 20}, "particles": [)"
                       R"({"id": 0, "type": 0, "r": [0, 0], "v": [1e200, 0]},)"
                       R"({"id": 1, "type": 0, "r": [3, 0], "v": [0, 1]}]}})");
    expect_refused_quickly("dimension = 2\n[box]\nlength = 20.0\n[[species]]\nname = \"A\"\n"
                           "radius = 0.5\n[initial]\nfile = \"fast.json\"\n[run]\ntime = 1.0\n",
                           {"fast.json: particle 0", "speed above 1e100"});
}

// A JSON box with Lz was silently dropped in a 2D run.
TEST_F(HostileInput, ThreeDimensionalBoxInATwoDimensionalRun) {
    write("init.json",
          R"({"system": {"box": {"Lx": 20, "Ly": 20, "Lz": 20}, "particles": [)"
          R"({"id": 0, "type": 0, "r": [0, 0]}, {"id": 1, "type": 0, "r": [3, 0]}]}})");
    expect_refused_quickly("dimension = 2\ndynamics = \"brownian\"\n[initial]\nfile = "
                           "\"init.json\"\n[[integrator]]\nname = \"brownian\"\nT = 1.0\n"
                           "gamma = 1.0\n[run]\nsteps = 10\ndt = 0.01\n",
                           {"init.json", "Lz", "2D"});
}
