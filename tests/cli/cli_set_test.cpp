// `--set KEY=VALUE` of pedesis run and pedesis sweep: any key of the config by its dotted
// path, the value typed as in TOML and checked as the file is, messages naming the --set
// (or the file's own line, unmoved), and the run directory's config.toml the config as run.
#include "cli_support.hpp"

#include <nlohmann/json.hpp>

using namespace pedesis::test;

namespace {

// A small Brownian run; `extra` goes after [run] (an [output] table, say).
std::string soft(const std::string& extra = "[output]\nprogress = false\nformats = []\nlog_every = "
                                            "100\n") {
    return "dimension = 2\ndynamics = \"brownian\"\n[box]\nlength = 12\n[[species]]\nname = "
           "\"A\"\ncount = 20\nradius = 0.5\n[[force]]\nname = \"harmonic\"\nk = 10.0\n"
           "[[integrator]]\nname = \"brownian\"\nT = 0.1\ngamma = 1.0\n[run]\nsteps = 200\n"
           "dt = 0.001\n" +
           extra;
}

class SetOption : public ScratchDir {
  protected:
    nlohmann::json summary(const std::string& out) {
        return nlohmann::json::parse(read(out + "/summary.json"));
    }
    void expect_refused(const std::string& sets, std::initializer_list<std::string> fragments) {
        const CliResult r = run_pedesis("run run.toml --out out " + sets, dir, 60);
        EXPECT_EQ(r.exit_code, 2) << sets << "\n" << r.output;
        for (const auto& f : fragments)
            EXPECT_NE(r.output.find(f), std::string::npos)
                << "missing '" << f << "' in: " << r.output;
        EXPECT_EQ(r.output.find("internal error"), std::string::npos) << r.output;
        EXPECT_FALSE(std::filesystem::exists(dir / "out" / "summary.json")) << sets;
    }
};

TEST_F(SetOption, ChangesTheRunAndIsRecordedInItsConfig) {
    write("run.toml", soft());
    const CliResult r = run_pedesis(
        "run run.toml --set run.steps=30 --out out --set output.log_every=10 --set seed=7", dir,
        60);
    ASSERT_EQ(r.exit_code, 0) << r.output;
    EXPECT_EQ(summary("out")["steps"], 30);
    const CsvColumns log = csv_columns(read("out/log.csv"));
    EXPECT_EQ(log.numbers("step"), (std::vector<double>{0, 10, 20, 30}));
    // the copy in the run directory is the config as run: rerun, it gives the same run
    const std::string config = read("out/config.toml");
    EXPECT_EQ(config.rfind("# run.toml with --set run.steps=30 --set output.log_every=10 --set "
                           "seed=7\n",
                           0),
              0u)
        << config;
    EXPECT_NE(config.find("steps = 30\n"), std::string::npos) << config;
    EXPECT_NE(config.find("seed = 7\n"), std::string::npos) << config;
    ASSERT_EQ(run_pedesis("run out/config.toml --out again", dir, 60).exit_code, 0);
    EXPECT_EQ(read("again/log.csv"), read("out/log.csv"));
    // the file itself is untouched
    EXPECT_EQ(read("run.toml"), soft());
}

TEST_F(SetOption, MissingTablesAreCreated) {
    write("run.toml", soft(""));
    const CliResult r = run_pedesis(
        "run run.toml --out out --set output.progress=false --set 'output.formats=[\"xyz\"]' "
        "--set output.snapshot_every=100",
        dir, 60);
    ASSERT_EQ(r.exit_code, 0) << r.output;
    EXPECT_TRUE(std::filesystem::exists(dir / "out/trajectory.xyz"));
    EXPECT_FALSE(std::filesystem::exists(dir / "out/trajectory.gsd"));
    EXPECT_NE(read("out/config.toml").find("[output]\nprogress = false\n"), std::string::npos);
}

TEST_F(SetOption, ValuesAreTypedAsInToml) {
    write("run.toml", soft());
    expect_refused("--set run.steps=3.5", {"--set run.steps=3.5: key 'run.steps'"});
    expect_refused("--set dynamics=langevin",
                   {"--set dynamics=langevin: 'langevin' is not a TOML value; a string needs "
                    "quotes",
                    "--set 'dynamics=\"langevin\"'"});
    expect_refused("--set run.steps", {"--set run.steps: expected KEY=VALUE"});
    expect_refused("--set run.steps=[1,", {"--set run.steps=[1,: '[1,' is not a TOML value"});
    expect_refused("--set run.dt=-0.1", {"--set run.dt=-0.1: key 'run.dt'"});
    // a quoted string is a string
    const CliResult r =
        run_pedesis("run run.toml --out out --set 'dynamics=\"nve\"' --set run.steps=5", dir, 60);
    EXPECT_NE(r.output.find("nve"), std::string::npos) << r.output;
}

TEST_F(SetOption, BadKeysAreRefused) {
    write("run.toml", soft());
    expect_refused("--set run.stepz=10", {"--set run.stepz=10: unknown key 'run.stepz'"});
    expect_refused("--set force.lj.k=1.0",
                   {"--set force.lj.k=1.0: run.toml has no [[force]] named 'lj' (it has: "
                    "harmonic; or give an index)"});
    expect_refused("--set run=3", {"'run' is a table of run.toml"});
    expect_refused("--set run.steps=1 --set run.steps=2", {"that key is set twice"});
    expect_refused("--set =1", {"expected KEY=VALUE"});
}

TEST_F(SetOption, MessagesSayWhatTheValueOrIndexNeeds) {
    write("run.toml", soft());
    // an index past the end is out of range, not a missing name
    expect_refused("--set species.3.count=10",
                   {"--set species.3.count=10: index 3 of [[species]] is out of range (run.toml "
                    "has 1 entry: 0..0)"});
    // a bare word where the file has a number or a boolean: quotes would not help
    expect_refused("--set force.harmonic.k=abc",
                   {"--set force.harmonic.k=abc: 'abc' is not a number, and 'force.harmonic.k' "
                    "takes one (run.toml:11:5 gives a number)"});
    expect_refused("--set output.progress=yes",
                   {"'yes' is neither true nor false, which 'output.progress' takes"});
    expect_refused("--set output.progress=True",
                   {"'True' is not a TOML value; TOML's booleans are lower case: --set "
                    "output.progress=true"});
    const CliResult word =
        run_pedesis("run run.toml --out out --set force.harmonic.k=abc", dir, 60);
    EXPECT_EQ(word.output.find("needs quotes"), std::string::npos) << word.output;
    // a key the --set adds that clashes with the file's: both are named
    expect_refused("--set 'box.lengths=[12.0, 12.0]'",
                   {"run.toml:4:10: key 'box.length': give either length or lengths, not both "
                    "(lengths is given by --set box.lengths=[12.0, 12.0])"});
}

TEST_F(SetOption, TheFileKeepsItsLineNumbers) {
    // seed is added at the top and device under [run]: the file's fault keeps its line
    write("run.toml", soft() + "[neighbor_list]\nskin = -1.0\n");
    expect_refused("--set seed=3 --set 'run.device=\"cpu\"'",
                   {"run.toml:24:8: key 'neighbor_list.skin'"});
    write("run.toml", soft());
    expect_refused("--set species.A.count=0 --set force.0.k=-1.0",
                   {"--set species.A.count=0: key 'species[0].count'"});
}

TEST_F(SetOption, SweepSetsTheBaseOfEveryPoint) {
    write("base.toml", soft());
    write("sweep.toml", "base = \"base.toml\"\n[vary]\nseed = [1, 2]\n");
    const CliResult r = run_pedesis("sweep sweep.toml --out sw --set run.steps=20", dir, 120);
    ASSERT_EQ(r.exit_code, 0) << r.output;
    for (const std::string point : {"point_000", "point_001"}) {
        EXPECT_EQ(summary("sw/" + point)["steps"], 20) << point;
        EXPECT_NE(read("sw/configs/" + point + ".toml").find("with --set run.steps=20"),
                  std::string::npos);
    }
    const CliResult bad = run_pedesis("sweep sweep.toml --out bad --set run.stepz=20", dir, 60);
    EXPECT_EQ(bad.exit_code, 2) << bad.output;
    EXPECT_NE(bad.output.find("unknown key 'run.stepz'"), std::string::npos) << bad.output;
}

} // namespace
