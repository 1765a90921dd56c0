#pragma once
// The run directory of the two hard-particle engines, event and stepped, so that a plot
// or a movie made from one works for the other: log.csv with the thermodynamic columns
// both share, trajectory.xyz and snapshots/, speed_histogram.csv, and the common part of
// summary.json and of the printed summary. Each driver adds its own columns and keys.
#include "pedesis/core/box.hpp"
#include "pedesis/core/particles.hpp"
#include "pedesis/event/event_engine.hpp" // EventCounters: the running totals of both engines
#include "pedesis/io/atomic_file.hpp"
#include "pedesis/io/frame_writers.hpp"
#include "pedesis/io/run_config.hpp"
#include "pedesis/observe/speed_histogram.hpp"
#include "pedesis/observe/thermo.hpp"
#include "pedesis/run/event_run.hpp" // RunOptions

#include <nlohmann/json.hpp>

#include <iosfwd>
#include <memory>
#include <string>

namespace pedesis {

// Collisions, elastic or not, conserve momentum: only walls and fixed obstacles (which
// thermo.hpp sees in the box and the masses) take degrees of freedom back.
inline constexpr Momentum hard_particle_dynamics = Momentum::conserving;

// What the run directory accumulates, kept in checkpoints so that a continued run
// writes what the uninterrupted one would have.
template <int D> struct HardRunRecord {
    double initial_kinetic = 0.0;
    double integral_T_dt = 0.0; // for the kinetic part of the run-averaged pressure
    double last_log_time = 0.0;
    double last_temperature = 0.0;
    EventCounters<D> last_counters{};
    std::uint64_t frames = 0;
    SpeedHistogram histogram;

    void save(std::ostream& out) const;
    void load(std::istream& in);
};

// One row of log.csv as measured: the shared columns as text (no line end) and the
// values the drivers print.
struct LogRow {
    std::string csv;
    SpeciesKinetics kinetics;
    double temperature = 0.0;
    double pressure = 0.0; // over the interval since the previous row
    bool has_pressure = false;
};

template <int D> class HardRunOutput {
  public:
    HardRunOutput(const RunConfig& c, const RunOptions& o, HardRunRecord<D>& record)
        : c_(c), o_(o), record_(record) {}

    // Creates the directory, removes an earlier run's results, copies the config, and
    // starts log.csv with the shared columns followed by `extra_columns` (",a,b").
    void open(const std::string& extra_columns);

    // Measures a row at time t (velocities of p must be current), samples the speed
    // histogram if asked, and moves the record on. The caller appends its own columns.
    LogRow measure(const ParticleStore<D>& p, const Box<D>& box, double t,
                   const EventCounters<D>& counters);
    void append_log(const std::string& line);

    // A frame (positions and velocities current) in every format the config asks for.
    void frame(const Frame<D>& f);

    // speed_histogram.csv from the samples, plus `final_state` when the histogram is of
    // the final state only. Not in the record, so a continued run does not count it twice.
    void write_speed_histogram(const ParticleStore<D>& final_state);

    // Gives the log and the trajectory their final names (also for a stopped run).
    void close();

    // The summary fields both engines share: temperatures, run-averaged pressure against
    // the ideal gas and the hard-disk / hard-sphere equation of state, collisions.
    nlohmann::json summary(const ParticleStore<D>& p, const Box<D>& box, double t,
                           const EventCounters<D>& counters) const;
    // The printed lines for those fields, from the temperature to the mean free time.
    void print_summary(std::ostream& console, const nlohmann::json& j, const Box<D>& box) const;
    void write_summary(const nlohmann::json& j) const;

  private:
    const RunConfig& c_;
    const RunOptions& o_;
    HardRunRecord<D>& record_;
    std::unique_ptr<AtomicAppendFile> log_;
    std::unique_ptr<FrameWriters<D>> frames_;
};

// "30w x 20p": the box for the first printed line.
template <int D> std::string box_text(const Box<D>& box);

// Volume fraction of the particles in the box.
template <int D> double packing_fraction(const ParticleStore<D>& p, const Box<D>& box);

// The first multiple of `interval` after t (a grid anchored at t = 0).
double next_multiple(double t, double interval);

// Throws InputError if a checkpoint's species or box differ from the config's.
template <int D>
void check_checkpoint_matches(const std::vector<Species>& table, const Box<D>& box,
                              const RunConfig& c);

extern template class HardRunOutput<2>;
extern template class HardRunOutput<3>;

} // namespace pedesis
