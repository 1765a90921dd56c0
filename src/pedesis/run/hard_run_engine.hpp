#pragma once
// What the event and stepped engines' runs share: a time-grid schedule from [output],
// the run record kept in the checkpoint (frame numbers, pressure integrals, the speed
// histogram) and the files of a hard-particle run directory.
#include "pedesis/run/hard_run_output.hpp"
#include "pedesis/run/run_engine.hpp"
#include "pedesis/run/run_options.hpp"
#include "pedesis/run/simulation.hpp"
#include "pedesis/run/transport_plan.hpp"
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
        return {"summary.json", "speed_histogram.csv", "transport.csv", "velocity_profile.csv"};
    }

  protected:
    // [transport]: starts the measurement at `now` unless the checkpoint carries one (a
    // config without the table drops it); the engine keeps its flux moments from then on.
    template <class Engine>
    void start_transport_if_asked(Engine& e, const ParticleStore<D>& p, double step) {
        if (!c_.transport.on) {
            record_.transport.reset();
            return;
        }
        if (e.box().sheared())
            throw InputError(c_.transport.where + ": not under shear: summary.json's \"shear\" "
                                                  "gives the viscosity of a sheared run");
        if (!record_.transport)
            record_.transport.emplace(start_transport<D>(c_, p, e.box(), e.time(), step));
        e.track_flux_moments();
        followed_ = followed_particles(p, record_.transport->plan().particles);
        if (followed_.size() != record_.transport->plan().particles)
            throw InputError(
                c_.transport.where + ": the particles [transport] follows (tags below " +
                std::to_string(record_.transport->plan().particles) + ") are not all there");
    }
    bool transport_due(double now, double step) const {
        return record_.transport && now >= record_.transport->next_time() - 1e-9 * (step + 1e-300);
    }
    // One sample: G = V ∫ P dt (the kinetic integrals and the collision virial), H = ∫ J_q dt,
    // the followed particles' unwrapped positions and velocities when due.
    template <class Engine> void sample_transport(const Engine& e) {
        auto& m = *record_.transport;
        const FluxMoments<D> f = e.flux_moments();
        SymTensor G{};
        for (int s = 0; s < 6; ++s) G[s] = f.kinetic_integral[s] + e.counters().virial[s];
        const Vec<D> H = f.heat_integral + f.heat_collisional;
        positions_.clear();
        velocities_.clear();
        if (m.positions_due())
            for (const auto i : followed_) positions_.push_back(e.unwrapped_now(i));
        if (m.velocities_due())
            for (const auto i : followed_) velocities_.push_back(e.velocity(i));
        m.add(G, H, positions_, velocities_);
    }
    // summary.json's "transport", transport.csv and the printed lines, at the end.
    void transport_summary(nlohmann::json& j, const Box<D>& box, const ParticleStore<D>& p) const {
        if (!record_.transport) return;
        const double T = j["time_averaged_temperature"].template get<double>();
        j["transport"] = record_.transport->summary(transport_scales(c_, box, p, T));
    }
    void write_transport(const nlohmann::json& j, const Box<D>& box, const ParticleStore<D>& p) {
        if (!record_.transport) return;
        const double T = j["time_averaged_temperature"].template get<double>();
        record_.transport->write_csv(o_.out_dir / "transport.csv", transport_scales(c_, box, p, T));
        print_transport(console_, j["transport"]);
    }

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
    std::vector<std::uint32_t> followed_;        // [transport]'s particles, storage indices
    std::vector<Vec<D>> positions_, velocities_; // a sample's scratch
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
