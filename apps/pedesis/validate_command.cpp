// `pedesis validate [--quick] [--out DIR] [--only CASES] [--jobs N] [--list]`
// (docs/validation.md). The suite is the Python package's pedesis.validate: it runs this
// very binary (PEDESIS_BIN) on each case's configs and compares what it measures with
// theory. Exit status: 0 when every case passes, 1 when one fails, 2 for bad arguments.
#include "validate_command.hpp"
#include "mpi_world.hpp"
#include "python_module.hpp"

#include "pedesis/core/error.hpp"

#include <fmt/core.h>

#include <filesystem>
#include <memory>
#include <string>
#include <vector>

namespace pedesis::cli {

namespace {

struct ValidateArgs {
    bool quick = false;
    bool list = false;
    std::string out;
    std::string only;
    int jobs = 0;
};

void validate(const ValidateArgs& a) {
    std::vector<std::string> args;
    if (a.quick) args.emplace_back("--quick");
    if (a.list) args.emplace_back("--list");
    if (!a.out.empty()) args.insert(args.end(), {"--out", a.out});
    if (!a.only.empty()) args.insert(args.end(), {"--only", a.only});
    if (a.jobs > 0) args.insert(args.end(), {"--jobs", std::to_string(a.jobs)});
    std::error_code ec;
    const auto self = std::filesystem::read_symlink("/proc/self/exe", ec);
    if (ec) throw InputError(fmt::format("validate: cannot find this binary: {}", ec.message()));
    const int code =
        run_python_module("validate", "validate", args, {"PEDESIS_BIN=" + self.string()});
    // the module printed its table or its one-line message
    if (code != 0) throw SilentExit{code};
}

} // namespace

void add_validate_command(CLI::App& app) {
    auto a = std::make_shared<ValidateArgs>();
    auto* cmd = app.add_subcommand(
        "validate", "Check pedesis's physics on this machine against theory and published data "
                    "(docs/validation.md)");
    cmd->add_flag("--quick", a->quick, "Short runs: under 2 minutes on 2 cores (full: under 30)");
    cmd->add_option("--out", a->out,
                    "Report directory (default runs/validate, or runs/validate_quick)");
    cmd->add_option("--only", a->only, "Comma-separated case names (see --list)");
    cmd->add_option("--jobs", a->jobs, "Cases side by side, one core each (default: every core)")
        ->check(CLI::Range(1, 4096));
    cmd->add_flag("--list", a->list, "List the cases and exit");
    cmd->callback([a] { validate(*a); });
}

} // namespace pedesis::cli
