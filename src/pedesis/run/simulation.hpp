#pragma once
// The one run loop of every engine: advance to the next trigger, do what is due (log row,
// frame, checkpoint), stop on the engine's stop condition, and end the run directory the
// same way for all: the last frame, the checkpoint, the summary. A run that fails
// mid-way (RunError: a blow-up, inelastic collapse) keeps its log and frames, complete
// and under their final names, and says which frame was the last good one.
#include "pedesis/io/atomic_file.hpp"
#include "pedesis/io/frame_writers.hpp"
#include "pedesis/run/run_engine.hpp"
#include "pedesis/run/run_options.hpp"
#include "pedesis/run/trigger.hpp"

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
};

template <int D> class Simulation {
  public:
    // Throws InputError (before any file exists) if a chosen quantity is one the engine
    // does not measure.
    Simulation(RunEngine<D>& engine, Schedule schedule, OutputChoice outputs,
               const RunOptions& options);

    // Prepares the run directory, runs to the engine's stop condition and writes the end
    // of the run. Throws RunError (outputs kept) if the run fails.
    void run();

  private:
    void write_frame();
    void write_log_row();
    void close();
    std::string failure_note() const;

    RunEngine<D>& engine_;
    Schedule schedule_;
    OutputChoice outputs_;
    std::vector<std::size_t> columns_; // indices into the engine's log_columns()
    std::vector<bool> counts_;         // per chosen column: written as an integer
    std::vector<double> values_;       // one measured row, reused
    const RunOptions& options_;
    std::unique_ptr<AtomicAppendFile> log_;
    std::unique_ptr<FrameWriters<D>> frames_;
    std::uint64_t frames_this_run_ = 0; // by this invocation (a restart starts at 0)
    std::uint64_t last_frame_step_ = 0;
    double last_frame_time_ = 0.0;
};

extern template class Simulation<2>;
extern template class Simulation<3>;

} // namespace pedesis
