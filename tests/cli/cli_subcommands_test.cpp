// A misspelt or missing subcommand, at any level of the command line, gets one message
// that names it and lists the known ones, and exit code 2 (CLI11 alone says "A subcommand
// is required" for both).
#include "cli_support.hpp"

using namespace pedesis::test;

namespace {

class Subcommands : public ScratchDir {
  protected:
    void expect_message(const std::string& args, const std::string& message) {
        const CliResult r = run_pedesis(args, dir, 60);
        EXPECT_EQ(r.exit_code, 2) << args << "\n" << r.output;
        EXPECT_NE(r.output.find("pedesis: error: " + message), std::string::npos)
            << "missing '" << message << "' in: " << r.output;
        EXPECT_EQ(r.output.find("A subcommand is required"), std::string::npos) << r.output;
    }
};

TEST_F(Subcommands, UnknownOnesAreNamedWithTheKnownOnes) {
    expect_message("analyze struct RUN",
                   "unknown subcommand 'struct' of 'pedesis analyze' (known: speed, thermo, msd, "
                   "order, structure, bond_order, clusters, transport)");
    expect_message("runn cfg.toml", "unknown subcommand 'runn' of 'pedesis' (known: run, sweep, "
                                    "init, analyze, ");
    expect_message("bench evnt", "unknown subcommand 'evnt' of 'pedesis bench' (known: event, ");
    expect_message("init randm --phi 0.1", "unknown subcommand 'randm' of 'pedesis init' "
                                           "(known: random)");
}

TEST_F(Subcommands, MissingOnesListTheKnownOnes) {
    expect_message("", "'pedesis' needs a subcommand (known: run, sweep, ");
    expect_message("analyze", "'pedesis analyze' needs a subcommand (known: speed, thermo, ");
    expect_message("bench", "'pedesis bench' needs a subcommand (known: event, ");
}

TEST_F(Subcommands, ParseErrorsAreOneLineAndSuggestTheOption) {
    // the whole output is the one line (CLI11 alone adds "Run with --help ...")
    const auto expect_only = [&](const std::string& args, const std::string& line) {
        const CliResult r = run_pedesis(args, dir, 60);
        EXPECT_EQ(r.exit_code, 2) << args << "\n" << r.output;
        EXPECT_EQ(r.output, "pedesis: error: " + line + "\n") << args;
    };
    expect_only("run", "pedesis run: config is required (pedesis run --help lists what it takes)");
    expect_only("run cfg.toml --thread 2",
                "unknown option '--thread' of 'pedesis run' (did you mean --threads?)");
    expect_only("run cfg.toml --ot x",
                "unknown option '--ot' of 'pedesis run' (did you mean --out?)");
    expect_only("analyze speed RUN --bogus-option",
                "unknown option '--bogus-option' of 'pedesis analyze speed' (its options: "
                "--help, --out)");
    expect_only("run --threads 0 cfg.toml",
                "pedesis run: --threads: Value 0 not in range 1 to 1024 (pedesis run --help "
                "lists what it takes)");
}

TEST_F(Subcommands, ADirectoryForAConfigIsNamed) {
    std::filesystem::create_directories(dir / "runs/lj");
    std::filesystem::create_directories(dir / "empty");
    write("runs/lj/config.toml", small_config());
    const auto expect_error = [&](const std::string& args, const std::string& message) {
        const CliResult r = run_pedesis(args, dir, 60);
        EXPECT_EQ(r.exit_code, 2) << args << "\n" << r.output;
        EXPECT_NE(r.output.find("pedesis: error: " + message), std::string::npos)
            << "missing '" << message << "' in: " << r.output;
        EXPECT_EQ(r.output.find("[box]"), std::string::npos) << r.output;
    };
    const std::string holds = "runs/lj: is a directory, not a config file (it holds the config "
                              "of its run: give runs/lj/config.toml)";
    expect_error("run runs/lj", holds);
    expect_error("run runs/lj --set run.time=1", holds);
    expect_error("sweep runs/lj", holds);
    expect_error("run empty", "empty: is a directory, not a config file\n");
}

TEST_F(Subcommands, OtherFaultsKeepTheirOwnMessage) {
    // a known subcommand with a bad argument is not a subcommand fault
    const CliResult extra = run_pedesis("run a.toml b.toml", dir, 60);
    EXPECT_EQ(extra.exit_code, 2) << extra.output;
    EXPECT_NE(extra.output.find("b.toml"), std::string::npos) << extra.output;
    EXPECT_EQ(extra.output.find("subcommand"), std::string::npos) << extra.output;
    const CliResult missing = run_pedesis("analyze speed", dir, 60);
    EXPECT_EQ(missing.exit_code, 2) << missing.output;
    EXPECT_NE(missing.output.find("run_dir is required"), std::string::npos) << missing.output;
    const CliResult help = run_pedesis("analyze --help", dir, 60);
    EXPECT_EQ(help.exit_code, 0) << help.output;
    EXPECT_NE(help.output.find("clusters"), std::string::npos) << help.output;
    EXPECT_NE(help.output.find("transport"), std::string::npos) << help.output;
    const CliResult version = run_pedesis("--version", dir, 60);
    EXPECT_EQ(version.exit_code, 0) << version.output;
}

} // namespace
