#include "run_command.hpp"

#include "mpi_communicator.hpp"
#include "mpi_world.hpp"
#include "pedesis/core/error.hpp"
#include "pedesis/core/interrupt.hpp"
#include "pedesis/observe/quantities.hpp"
#include "pedesis/run/resume.hpp"
#include "pedesis/run/run.hpp"
#include "pedesis/run/run_directory.hpp"
#include "pedesis/run/run_directory_lock.hpp"
#include "pedesis/run/steering.hpp"
#include "pedesis/setup/config_overrides.hpp"
#include "pedesis/setup/run_config.hpp"
#if PEDESIS_HAVE_GRAPHICS
#include "pedesis/view/view_server.hpp"
#endif
#include "set_option.hpp"
#include "thread_choice.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cstdlib>
#include <cstring>
#include <iostream>
#include <memory>
#include <random>
#include <sstream>
#include <unistd.h>

namespace pedesis::cli {

namespace {
struct RunArgs {
    std::string config;
    std::string out;
    std::string restart;
    bool resume = false;
    bool list_quantities = false;
    int threads = 0;    // 0: choose (thread_choice.hpp)
    std::string device; // empty: the config's [run] device
    bool view = false;
    int view_port = 8765;
    std::string steering;          // a record to replay
    std::vector<std::string> sets; // --set KEY=VALUE
    std::string precision;         // --precision: one more --set
};

// 128 random bits, in hex: the token a page must show to change a run.
[[maybe_unused]] std::string random_token() {
    std::random_device device;
    std::string token;
    for (int k = 0; k < 4; ++k) token += fmt::format("{:08x}", device());
    return token;
}

#if PEDESIS_HAVE_GRAPHICS
// `pedesis run --view`: the viewer's server on the run directory, serving for as long as
// this lives, with the token that lets its page change the run.
class LiveView {
  public:
    LiveView(const std::filesystem::path& dir, int port, SteeringDesk* desk) {
        view::ViewOptions o;
        o.run_dir = dir;
        o.port = port;
        o.wait_for_frames = true;
        if (desk) {
            token_ = random_token();
            o.steering = view::SteeringHooks{
                token_,
                [desk] {
                    std::vector<view::SteerableValue> out;
                    for (const SteerableParameter& p : desk->parameters())
                        out.push_back({p.name, p.value, p.min, p.max});
                    return out;
                },
                [desk](const std::string& p, double v) { return desk->request(p, v); }};
        }
        server_ = std::make_unique<view::ViewServer>(o);
        server_->start();
    }
    // with the token when the page may change the run
    std::string url() const { return server_->url() + (token_.empty() ? "" : "?token=" + token_); }

