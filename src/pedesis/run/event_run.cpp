#include "pedesis/run/event_run.hpp"

#include "pedesis/run/engine_params.hpp"

#include "pedesis/core/error.hpp"
#include "pedesis/event/event_engine.hpp"
#include "pedesis/io/atomic_file.hpp"
#include "pedesis/io/binary_stream.hpp"
#include "pedesis/observe/thermo.hpp"
#include "pedesis/run/hard_checkpoint.hpp"
#include "pedesis/run/hard_run_output.hpp"
#include "pedesis/setup/build_system.hpp"

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <fstream>
#include <memory>
#include <optional>

namespace pedesis {

namespace {

constexpr std::uint64_t run_checkpoint_magic = 0x31304e5552444550ull; // "PEDRUN01"

template <int D>
void save_checkpoint(const std::filesystem::path& path, const EventEngine<D>& e,
                     const HardRunRecord<D>& s) {
    save_hard_checkpoint(path, run_checkpoint_magic, e, s);
}

template <int D>
std::unique_ptr<EventEngine<D>> load_checkpoint(const std::filesystem::path& path,
                                                const RunConfig& c, HardRunRecord<D>& s) {
    return load_hard_checkpoint<EventEngine<D>>(
        path, run_checkpoint_magic, "not a pedesis run checkpoint", event_params(c), c, s,
        [](const EventEngine<D>& e) -> const std::vector<Species>& {
            return e.lazy_particles().species_table;
        });
}

template <int D> class EventRun {
  public:
    EventRun(const RunConfig& c, const RunOptions& o, std::ostream& console)
        : c_(c), o_(o), console_(console), out_(c, o, state_) {}

    void execute() {
        const Box<D> box = build_box<D>(c_);
        if (o_.restart) {
            engine_ = load_checkpoint<D>(*o_.restart, c_, state_);
        } else {
            engine_ = std::make_unique<EventEngine<D>>(build_particles<D>(c_, box), box,
                                                       event_params(c_));
            state_.initial_kinetic = engine_->kinetic_energy();
            state_.last_temperature =
                measure_kinetics(engine_->lazy_particles(), box, hard_particle_dynamics)
                    .temperature();
            state_.histogram = SpeedHistogram(c_.species.size(), c_.histogram_bins);
        }
        growing_ = c_.growth_rate > 0;
        out_.open(growing_ ? ",list_rebuilds,packing_fraction,growth_pressure" : ",list_rebuilds");
        const std::size_t n = engine_->size();

        StopLimits limits;
        const double t_end = c_.stop_time.value_or(std::numeric_limits<double>::infinity());
        if (c_.stop_collisions_per_particle)
            limits.pair_collisions = static_cast<std::uint64_t>(
                std::ceil(*c_.stop_collisions_per_particle * static_cast<double>(n)));
        if (c_.stop_energy_fraction)
            limits.min_kinetic_energy = *c_.stop_energy_fraction * state_.initial_kinetic;

        console_ << fmt::format(
            "pedesis: {}D event-driven run, N = {}, box {}, eta = {:.4f}, output in {}\n", D, n,
            box_text(engine_->box()), packing_fraction(engine_->lazy_particles(), engine_->box()),
            o_.out_dir.string());
        if (!o_.restart) {
            log_row();
            frame();
        }
        wall_start_ = std::chrono::steady_clock::now();
        collisions_start_ = engine_->counters().pair_collisions;
        const double li = c_.log_interval;
        double next_log = next_multiple(engine_->time(), li);
        double next_snap =
            c_.snapshot_interval > 0 ? next_multiple(engine_->time(), c_.snapshot_interval) : t_end;
        double next_ckpt = c_.checkpoint_interval > 0
                               ? next_multiple(engine_->time(), c_.checkpoint_interval)
                               : t_end;
        StopReason reason = StopReason::time;
        try {
            while (true) {
                limits.time = std::min({next_log, next_snap, next_ckpt, t_end});
                reason = engine_->run(limits);
                const double t = engine_->time();
                if (reason == StopReason::grown) announce_growth_end();
                const bool stop = (reason != StopReason::time && reason != StopReason::grown) ||
                                  (reason == StopReason::grown && c_.stop_when_grown) || t >= t_end;
                if (t >= next_log || stop || reason == StopReason::grown) {
                    log_row();
                    next_log = next_multiple(t, li);
                }
                if (c_.snapshot_interval > 0 && t >= next_snap && !stop) {
                    frame();
                    next_snap = next_multiple(t, c_.snapshot_interval);
                }
                if (c_.checkpoint_interval > 0 && t >= next_ckpt && !stop) {
                    save_checkpoint(o_.out_dir / "checkpoint.bin", *engine_, state_);
                    next_ckpt = next_multiple(t, c_.checkpoint_interval);
                }
                if (stop) break;
            }
        } catch (const RunError& e) {
            // keep what is good: frames so far, the log, and the last checkpoint
            out_.close();
            throw RunError(std::string(e.what()) +
                           " (the log, the frames and the last checkpoint written so far are in " +
                           o_.out_dir.string() + ")");
        }
        finish(reason);
    }

  private:
    void log_row() {
        const auto& e = *engine_;
        const LogRow row = out_.measure(e.lazy_particles(), e.box(), e.time(), e.counters());
        std::string extra = fmt::format(",{}", e.counters().list_rebuilds);
        if (growing_)
            extra +=
                fmt::format(",{:.10g},{:.10g}", e.packing_fraction(), e.growth().last_pressure);
        out_.append_log(row.csv + extra + "\n");
        progress(row.temperature, row.pressure, row.has_pressure);
    }

    void progress(double T, double P, bool has_pressure) {
        if (!c_.progress) return;
        const auto now = std::chrono::steady_clock::now();
        if (last_progress_ && now - *last_progress_ < std::chrono::seconds(1)) return;
        last_progress_ = now;
        const double wall = std::chrono::duration<double>(now - wall_start_).count();
        const double rate =
            wall > 0
                ? static_cast<double>(engine_->counters().pair_collisions - collisions_start_) /
                      wall
                : 0.0;
        console_ << fmt::format("  t = {:<10.4g} collisions/particle = {:<9.4g} T = {:<10.5g} P = "
                                "{:<10s} {:.3g} collisions/s\n",
                                engine_->time(),
                                static_cast<double>(engine_->counters().pair_collisions) /
                                    static_cast<double>(engine_->size()),
                                T, has_pressure ? fmt::format("{:.5g}", P) : "-", rate);
    }

    void announce_growth_end() {
        const auto& g = engine_->growth();
        console_ << fmt::format(
            "pedesis: growth ended at t = {:.6g}: {} (packing fraction {:.6f}, reduced pressure "
            "{:.4g})\n",
            engine_->time(),
            g.ended == GrowthEnd::pressure ? "reduced pressure reached event.growth_max_pressure"
                                           : "reached event.growth_packing_fraction",
            engine_->packing_fraction(), g.last_pressure);
    }

    void frame() {
        const ParticleStore<D> now = engine_->snapshot();
        const auto& n = engine_->counters();
        out_.frame(
            Frame<D>{engine_->box(), now, engine_->time(), n.pair_collisions + n.wall_collisions});
    }

    void finish(StopReason reason) {
        const auto& e = *engine_;
        frame();
        save_checkpoint(o_.out_dir / "checkpoint.bin", e, state_);
        out_.write_speed_histogram(e.lazy_particles());
        out_.close();
        write_summary(reason);
    }

    void write_summary(StopReason reason) {
        const auto& e = *engine_;
        nlohmann::json j = out_.summary(e.lazy_particles(), e.box(), e.time(), e.counters());
        const char* why = reason == StopReason::time         ? "time"
                          : reason == StopReason::collisions ? "collisions_per_particle"
                          : reason == StopReason::energy     ? "energy_fraction"
                          : reason == StopReason::grown      ? "grown"
                                                             : "no more events";
        j["stopped_by"] = why;
        if (growing_) {
            const auto& g = e.growth();
            j["growth"] = {{"growing", g.growing},
                           {"ended_by", g.ended == GrowthEnd::pressure ? "pressure"
                                        : g.ended == GrowthEnd::packing_fraction
                                            ? "packing_fraction"
                                            : "not ended"},
                           {"packing_fraction", e.packing_fraction()},
                           {"last_reduced_pressure", g.last_pressure},
                           {"steps", g.steps}};
            j["packing_fraction"] = e.packing_fraction(); // the radii of this instant
        }
        out_.write_summary(j);
        console_ << fmt::format(
            "pedesis: stopped by {} at t = {:.6g} after {} collisions ({:.3g} per particle)\n", why,
            e.time(), e.counters().pair_collisions,
            j["collisions_per_particle"].template get<double>());
        out_.print_summary(console_, j, e.box());
        console_ << fmt::format("  outputs            {}\n", o_.out_dir.string());
    }

    const RunConfig& c_;
    const RunOptions& o_;
    std::ostream& console_;
    std::unique_ptr<EventEngine<D>> engine_;
    HardRunRecord<D> state_;
    HardRunOutput<D> out_;
    std::chrono::steady_clock::time_point wall_start_;
    std::optional<std::chrono::steady_clock::time_point> last_progress_;
    std::uint64_t collisions_start_ = 0;
    bool growing_ = false; // growth configured: log packing fraction and pressure
};

} // namespace

void run_event_simulation(const RunConfig& config, const RunOptions& options,
                          std::ostream& console) {
    if (config.dimension == 2)
        EventRun<2>(config, options, console).execute();
    else
        EventRun<3>(config, options, console).execute();
}

} // namespace pedesis
