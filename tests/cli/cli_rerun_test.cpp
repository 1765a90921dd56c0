// A run into a directory an earlier run used: the earlier run's plots and movie go (they
// would pass for this run's), the user's own files stay; and a --restart with nothing left
// to run is refused rather than ending at once as if it had run.
#include "cli_support.hpp"

#include <nlohmann/json.hpp>

using namespace pedesis::test;

namespace {

class Rerun : public ScratchDir {
  protected:
    void write_event_and_soft();
};

// the default names of pedesis analyze KIND and pedesis render (docs/analyze.md, docs/render.md)
const std::vector<std::string> earlier_plots{
    "speed_distribution.png", "thermo.png",   "msd.png",       "order.png", "structure.png",
    "bond_order.png",         "clusters.png", "transport.png", "movie.mp4"};

// A small event run as event.toml and a small Brownian run as soft.toml.
void Rerun::write_event_and_soft() {
    write("event.toml", small_config());
    write("soft.toml",
          "dimension = 2\ndynamics = \"brownian\"\n[box]\nlength = 12\n[[species]]\nname = "
          "\"A\"\ncount = 20\n[[force]]\nname = \"harmonic\"\nk = 10.0\n[[integrator]]\nname = "
          "\"brownian\"\nT = 0.1\ngamma = 1.0\n[run]\nsteps = 20\ndt = 0.001\n[output]\n"
          "progress = false\n");
}

TEST_F(Rerun, EarlierPlotsGoAndOtherFilesStay) {
    write_event_and_soft();
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

// The run directory's config.toml runs again from anywhere (docs/config.md): a relative
// [initial] file is written there as the absolute path it named, the rest kept as it was.
TEST_F(Rerun, RecordedConfigRerunsFromAnotherDirectory) {
    std::filesystem::create_directories(dir / "cfg");
    std::filesystem::create_directories(dir / "elsewhere");
    const CliResult init =
        run_pedesis("init random --phi 0.1 --L 12 --rcut 1.0 -o cfg/init.json", dir, 60);
    ASSERT_EQ(init.exit_code, 0) << init.output;
    const std::string soft =
        "dimension = 2\ndynamics = \"brownian\"\nseed = 4\n[initial]\nfile = \"init.json\" # "
        "my start\n[[force]]\nname = \"harmonic\"\nk = 10.0\n[[integrator]]\nname = "
        "\"brownian\"\nT = 0.1\ngamma = 1.0\n[run]\nsteps = 200\ndt = 0.001\n[output]\n"
        "progress = false\nformats = []\n";
    write("cfg/soft.toml", soft);
    for (const std::string set : {"", " --set run.steps=60"}) {
        ASSERT_EQ(run_pedesis("run cfg/soft.toml --out runs/x" + set, dir, 60).exit_code, 0);
        const std::string recorded = read("runs/x/config.toml");
        const std::string absolute = (dir / "cfg" / "init.json").string();
        EXPECT_NE(recorded.find("file = \"" + absolute + "\" # my start\n"), std::string::npos)
            << recorded;
        if (set.empty()) { // all else is the file's text
            EXPECT_EQ(recorded.substr(0, recorded.find("file = ")) +
                          recorded.substr(recorded.find(" # my start")),
                      soft.substr(0, soft.find("file = ")) + soft.substr(soft.find(" # my start")));
        }
        const CliResult again =
            run_pedesis("run ../runs/x/config.toml --out x2", dir / "elsewhere", 60);
        ASSERT_EQ(again.exit_code, 0) << set << "\n" << again.output;
        const auto first = nlohmann::json::parse(read("runs/x/summary.json"));
        const auto second = nlohmann::json::parse(read("elsewhere/x2/summary.json"));
        EXPECT_EQ(first["final"], second["final"]) << set;
        EXPECT_EQ(first["steps"], set.empty() ? 200 : 60);
    }
}

TEST_F(Rerun, RestartWhoseStopCameFromASetNamesIt) {
    write("two.toml", small_config());
    ASSERT_EQ(run_pedesis("run two.toml --out two", dir, 60).exit_code, 0);
    const CliResult r = run_pedesis(
        "run two.toml --restart two/checkpoint.bin --set run.time=1.5 --out again", dir, 60);
    EXPECT_EQ(r.exit_code, 2) << r.output;
    EXPECT_NE(r.output.find("already meets the stop condition (time, from --set run.time=1.5); "
                            "raise it (--set run.time=...) to continue"),
              std::string::npos)
        << r.output;
}

// A checkpoint of another engine is named as such, with the engine this config runs.
TEST_F(Rerun, CheckpointOfAnotherEngineNamesBothEngines) {
    write_event_and_soft();
    write("stepped.toml", "dynamics = \"stepped\"\n" + small_config() + "[stepped]\ndt = 0.01\n");
    const std::map<std::string, std::string> engine{
        {"event", "the event engine (dynamics = \"event\")"},
        {"soft", "the soft engine (dynamics = \"brownian\", \"langevin\" or \"nve\")"},
        {"stepped", "the stepped engine (dynamics = \"stepped\")"}};
    for (const auto& [name, words] : engine) {
        const CliResult r = run_pedesis("run " + name + ".toml --out " + name, dir, 60);
        ASSERT_EQ(r.exit_code, 0) << name << "\n" << r.output;
    }
    for (const auto& [config, runs] : engine)
        for (const auto& [checkpoint, its] : engine) {
            if (config == checkpoint) continue;
            const CliResult r = run_pedesis("run " + config + ".toml --restart " + checkpoint +
                                                "/checkpoint.bin --out x",
                                            dir, 60);
            EXPECT_EQ(r.exit_code, 2) << r.output;
            EXPECT_NE(r.output.find(checkpoint + "/checkpoint.bin: a checkpoint of " + its +
                                    ", and this config runs " + runs),
                      std::string::npos)
                << config << " <- " << checkpoint << ": " << r.output;
        }
}

} // namespace
