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

template <int D> class Simulation {
  public:
    Simulation(RunEngine<D>& engine, Schedule schedule, std::vector<std::string> formats,
               const RunOptions& options);

    // Prepares the run directory, runs to the engine's stop condition and writes the end
    // of the run. Throws RunError (outputs kept) if the run fails.
    void run();

  private:
    void write_frame();
    void close();
    std::string failure_note() const;

    RunEngine<D>& engine_;
    Schedule schedule_;
    std::vector<std::string> formats_;
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
