#pragma once
// What the one run loop (simulation.hpp) needs of an engine: advance, the clock, a frame
// to write, the log, the checkpoint and the end of a run. Each engine's implementation
// (run/event_run.cpp, run/stepped_run.cpp, run/soft_run.cpp) builds or restores its
// engine from the config and keeps what the run directory accumulates; the loop, the
// triggers, the frames, the failure path and the order of the files are the
// Simulation's, written once.
#include "pedesis/core/error.hpp"
#include "pedesis/core/frame.hpp"
#include "pedesis/core/interrupt.hpp"

#include <nlohmann/json.hpp>

#include <cstdint>
#include <filesystem>
#include <string>
#include <utility>
#include <vector>

namespace pedesis {

// What one advance ended with.
struct Advance {
    const char* stopped_by = nullptr; // a [run] stop condition was met: its name
    bool log_now = false;             // the log must show this instant (growth ended)
};

template <int D> class RunEngine {
  public:
    virtual ~RunEngine() = default;

    virtual std::uint64_t step() const = 0;
    virtual double time() const = 0;

    // Advances to the first of: step `until_step`, time `until_time`, a stop condition of
    // the config. It may return earlier (the stepped engine returns after every step);
    // the Simulation then asks again.
    virtual Advance advance(std::uint64_t until_step, double until_time) = 0;
    // Whether a caught signal asks the run to stop (a run divided among processes
    // answers the same on all of them).
    virtual bool interrupted() const { return interrupt_requested(); }

    // Under a Communicator (RunOptions::comm) every process makes every call below, in the
    // same order, and only process 0's answers are whole (frame, summary).

    // The current state, valid until the next call that changes the engine.
    virtual Frame<D> frame() = 0;

    // Frames written so far by this run and the runs it continues (numbering survives a
    // restart through the checkpoint).
    virtual std::uint64_t frames() const = 0;
    virtual void frame_written() = 0;

    // The exact state and what the run directory accumulates, for --restart.
    virtual void save_checkpoint(const std::filesystem::path& path) = 0;

    // Results of an earlier run in the directory that this run will write anew and that
    // must not pass for its own meanwhile (summary.json, ...).
    virtual std::vector<const char*> stale_results() const = 0;
    // The quantities it logs (names of observe/quantities.hpp), in the order of a default
    // log.csv; measure() appends the value of each, in that order, measured now (it may
    // print a progress line and move run averages on).
    virtual std::vector<std::string> log_columns() const = 0;
    virtual void measure(std::vector<double>& values) = 0;

    // Called once before the loop: the first printed line, and for a fresh run whatever
    // frame 0 must show (the soft engine computes the initial forces).
    virtual void start(bool fresh) = 0;
    // The end of a finished run, after the last frame and checkpoint. summary: this
    // engine's entries of summary.json (run averages, counts, the engine's parameters);
    // the Simulation adds stopped_by and the last log row by quantity name, and writes it.
    // finish: the files only the end writes (speed histogram) and the printed summary.
    virtual nlohmann::json summary(const char* stopped_by) = 0;
    virtual void finish(const nlohmann::json& summary) = 0;

    // What a running simulation lets change between steps (`pedesis run --view`,
    // `--steering`): each parameter's name and current value (none by default).
    virtual std::vector<std::pair<std::string, double>> steerable() const { return {}; }
    // Sets one from the next step on; InputError for an unknown name or a bad value.
    virtual void steer(const std::string& name, double /*value*/) {
        throw InputError("this engine has no parameter '" + name + "' to change while it runs");
    }
};

} // namespace pedesis
