// `pedesis analyze speed|thermo|msd|order RUN_DIR [--out FILE]` (docs/analyze.md).
// The plots are drawn by the Python package's pedesis.analyze (python3 -m pedesis.analyze
// KIND RUN_DIR, matplotlib) run with Debian's Python; this side checks the run directory
// first, so the common mistakes get the project's one-line message and exit code 2
// without starting Python, and then passes the module's exit status on.
#include "analyze_command.hpp"

#include "pedesis/core/error.hpp"
#include "pedesis/core/interrupt.hpp"

#include <fmt/core.h>

#include <array>
#include <cerrno>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <iostream>
#include <memory>
#include <stdexcept>
#include <string>
#include <vector>

#include <csignal>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

extern char** environ;

namespace pedesis::cli {

namespace {

namespace fs = std::filesystem;

struct Kind {
    const char* name;
    const char* help;
    bool reads_log;    // log.csv
    bool reads_frames; // snapshots/frame_*.json, trajectory.xyz or trajectory.gsd
};

constexpr std::array<Kind, 4> kinds{{
    {"speed",
     "Speed distribution of the final frame per species over Rayleigh (2D) / Maxwell (3D) at "
     "the measured temperature; prints the Kolmogorov-Smirnov distance (speed_distribution.png)",
     false, true},
    {"thermo",
     "Energies, temperatures and pressures of log.csv against time (and collisions per "
     "particle) (thermo.png)",
     true, false},
    {"msd", "Mean squared displacement of a soft run against the free-ABP curve (msd.png)", true,
     false},
    {"order", "Polar order parameter of a soft run against time (order.png)", true, false},
}};

struct AnalyzeArgs {
    std::string run_dir;
    std::string out;
};

// An environment variable overrides the path built in at compile time, so an installed
// binary or a moved source tree still finds its interpreter and package.
std::string configured_path(const char* variable, const char* built_in) {
    const char* v = std::getenv(variable);
    return v && *v ? std::string(v) : std::string(built_in);
}

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
    if (kind.reads_frames && !has_json_frame(dir / "snapshots") &&
        !fs::is_regular_file(dir / "trajectory.xyz", ec) &&
        !fs::is_regular_file(dir / "trajectory.gsd", ec))
        throw InputError(fmt::format(
            "{}: no frames to take velocities from (snapshots/frame_*.json, trajectory.xyz or "
            "trajectory.gsd); add \"json\" to [output] formats and run again",
            dir.string()));
}

std::string python_interpreter() {
    const std::string python = configured_path("PEDESIS_PYTHON", PEDESIS_ANALYZE_PYTHON);
    if (::access(python.c_str(), X_OK) != 0)
        throw InputError(fmt::format(
            "analyze: no Python interpreter at {}: the plots need Debian's python3 with "
            "python3-matplotlib (apt-get install python3-matplotlib), or set PEDESIS_PYTHON",
            python));
    return python;
}

// The folder holding the pedesis package (build/python; the source tree's python/ in a
// build without the compiled module, whose pure-Python plots work all the same).
std::string package_path() {
    const std::string dir = configured_path("PEDESIS_PYTHONPATH", PEDESIS_ANALYZE_PYTHONPATH);
    std::error_code ec;
    if (!fs::is_regular_file(fs::path(dir) / "pedesis" / "analyze" / "__main__.py", ec))
        throw InputError(fmt::format(
            "analyze: the pedesis Python package is not in {} (no pedesis/analyze there); set "
            "PEDESIS_PYTHONPATH to the build's python folder",
            dir));
    return dir;
}

// This process's environment with `dir` first on PYTHONPATH (a user's own entries stay).
std::vector<std::string> environment_with_package(const std::string& dir) {
    std::vector<std::string> env;
    std::string path = "PYTHONPATH=" + dir;
    for (char** e = environ; *e; ++e) {
        const std::string entry(*e);
        if (entry.rfind("PYTHONPATH=", 0) == 0) {
            if (entry.size() > 11) path += ":" + entry.substr(11);
        } else {
            env.push_back(entry);
        }
    }
    env.push_back(path);
    return env;
}

// Runs argv[0] with the arguments, sharing stdout and stderr, and returns its wait status.
// A signal to pedesis (SIGINT, SIGTERM, SIGHUP) is passed on to the script, which ends
// without leaving its figure half written (pedesis/analyze/plots/figure.py writes, then
// renames); once it has ended, pedesis ends by the same signal: no orphan goes on.
int run_process(const std::vector<std::string>& args, const std::vector<std::string>& env,
                const InterruptGuard& guard) {
    std::vector<char*> argv, envp;
    for (const std::string& a : args) argv.push_back(const_cast<char*>(a.c_str()));
    argv.push_back(nullptr);
    for (const std::string& e : env) envp.push_back(const_cast<char*>(e.c_str()));
    envp.push_back(nullptr);
    // what this process printed must come out before the child's lines
    std::cout.flush();
    std::fflush(stdout);
    pid_t pid = 0;
    const int err = ::posix_spawn(&pid, argv[0], nullptr, nullptr, argv.data(), envp.data());
    if (err != 0)
        throw InputError(fmt::format("analyze: cannot start {}: {}", args[0], std::strerror(err)));
    int status = 0;
    bool passed_on = false;
    // polled, so that a signal between two looks cannot be missed by a blocking wait
    for (;;) {
        const pid_t done = ::waitpid(pid, &status, WNOHANG);
        if (done == pid) return status;
        if (done < 0 && errno != EINTR)
            throw std::runtime_error(
                fmt::format("analyze: waiting for {}: {}", args[0], std::strerror(errno)));
        if (guard.signal() != 0 && !passed_on) {
            ::kill(pid, guard.signal());
            passed_on = true;
        }
        ::usleep(10000);
    }
}

void analyze(const Kind& kind, const AnalyzeArgs& a) {
    check_run_dir(a.run_dir, kind);
    const std::string package = package_path();
    std::vector<std::string> args{python_interpreter(),
                                  "-B", // no __pycache__ in the source tree
                                  "-m",
                                  "pedesis.analyze",
                                  kind.name,
                                  a.run_dir};
    if (!a.out.empty()) {
        args.push_back("--out");
        args.push_back(a.out);
    }
    InterruptGuard guard;
    const int status = run_process(args, environment_with_package(package), guard);
    if (guard.signal() != 0) guard.reraise();
    if (WIFEXITED(status)) {
        const int code = WEXITSTATUS(status);
        if (code == 0) return;
        // the script has printed its one-line message; a silent ParseError carries the code
        if (code == exit_input_error) throw CLI::RuntimeError(exit_input_error);
        throw std::runtime_error(fmt::format(
            "analyze {}: python3 -m pedesis.analyze failed with exit status {}", kind.name, code));
    }
    throw std::runtime_error(fmt::format("analyze {}: python3 -m pedesis.analyze was killed by "
                                         "signal {}",
                                         kind.name, WIFSIGNALED(status) ? WTERMSIG(status) : -1));
}

} // namespace

void add_analyze_command(CLI::App& app) {
    auto* cmd = app.add_subcommand(
        "analyze", "Plot a run directory's outputs with matplotlib (docs/analyze.md)");
    cmd->require_subcommand(1);
    for (const Kind& kind : kinds) {
        auto a = std::make_shared<AnalyzeArgs>();
        auto* sub = cmd->add_subcommand(kind.name, kind.help);
        sub->add_option("run_dir", a->run_dir, "Run directory (written by pedesis run)")
            ->required();
        sub->add_option("--out", a->out,
                        "Output file, .png, .pdf or .svg (default: inside the run directory)");
        sub->callback([&kind, a] { analyze(kind, *a); });
    }
}

} // namespace pedesis::cli
