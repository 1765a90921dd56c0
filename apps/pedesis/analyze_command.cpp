// `pedesis analyze KIND RUN_DIR [--out FILE]`, KIND one of the kinds below (docs/analyze.md).
// The plots are drawn by the Python package's pedesis.analyze (python3 -m pedesis.analyze
// KIND RUN_DIR, matplotlib) run with Debian's Python; this side checks the run directory
// first, so the common mistakes get the project's one-line message and exit code 2
// without starting Python, and then passes the module's exit status on.
#include "analyze_command.hpp"
#include "mpi_world.hpp"
#include "python_module.hpp"

#include "pedesis/core/error.hpp"
#include "pedesis/run/analysis_outputs.hpp"

#include <fmt/core.h>

#include <array>
#include <filesystem>
#include <memory>
#include <stdexcept>
#include <string>
#include <string_view>
#include <vector>

namespace pedesis::cli {

namespace {

namespace fs = std::filesystem;

enum class Frames {
    none,
    any, // snapshots/frame_*.json, trajectory.xyz or trajectory.gsd
    gsd, // trajectory.gsd (read through the gsd package)
};

struct Kind {
    const char* name;
    const char* help;
    bool reads_log; // log.csv
    Frames frames;
    bool has_options; // options of its own, passed on to the module to check
};

constexpr std::array<Kind, 8> kinds{{
    {"speed",
     "Speed distribution of the final frame per species over Rayleigh (2D) / Maxwell (3D) at "
     "the measured temperature; prints the Kolmogorov-Smirnov distance",
     false, Frames::any, false},
    {"thermo",
     "Energies, temperatures and pressures of log.csv against time (and collisions per "
     "particle)",
     true, Frames::none, false},
    {"msd",
     "Mean squared displacement of log.csv; a brownian or langevin run against the free-ABP "
     "curve",
     true, Frames::none, false},
    {"order", "Polar order parameter of a soft run against time", true, Frames::none, false},
    {"structure", "g(r) over the last frames and S(q), direct and from g(r), of trajectory.gsd",
     false, Frames::gsd, false},
    {"bond_order",
     "Voronoi-weighted hexatic order psi6 (2D) or Steinhardt q4, q6 (3D) against time", false,
     Frames::gsd, false},
    {"clusters",
     "Local area fraction histogram (phase separation: two peaks), largest dense cluster "
     "against time and cluster sizes; --cell, --contact, --min-neighbours",
     false, Frames::gsd, true},
    {"transport",
     "Running transport coefficients of [transport] (transport.csv) against the lag, with the "
     "fit window, the values and errors of summary.json and Enskog's",
     false, Frames::none, false},
}};

// Each kind's plot has its name in the one list a new run removes from its directory.
constexpr bool same_kinds_as_outputs() {
    if (kinds.size() != analysis_outputs.size()) return false;
    for (std::size_t k = 0; k < kinds.size(); ++k)
        if (std::string_view(kinds[k].name) != analysis_outputs[k].kind) return false;
    return true;
}
static_assert(same_kinds_as_outputs(),
              "a kind of pedesis analyze without its file in run/analysis_outputs.hpp");

const char* output_file(const Kind& kind) {
    return analysis_outputs[static_cast<std::size_t>(&kind - kinds.data())].file;
}

struct AnalyzeArgs {
    std::string run_dir;
    std::string out;
    std::vector<std::string> options; // a kind's own, for the module to check
};

void require_file(const fs::path& file, const std::string& hint) {
    std::error_code ec;
    if (fs::is_regular_file(file, ec)) return;
    if (fs::exists(file, ec))
        throw InputError(fmt::format("{}: not a regular file{}", file.string(), hint));
    fs::path part = file;
    part += ".part";
    if (fs::exists(part, ec))
        throw InputError(
            fmt::format("{}: missing ({} exists: the run is still going, or was killed)",
                        file.string(), part.filename().string()));
    throw InputError(fmt::format("{}: missing{}", file.string(), hint));
}

bool has_json_frame(const fs::path& snapshots) {
    std::error_code ec;
    if (!fs::is_directory(snapshots, ec)) return false;
    for (const auto& entry : fs::directory_iterator(snapshots, ec)) {
        const std::string name = entry.path().filename().string();
        if (name.starts_with("frame_") && name.ends_with(".json")) return true;
    }
    return false;
}

// The files each kind needs exist; their contents are the scripts' to judge.
void check_run_dir(const fs::path& dir, const Kind& kind) {
    std::error_code ec;
    if (!fs::exists(dir, ec))
        throw InputError(fmt::format("{}: no such run directory", dir.string()));
    if (!fs::is_directory(dir, ec))
        throw InputError(fmt::format("{}: not a directory (give the run directory)", dir.string()));
    require_file(dir / "config.toml",
                 fmt::format(" (is {} a pedesis run directory?)", dir.string()));
    if (kind.reads_log) require_file(dir / "log.csv", "");
    if (kind.frames == Frames::gsd)
        require_file(dir / "trajectory.gsd", " (add \"gsd\" to [output] formats and run again)");
    if (kind.frames == Frames::any && !has_json_frame(dir / "snapshots") &&
        !fs::is_regular_file(dir / "trajectory.xyz", ec) &&
        !fs::is_regular_file(dir / "trajectory.gsd", ec))
        throw InputError(fmt::format(
            "{}: no frames to take velocities from (snapshots/frame_*.json, trajectory.xyz or "
            "trajectory.gsd); add \"json\" to [output] formats and run again",
            dir.string()));
}

void analyze(const Kind& kind, const AnalyzeArgs& a) {
    check_run_dir(a.run_dir, kind);
    const std::string out =
        a.out.empty() ? (fs::path(a.run_dir) / output_file(kind)).string() : a.out;
    std::vector<std::string> args{kind.name, a.run_dir, "--out", out};
    args.insert(args.end(), a.options.begin(), a.options.end());
    const int code = run_python_module("analyze", "analyze", args);
    if (code == 0) return;
    // the module has printed its one-line message: only the code is left to pass on
    if (code == exit_input_error) throw SilentExit{exit_input_error};
    throw std::runtime_error(fmt::format(
        "analyze {}: python3 -m pedesis.analyze failed with exit status {}", kind.name, code));
}

} // namespace

void add_analyze_command(CLI::App& app) {
    auto* cmd = app.add_subcommand(
        "analyze", "Plot a run directory's outputs with matplotlib (docs/analyze.md)");
    cmd->require_subcommand(1);
    for (const Kind& kind : kinds) {
        auto a = std::make_shared<AnalyzeArgs>();
        auto* sub =
            cmd->add_subcommand(kind.name, fmt::format("{} ({})", kind.help, output_file(kind)));
        sub->add_option("run_dir", a->run_dir, "Run directory (written by pedesis run)")
            ->required();
        sub->add_option("--out", a->out,
                        "Output file, .png, .pdf or .svg (default: inside the run directory)");
        if (kind.has_options) sub->allow_extras();
        sub->callback([&kind, a, sub] {
            a->options = sub->remaining();
            analyze(kind, *a);
        });
    }
}

} // namespace pedesis::cli
