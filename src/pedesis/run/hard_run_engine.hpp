#pragma once
// What the event and stepped engines' runs share: a time-grid schedule from [output],
// the run record kept in the checkpoint (frame numbers, pressure integrals, the speed
// histogram) and the files of a hard-particle run directory.
#include "pedesis/run/hard_run_output.hpp"
#include "pedesis/run/run_engine.hpp"
#include "pedesis/run/run_options.hpp"
#include "pedesis/run/simulation.hpp"
#include "pedesis/setup/run_config.hpp"

#include <ostream>

namespace pedesis {

template <int D> class HardRunEngine : public RunEngine<D> {
  public:
    HardRunEngine(const RunConfig& c, const RunOptions& o, std::ostream& console)
        : c_(c), o_(o), console_(console), out_(c, o, record_) {}

    Schedule schedule() const {
        return {Trigger::every_time(c_.log_interval),
                c_.snapshot_interval > 0 ? Trigger::every_time(c_.snapshot_interval)
                                         : Trigger::never(),
                c_.checkpoint_interval > 0 ? Trigger::every_time(c_.checkpoint_interval)
                                           : Trigger::never()};
    }
    OutputChoice outputs() const {
        return {c_.formats, c_.log_quantities, c_.log_quantities_where};
    }

    std::uint64_t frames() const override { return record_.frames; }
    void frame_written() override { ++record_.frames; }
    std::vector<const char*> stale_results() const override {
        return {"summary.json", "speed_histogram.csv"};
    }

  protected:
    // The MSD's origin: the unwrapped positions of a fresh start, or of the restart from a
    // checkpoint written before image counts (which the console is told).
    void keep_msd_origin(std::vector<Vec<D>> unwrapped, double t) {
        if (!record_.start.empty()) return;
        record_.start = std::move(unwrapped);
        if (o_.restart)
            console_ << "pedesis: the checkpoint predates image counts: the msd counts from its "
                        "time, t = "
                     << t << "\n";
    }

    // Builds the engine from the config's particles; an engine's refusal ("particle 3:
    // speed above 1e100") names the file the particles came from.
    template <class Make> auto with_source(Make make) const {
        try {
            return make();
        } catch (const InputError& e) {
            const std::string what = e.what();
            for (const std::string& named : {c_.file, c_.initial_file.value_or(c_.file)})
                if (what.rfind(named + ":", 0) == 0) throw; // names its file already
            // the engine's refusals of the box are about [box] length(s): their line
            if (what.starts_with("box: ") && !c_.lengths_where.empty())
                throw InputError(c_.lengths_where + ": " + what.substr(5));
            throw InputError(c_.initial_file.value_or(c_.file) + ": " + what);
        }
    }

    const RunConfig& c_;
    const RunOptions& o_;
    std::ostream& console_;
    HardRunRecord<D> record_;
    HardRunOutput<D> out_;
};

// The setup of a hard-particle engine's run (EventRunEngine, SteppedRunEngine).
template <template <int> class Engine, int D>
EngineSetup<D> hard_engine_setup(const RunConfig& config, const RunOptions& options,
                                 std::ostream& console) {
    auto engine = std::make_unique<Engine<D>>(config, options, console);
    EngineSetup<D> setup{nullptr, engine->schedule(), engine->outputs()};
    setup.engine = std::move(engine);
    return setup;
}

} // namespace pedesis
