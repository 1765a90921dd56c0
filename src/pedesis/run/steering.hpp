#pragma once
// Changes of a running simulation's parameters (temperature, alpha, J, restitution:
// RunEngine::steer) asked for while it runs (`pedesis run --view`, from the page) or
// replayed from a record (`pedesis run --steering FILE`). Each is applied between two
// steps, at the step it is recorded with, so that replaying the record reproduces the run
// bit for bit. The event engine has no steps (its step is the collision count, which can
// stand still): there a change is tied to its time, and the replay stops the run at that
// exact time (replay_until).
//
// The record, steering.csv in the run directory: a header `step,time,parameter,value`,
// then one row per change in the order applied, numbers in their shortest exact form.
#include "pedesis/io/atomic_file.hpp"
#include "pedesis/run/run.hpp"

#include <cstdint>
#include <deque>
#include <filesystem>
#include <memory>
#include <mutex>
#include <optional>
#include <string>
#include <utility>
#include <vector>

namespace pedesis {

struct SteeringChange {
    std::uint64_t step = 0;
    double time = 0.0;
    std::string parameter;
    double value = 0.0;
};

// A record as steering.csv holds it; InputError naming the file and line.
std::vector<SteeringChange> read_steering(const std::filesystem::path& file);

// A parameter as the page shows it: its value now and what a change may set it to.
struct SteerableParameter {
    std::string name;
    double value = 0.0;
    double min = 0.0, max = 0.0;
};

// What a change may set a parameter to, from its value at the start: a restitution lies in
// [0, 1]; a temperature in [0, 10^6 x its start] (10^6 where it started at 0); alpha and
// J, whose sign is physical (swimming backwards, anti-alignment), within +-10^6 x their
// start (or 10^6). Wider changes only blow a run up: its dt was chosen for the start.
std::pair<double, double> steering_range(const std::string& parameter, double start);

class SteeringDesk {
  public:
    // `record`: where to write the changes applied (empty: nowhere); `replay`: changes
    // to apply at their steps. Those at or before the run's current step (a restart) are
    // applied now. InputError if the replay names a parameter the run does not have.
    SteeringDesk(Run& run, std::filesystem::path record, std::vector<SteeringChange> replay);
    ~SteeringDesk(); // commits the record: every row in it is whole

    // From any thread (the viewer's server): queues a change for the next step, or says
    // why not ("" when queued). Refused: unknown parameters, values outside
    // steering_range (non-finite ones included).
    std::string request(const std::string& parameter, double value);
    // After the run has ended, every request is refused (the page may stay open), and the
    // record is committed under its final name.
    void run_ended();
    // The parameters, their values as last applied and their ranges, from any thread.
    std::vector<SteerableParameter> parameters() const;
    // For a run that failed: " (after the change of <parameter> to <value> at step S, t
    // = T)", naming the last change applied, or "" where none was.
    std::string failure_note() const;

    // From the run's thread between steps (an every-step operation of the run): applies
    // the replayed changes of this step, then the requests queued since the last call,
    // and records each.
    void apply_due();

    // Runs the simulation up to each replayed change still ahead and applies it there,
    // so that it lands at its recorded step or time even where no trigger stops the run
    // (the event engine, or a change from Python between two rows); then returns.
    void replay_until_done();

  private:
    bool due(const SteeringChange& change) const;
    void apply(const SteeringChange& change);
    void write_record(); // the rows applied since the last call

    Run& run_;
    std::filesystem::path record_path_;
    std::unique_ptr<AtomicAppendFile> record_;
    std::string unwritten_; // rows applied, not yet in the record
    std::vector<SteeringChange> replay_;
    std::size_t next_replay_ = 0;
    mutable std::mutex mutex_; // requests_, values_ and ended_
    std::deque<std::pair<std::string, double>> requests_;
    std::vector<std::pair<std::string, double>> values_;
    std::vector<std::pair<double, double>> ranges_; // values_'s, from their start
    std::optional<SteeringChange> last_applied_;
    bool ended_ = false;
};

} // namespace pedesis