  private:
    std::string token_;
    std::unique_ptr<view::ViewServer> server_;
};
#else
// A build without the viewer (PEDESIS_GRAPHICS off) refuses --view.
class LiveView {
  public:
    LiveView(const std::filesystem::path&, int, SteeringDesk*) {
        throw InputError("--view: this pedesis was built without the viewer (PEDESIS_GRAPHICS)");
    }
    std::string url() const { return {}; }
};
#endif

// One line per quantity: name, unit, engines, meaning.
void print_quantities(std::ostream& out) {
    std::size_t width = 0;
    for (const QuantityInfo& q : quantity_catalogue()) width = std::max(width, std::strlen(q.name));
    out << fmt::format("{:<{}}  {:<16}  {:<30}  {}\n", "name", width, "unit", "engines", "meaning");
    for (const QuantityInfo& q : quantity_catalogue())
        out << fmt::format("{:<{}}  {:<16}  {:<30}  {}\n", q.name, width, q.unit, q.engines,
                           q.meaning);
}
} // namespace

void add_run_command(CLI::App& app) {
    auto a = std::make_shared<RunArgs>();
    auto* cmd =
        app.add_subcommand("run", "Run a simulation described by a TOML config (docs/config.md)");
    auto* config = cmd->add_option("config", a->config, "Config file");
    auto* list = cmd->add_flag("--list-quantities", a->list_quantities,
                               "Print every quantity log.csv can hold ([log] quantities) and exit");
    config->excludes(list);
    cmd->add_option("--threads", a->threads,
                    "OpenMP threads (default: the idle cores, or OMP_NUM_THREADS); results are "
                    "the same for any number")
        ->check(CLI::Range(1, 1024));
    cmd->add_option("--out", a->out, "Run directory (default: runs/<config name>)");
    cmd->add_option("--device", a->device,
                    "Where a soft-engine run steps: cpu or gpu (default: the config's [run] "
                    "device, else cpu; docs/gpu.md)")
        ->check(CLI::IsMember({"cpu", "gpu"}));
    cmd->add_option("--precision", a->precision,
                    "Pair math of a soft-engine run: double or mixed (float pair rows, double "
                    "integration); the same as --set precision=VALUE, recorded as one")
        ->check(CLI::IsMember({"double", "mixed"}));
    auto* restart = cmd->add_option("--restart", a->restart,
                                    "Continue exactly from a checkpoint.bin of an earlier run");
    cmd->add_flag("--resume", a->resume,
                  "Continue the unfinished run in --out in place from its newest checkpoint "
                  "(start it if there is none; nothing to do if it finished)")
        ->excludes(restart);
    cmd->add_flag("--view", a->view,
                  "Serve the run in the browser while it goes, and after it until Ctrl-C "
                  "(pedesis view; docs/view.md)");
    cmd->add_option("--view-port", a->view_port, "Port of --view (0: any free port)")
        ->check(CLI::Range(0, 65535));
    cmd->add_option("--steering", a->steering,
                    "Replay a steering.csv: apply its changes at their steps (docs/view.md)");
    add_set_option(*cmd, a->sets, "the config");
    cmd->callback([a] {
        if (a->list_quantities) {
            print_quantities(std::cout);
            return;
        }
        if (a->config.empty()) throw CLI::RequiredError("config");
        // (first: under mpirun, only process 0 may tell what is wrong with the config)
        const std::unique_ptr<Communicator> comm = world_communicator();
        if (!a->precision.empty()) a->sets.push_back("precision=\"" + a->precision + "\"");
        std::optional<ConfigWithSets> with_sets;
        if (!a->sets.empty()) with_sets.emplace(a->config, a->sets);
        const RunConfig config = with_sets ? with_sets->read() : load_run_config(a->config);
        // Under mpirun the soft engine divides the box among the processes; the hard
        // engines run on one (P copies would write one directory P times over).
        if (comm && !config.soft())
            throw InputError(fmt::format(
                "{}: the {} engine runs on one process, and mpirun started {}; start it without "
                "mpirun (threads: --threads), or run many configs with pedesis sweep",
                a->config, config.dynamics, comm->size()));
        RunOptions o;
        o.comm = comm.get();
        o.config_path = a->config;
        if (with_sets) {
            o.config_text = with_sets->text_as_run();
            o.set_keys = with_sets->set_keys();
        }
        o.out_dir = a->out.empty()
                        ? std::filesystem::path("runs") / std::filesystem::path(a->config).stem()
                        : std::filesystem::path(a->out);
        if (!a->restart.empty()) o.restart = a->restart;
        if (!a->device.empty()) o.device = a->device;
        if (a->resume && (a->view || !a->steering.empty()))
            throw InputError("--resume continues runs without steering; --view and --steering "
                             "cannot be given with it");
        // A signal during set-up ends the process at once (nothing there to close), and
        // removes the lock taken below first: caught from before the lock is taken.
        InterruptGuard guard(OutsideCleanStops::end_process);
        // one writer per run directory (process 0's lock speaks for an MPI run)
        std::unique_ptr<RunDirectoryLock> lock;
        on_process_zero(comm.get(), [&] { lock = std::make_unique<RunDirectoryLock>(o.out_dir); });
        // only process 0 talks; every process of an MPI run takes one thread unless told
        // otherwise (P processes of idle-core threads each would oversubscribe the cores)
        std::ostringstream unheard;
        std::ostream& console = comm && comm->rank() != 0 ? unheard : std::cout;
        std::optional<int> threads;
        if (a->threads > 0)
            threads = a->threads;
        else if (comm && !std::getenv("OMP_NUM_THREADS"))
            threads = 1;
        choose_threads(threads, console);
        if (a->resume) {
            const ResumePlan plan =
                plan_resume(o.out_dir, run_directory_config(o.config_path, o.config_text));
            console << "pedesis: " << plan.why << "\n" << std::flush;
            if (plan.kind == ResumePlan::Kind::finished) return;
            if (plan.kind == ResumePlan::Kind::resume) {
                o.restart = plan.checkpoint;
                o.resume_marks = plan.marks;
            }
        }
        const std::unique_ptr<Run> run = [&] {
            try {
                return make_run(config, o, console);
            } catch (const InputError& e) {
                // a key's place named in the set-up (the time step's): the file's, or the --set's
                if (with_sets) throw InputError(with_sets->explain(e.what()));
                throw;
            }
        }();
        // Changes from the page (--view) and from a record (--steering) go through one
        // desk, applied between steps and recorded in the run directory. Under MPI the
        // page only watches: a change reaching process 0 alone would split the run.
        std::unique_ptr<SteeringDesk> desk;
        const bool live_changes = a->view && !comm && !run->steerable().empty();
        if (live_changes || !a->steering.empty()) {
            std::vector<SteeringChange> replay;
            if (!a->steering.empty()) replay = read_steering(a->steering);
            desk = std::make_unique<SteeringDesk>(
                *run, !comm || comm->rank() == 0 ? o.out_dir / "steering.csv" : "",
                std::move(replay));
            run->add_operation(Trigger::every_steps(1), [d = desk.get()] { d->apply_due(); });
        }
        std::unique_ptr<LiveView> live;
        if (a->view && (!comm || comm->rank() == 0)) {
            live = std::make_unique<LiveView>(o.out_dir, a->view_port,
                                              live_changes ? desk.get() : nullptr);
            console << fmt::format("pedesis: watch the run at {}\n", live->url()) << std::flush;
        }
        {
            // from the first step to the steering record's close, a signal stops cleanly
            const CleanStopWindow window;
            try {
                if (desk) desk->replay_until_done();
                run->run();
            } catch (const RunError& e) {
                // a blow-up after a change: say which (the page may have asked for it)
                if (desk) throw RunError(e.what() + desk->failure_note());
                throw;
            }
            if (desk) desk->run_ended();
        }
        if (live && guard.signal() == 0) {
            lock.reset(); // the run is done: serving its directory does not write it
            console << fmt::format("pedesis: the run is done; {} still shows it until Ctrl-C\n",
                                   live->url())
                    << std::flush;
            // Every file is closed, so a signal ends the process by its default action
            // here (no clean stop to wait for, and no server close that a stuck client
            // could hold up): pause() returns only to a handler, and ours does not return.
            for (;;) ::pause();
        }
        if (const int sig = guard.signal(); sig != 0) {
            const bool checkpoint_signal = sig == SIGTERM || sig == SIGUSR1;
            console << fmt::format(
                "pedesis: interrupted by signal {} ({}) at step {} (t = {:.6g}); the run "
                "directory is complete up to here: continue in place with --resume (pedesis run "
                "{} --out {} --resume), or elsewhere with --restart {}{}\n",
                sig, strsignal(sig), run->step(), run->time(), a->config, o.out_dir.string(),
                (o.out_dir / "checkpoint.bin").string(),
                checkpoint_signal
                    ? fmt::format("; exit code {}: checkpointed, resume me", exit_checkpointed)
                    : "");
            console.flush();
            live.reset();
            desk.reset(); // its record, under its final name, before the signal ends us
            lock.reset();
            // a scheduler's signal asks for a checkpoint and an end a job script can test;
            // Ctrl-C and a hang-up end the process by the signal, as a shell expects
            if (checkpoint_signal) throw SilentExit{exit_checkpointed};
            guard.reraise();
        }
    });
}

} // namespace pedesis::cli
