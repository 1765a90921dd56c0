// A run into a directory an earlier run used: the earlier run's plots and movie go (they
// would pass for this run's), the user's own files stay; and a --restart with nothing left
// to run is refused rather than ending at once as if it had run.
#include "cli_support.hpp"

#include <nlohmann/json.hpp>

using namespace pedesis::test;

namespace {

class Rerun : public ScratchDir {};

// the default names of pedesis analyze KIND and pedesis render (docs/analyze.md, docs/render.md)
const std::vector<std::string> earlier_plots{
    "speed_distribution.png", "thermo.png",     "msd.png",      "order.png",
    "structure.png",          "bond_order.png", "clusters.png", "movie.mp4"};

TEST_F(Rerun, EarlierPlotsGoAndOtherFilesStay) {
    const std::string soft =
        "dimension = 2\ndynamics = \"brownian\"\n[box]\nlength = 12\n[[species]]\nname = "
        "\"A\"\ncount = 20\n[[force]]\nname = \"harmonic\"\nk = 10.0\n[[integrator]]\nname = "
        "\"brownian\"\nT = 0.1\ngamma = 1.0\n[run]\nsteps = 20\ndt = 0.001\n[output]\n"
        "progress = false\n";
    write("event.toml", small_config());
    write("soft.toml", soft);
    for (const std::string config : {"event.toml", "soft.toml"}) {
        ASSERT_EQ(run_pedesis("run " + config + " --out out", dir, 60).exit_code, 0) << config;
        for (const std::string& plot : earlier_plots) write("out/" + plot, "an earlier run's");
        write("out/my_notes.png", "the user's");
        const CliResult r = run_pedesis("run " + config + " --out out", dir, 60);
        ASSERT_EQ(r.exit_code, 0) << r.output;
        for (const std::string& plot : earlier_plots)
            EXPECT_FALSE(std::filesystem::exists(dir / "out" / plot)) << config << ": " << plot;
        EXPECT_EQ(read("out/my_notes.png"), "the user's") << config;
    }
}

TEST_F(Rerun, EventRestartWithNothingLeftIsRefused) {
    write("two.toml", small_config());
    ASSERT_EQ(run_pedesis("run two.toml --out two", dir, 60).exit_code, 0);
    write("one.toml", small_config("", "length = 20.0", "time = 1.0"));
    for (const std::string config : {"two.toml", "one.toml"}) {
        const CliResult r =
            run_pedesis("run " + config + " --restart two/checkpoint.bin --out again", dir, 60);
        EXPECT_EQ(r.exit_code, 2) << config << "\n" << r.output;
        EXPECT_NE(r.output.find(config + ": the checkpoint two/checkpoint.bin is at t = 2"),
                  std::string::npos)
            << r.output;
        EXPECT_NE(r.output.find("already meets the stop condition (time); raise it in [run]"),
                  std::string::npos)
            << r.output;
        EXPECT_FALSE(std::filesystem::exists(dir / "again" / "summary.json")) << config;
    }
    // with time left it runs on
    write("three.toml", small_config("", "length = 20.0", "time = 3.0"));
    const CliResult r =
        run_pedesis("run three.toml --restart two/checkpoint.bin --out on", dir, 60);
    ASSERT_EQ(r.exit_code, 0) << r.output;
    EXPECT_DOUBLE_EQ(nlohmann::json::parse(read("on/summary.json"))["time"].get<double>(), 3.0);
}

} // namespace
