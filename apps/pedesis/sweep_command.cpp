#include "sweep_command.hpp"

#include "mpi_world.hpp"
#include "set_option.hpp"
#include "thread_choice.hpp"

#include "pedesis/core/error.hpp"
#include "pedesis/core/interrupt.hpp"
#include "pedesis/run/sweep.hpp"

#include <fmt/format.h>

#include <chrono>
#include <csignal>
#include <cstdlib>
#include <cstring>
#include <iostream>
#include <memory>

namespace pedesis::cli {

namespace {

struct SweepArgs {
    std::string file;
    std::string out;
    std::string shard; // "I/N"
    int threads = 0;
    bool list = false;
    bool resume = false;
    std::vector<std::string> sets; // --set KEY=VALUE
};

struct Shard {
    std::size_t index = 0, count = 1;
};

Shard parse_shard(const std::string& text) {
    if (text.empty()) return {};
    const auto slash = text.find('/');
    try {
        if (slash != std::string::npos) {
            std::size_t used = 0;
            const auto i = std::stoul(text.substr(0, slash), &used);
            std::size_t used_n = 0;
            const auto n = std::stoul(text.substr(slash + 1), &used_n);
            if (used == slash && used_n == text.size() - slash - 1 && n > 0 && i < n) return {i, n};
        }
    } catch (const std::exception&) {
    }
    throw InputError("--shard " + text +
                     ": expected I/N with 0 <= I < N (for a job array of N "
                     "tasks: --shard $SLURM_ARRAY_TASK_ID/$SLURM_ARRAY_TASK_COUNT)");
}

std::string point_label(const Sweep& s, const SweepPoint& p) {
    std::string label = p.name + " (";
    for (std::size_t k = 0; k < s.keys.size(); ++k)
        label += fmt::format("{}{} = {}", k ? ", " : "", s.keys[k], p.values[k]);
    return label + ")";
}

void run_sweep(const SweepArgs& a) {
    MpiWorld& world = MpiWorld::get();
    const Shard shard = parse_shard(a.shard);
    const Sweep sweep = load_sweep(
        a.file, a.out.empty() ? std::nullopt : std::optional<std::filesystem::path>(a.out), a.sets);
    const bool talk = world.rank() == 0;
    if (a.list) {
        if (talk)
            for (const SweepPoint& p : sweep.points)
                std::cout << fmt::format("{}{}\n", point_label(sweep, p),
                                         point_done(p) ? " done" : "");
        return;
    }
    // several processes on one machine: one thread each, unless the user chose
    std::optional<int> threads;
    if (a.threads > 0)
        threads = a.threads;
    else if (world.size() > 1 && !std::getenv("OMP_NUM_THREADS"))
        threads = 1;
    choose_threads(threads, talk ? std::cout : std::cerr);

    // this shard's points, dealt round-robin among the processes
    std::vector<const SweepPoint*> mine;
    std::size_t in_shard = 0;
    for (const SweepPoint& p : sweep.points) {
        if (p.index % shard.count != shard.index) continue;
        if (in_shard++ % static_cast<std::size_t>(world.size()) ==
            static_cast<std::size_t>(world.rank()))
            mine.push_back(&p);
    }
    if (talk)
        std::cout << fmt::format(
            "pedesis sweep: {} points of {} in {}, on {} process{}{}\n", sweep.points.size(),
            sweep.base.string(), sweep.out.string(), world.size(), world.size() > 1 ? "es" : "",
            shard.count > 1 ? fmt::format(", shard {}/{}", shard.index, shard.count) : "");
    std::cout.flush();

    // Between points and in their runs a signal stops the sweep cleanly (its table
    // written); in the set-up of a point (make_run) it ends the process at once.
    InterruptGuard guard(OutsideCleanStops::end_process);
    const CleanStopWindow window;
    int failed = 0;
    for (const SweepPoint* p : mine) {
        if (point_done(*p)) {
            std::cout << fmt::format("  {} already done\n", point_label(sweep, *p));
            continue;
        }
        const auto start = std::chrono::steady_clock::now();
        const PointOutcome outcome = run_point(*p, std::cerr, a.resume);
        const double seconds =
            std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
        if (outcome == PointOutcome::failed) failed = 1;
        if (outcome == PointOutcome::interrupted || guard.signal() != 0) break;
        std::cout << fmt::format("  {} {} in {:.3g} s{}\n", point_label(sweep, *p),
                                 outcome == PointOutcome::done ? "done" : "failed", seconds,
                                 world.size() > 1 ? fmt::format(" (process {})", world.rank())
                                                  : "");
        std::cout.flush();
    }
    if (guard.signal() != 0) {
        // no collective step now: the other processes may be stopping or gone
        write_sweep_table(sweep);
        const int sig = guard.signal();
        const bool checkpoint_signal = sig == SIGTERM || sig == SIGUSR1;
        std::cout << fmt::format("pedesis sweep: interrupted by signal {}; run the same command "
                                 "with --resume to go on (done points are skipped, the "
                                 "interrupted one continues from its checkpoint){}\n",
                                 sig,
                                 checkpoint_signal ? fmt::format("; exit code {}: checkpointed, "
                                                                 "resume me",
                                                                 exit_checkpointed)
                                                   : "");
        std::cout.flush();
        if (checkpoint_signal) throw SilentExit{exit_checkpointed};
        guard.reraise();
    }
    world.barrier();
    failed = world.max(failed);
    if (talk) {
        write_sweep_table(sweep);
        std::size_t done = 0;
        for (const SweepPoint& p : sweep.points) done += point_done(p) ? 1 : 0;
        std::cout << fmt::format("pedesis sweep: {} of {} points done; table {}\n", done,
                                 sweep.points.size(), (sweep.out / "sweep.csv").string());
    }
    if (failed) {
        if (!talk) throw SilentExit{exit_run_error};
        throw RunError("a point of the sweep failed (its message is in its logs/*.failed file); "
                       "the other points ran");
    }
}

} // namespace

void add_sweep_command(CLI::App& app) {
    auto a = std::make_shared<SweepArgs>();
    auto* cmd = app.add_subcommand(
        "sweep", "Run a parameter sweep: a base config and keys to vary (docs/config.md); "
                 "under mpirun the points are shared among the processes");
    cmd->add_option("sweep", a->file, "Sweep file (TOML)")->required();
    cmd->add_option("--out", a->out, "Sweep directory (default: the file's out, or runs/<name>)");
    cmd->add_option("--shard", a->shard,
                    "Run only the points I, I+N, I+2N, ... (I/N: one task of a job array)");
    cmd->add_option("--threads", a->threads,
                    "OpenMP threads per run (default: as pedesis run; "
                    "1 per process under mpirun)")
        ->check(CLI::Range(1, 1024));
    cmd->add_flag("--list", a->list, "Print the points and which are done, and exit");
    cmd->add_flag("--resume", a->resume,
                  "Continue an interrupted point in place from its checkpoint (without it, "
                  "an unfinished point runs again from its start)");
    add_set_option(*cmd, a->sets, "the base config of every point");
    cmd->callback([a] { run_sweep(*a); });
}

} // namespace pedesis::cli
