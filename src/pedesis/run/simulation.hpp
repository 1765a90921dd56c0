#pragma once
// The one run loop of every engine: advance to the next trigger, do what is due (log row,
// frame, checkpoint), stop on the engine's stop condition, and end the run directory the
// same way for all: the last frame, the checkpoint, the summary. A run that fails
// mid-way (RunError: a blow-up, inelastic collapse) keeps its log and frames, complete
// and under their final names, and says which frame was the last good one.
#include "pedesis/core/error.hpp"
#include "pedesis/io/atomic_file.hpp"
#include "pedesis/io/frame_writers.hpp"
#include "pedesis/run/run_engine.hpp"
#include "pedesis/run/run_options.hpp"
#include "pedesis/run/trigger.hpp"

#include <chrono>
#include <functional>
#include <limits>
#include <memory>
#include <string>
#include <vector>

namespace pedesis {

struct Schedule {
    Trigger log = Trigger::never();
    Trigger frames = Trigger::never();
    Trigger checkpoint = Trigger::never();
};

// What the run directory holds: the frame formats, and the log's columns (the engine's
// own list when empty).
struct OutputChoice {
    std::vector<std::string> formats;
    std::vector<std::string> quantities;
    std::string quantities_where; // "file:line:col: key 'log.quantities'", for messages
};

// An engine built from a config, with what the config asks of its run directory.
template <int D> struct EngineSetup {
    std::unique_ptr<RunEngine<D>> engine;
    Schedule schedule;
    OutputChoice outputs;
};

template <int D> class Simulation {
  public:
    // Throws InputError (before any file exists) if a chosen quantity is one the engine
    // does not measure. An empty options.out_dir runs without a run directory: nothing is
    // written (the schedule then has no frames or checkpoints), the rest is the same.
    Simulation(RunEngine<D>& engine, Schedule schedule, OutputChoice outputs,
               const RunOptions& options);

    // The whole run as the CLI makes it: open, advance to the stop condition, close.
    // Throws RunError (outputs kept) if the run fails. A signal caught by an
    // InterruptGuard (core/interrupt.hpp) ends it early, closed as a finished run is
    // (last frame, checkpoint, summary), with ended_by "interrupted".
    void run();

    // The steps of run(), for a script that drives the run.
    // open: the run directory, the log's header, and (for a fresh run) row and frame 0;
    // called by advance and close if not yet.
    void open();
    // Advances until the config's stop condition (then returns its name) or until step
    // `max_step` / time `max_time`, whichever comes first, or until a caught signal
    // (then returns null). An
    // exception from an operation leaves the run able to go on.
    const char* advance(std::uint64_t max_step = std::numeric_limits<std::uint64_t>::max(),
                        double max_time = std::numeric_limits<double>::infinity());
    // The end of the run directory: the last frame, the checkpoint, the summary (whose
    // stopped_by is the stop condition, or `ended_by` if none was met). Once.
    void close(const char* ended_by);

    // One more thing to do when `trigger` fires (not at the stop, like frames): a
    // script's writer or callback.
    void add_operation(Trigger trigger, std::function<void()> act);

    // The log's columns and the values of its last row (empty before the first).
    const std::vector<std::string>& log_names() const { return chosen_; }
    const std::vector<double>& last_log_row() const { return last_row_; }
    const char* stopped_by() const { return stopped_by_; }
    bool closed() const { return closed_; }

  private:
    struct Operation {
        Trigger trigger;
        std::function<void()> act;
    };

    // Without a run directory (an empty out_dir) the loop keeps its triggers, operations,
    // stop conditions and checks, and writes nothing: how a script's own driver runs.
    bool in_directory() const { return !options_.out_dir.empty(); }
    void write_frame();
    void write_log_row();
    // The checkpoint, after the marks of every output written so far (io/resume_record.hpp).
    void write_checkpoint(bool final);
    // For --resume: the run directory's outputs, cut back to the marks of the checkpoint
    // the engine was loaded from.
    void reopen_outputs();
    void close_files();
    std::string failure_note() const;
    // Ends a run whose state broke (RunError): the files so far are committed, and the
    // error is thrown again with the last good snapshot named.
    [[noreturn]] void fail(const RunError& e);

    RunEngine<D>& engine_;
    Schedule schedule_;
    OutputChoice outputs_;
    std::vector<std::string> logged_;   // every column the engine measures
    std::vector<bool> may_be_infinite_; // per logged_ column (observe/quantities.hpp)
    std::vector<bool> is_count_;        // per logged_ column: an integer count
    std::vector<std::string> chosen_;   // the log's columns
    std::vector<std::size_t> columns_;  // their indices into logged_
    std::vector<double> values_;        // one measured row, reused
    std::vector<double> last_row_;      // the chosen columns of the last row
    const RunOptions& options_;
    std::vector<Operation> operations_;
    std::unique_ptr<AtomicAppendFile> log_;
    std::unique_ptr<FrameWriters<D>> frames_;
    std::vector<OutputMarks> marks_; // of the last two checkpoints, the newest last
    std::chrono::steady_clock::time_point last_checkpoint_wall_;
    bool opened_ = false, closed_ = false;
    const char* stopped_by_ = nullptr;
    std::uint64_t frames_this_run_ = 0; // by this invocation (a restart starts at 0)
    std::uint64_t last_frame_step_ = 0;
    std::uint64_t rows_this_run_ = 0, last_row_step_ = 0;
    double last_row_time_ = 0.0;
    double last_frame_time_ = 0.0;
};

extern template class Simulation<2>;
extern template class Simulation<3>;

} // namespace pedesis
