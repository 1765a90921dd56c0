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
                   "order, structure, bond_order, clusters)");
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
    const CliResult version = run_pedesis("--version", dir, 60);
    EXPECT_EQ(version.exit_code, 0) << version.output;
}

} // namespace
