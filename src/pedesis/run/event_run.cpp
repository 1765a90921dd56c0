#include "pedesis/run/event_run.hpp"

#include "pedesis/run/engine_params.hpp"

#include "pedesis/core/error.hpp"
#include "pedesis/core/interrupt.hpp"
#include "pedesis/core/simd_level.hpp"
#include "pedesis/event/event_engine.hpp"
#include "pedesis/io/atomic_file.hpp"
#include "pedesis/io/binary_stream.hpp"
#include "pedesis/observe/thermo.hpp"
#include "pedesis/run/hard_checkpoint.hpp"
#include "pedesis/run/hard_run_engine.hpp"
#include "pedesis/run/hard_run_output.hpp"
#include "pedesis/run/shear_output.hpp"
#include "pedesis/setup/build_system.hpp"

#include <fmt/format.h>
#include <fmt/ranges.h>
#include <nlohmann/json.hpp>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <fstream>
#include <memory>
#include <numbers>
#include <optional>

namespace pedesis {

namespace {

template <int D>
std::unique_ptr<EventEngine<D>> load_checkpoint(const std::filesystem::path& path,
                                                const RunConfig& c, HardRunRecord<D>& s) {
    return load_hard_checkpoint<EventEngine<D>>(
        path, event_checkpoint_magic, event_engine, event_params(c), c, s,
        [](const EventEngine<D>& e) -> const ParticleStore<D>& { return e.lazy_particles(); });
}

// The event-driven engine as the Simulation drives it. Its clock is continuous: it
// stops exactly at each trigger time, so frames and rows lie on the time grid.
template <int D> class EventRunEngine final : public HardRunEngine<D> {
    using Base = HardRunEngine<D>;
    using Base::c_, Base::o_, Base::console_, Base::record_, Base::out_;

  public:
    EventRunEngine(const RunConfig& c, const RunOptions& o, std::ostream& console)
        : HardRunEngine<D>(c, o, console) {
        Box<D> box = build_box<D>(c_);
        if (c_.shear_rate > 0.0) box.set_shear_rate(c_.shear_rate);
        if (o_.restart) {
            engine_ = load_checkpoint<D>(*o_.restart, c_, record_);
            if (engine_->box().shear_rate() != c_.shear_rate)
                throw InputError(
                    fmt::format("{}: [box] shear_rate = {:g} does not match the checkpoint's {:g}",
                                c_.shear_where.empty() ? c_.file : c_.shear_where, c_.shear_rate,
                                engine_->box().shear_rate()));
        } else {
            engine_ = this->with_source([&] {
                return std::make_unique<EventEngine<D>>(build_particles<D>(c_, box), box,
                                                        event_params(c_));
            });
            record_.initial_kinetic = engine_->kinetic_energy();
            record_.start_from(
                measure_kinetics(engine_->lazy_particles(), box, hard_particle_dynamics));
            record_.histogram = SpeedHistogram(c_.species.size(), c_.histogram_bins);
        }
        this->keep_msd_origin(engine_->unwrapped_now(), engine_->time());
        this->start_transport_if_asked(*engine_, engine_->lazy_particles(), 0.0);
        growing_ = c_.growth_rate > 0;
        const std::size_t n = engine_->size();
        t_end_ = c_.stop_time.value_or(std::numeric_limits<double>::infinity());
        if (c_.stop_collisions_per_particle)
            limits_.pair_collisions = static_cast<std::uint64_t>(
                std::ceil(*c_.stop_collisions_per_particle * static_cast<double>(n)));
        if (c_.stop_energy_fraction)
            limits_.min_kinetic_energy = *c_.stop_energy_fraction * record_.initial_kinetic;
        // (the stepped engine's refusal: a run with nothing left to do would end at once and
        // pass for one that ran)
        if (const char* why = o_.restart ? stop_met() : nullptr)
            throw InputError(fmt::format(
                "{}: the checkpoint {} is at t = {:g} ({} collisions), which already meets the "
                "{}",
                c_.file, o_.restart->string(), engine_->time(), step(), raise_stop(o_, why)));
    }

    // The collisions so far stand in for steps, which this engine does not have.
    std::uint64_t step() const override {
        return engine_->counters().pair_collisions + engine_->counters().wall_collisions;
    }
    double time() const override { return engine_->time(); }

    Advance advance(std::uint64_t /*until_step*/, double until_time) override {
        const double until = std::min(until_time, t_end_);
        StopReason reason = StopReason::time;
        // [transport]'s samples come at their own times, between the Simulation's
        for (;;) {
            const bool sampling = record_.transport && record_.transport->next_time() <= until;
            limits_.time = sampling ? record_.transport->next_time() : until;
            reason = engine_->run(limits_);
            if (reason != StopReason::time || !sampling) break;
            this->sample_transport(*engine_);
            // (samples closer than events return at once from run(), which then never
            // looks for a signal)
            if (interrupt_requested()) return {};
            if (engine_->time() >= until) break;
        }
        if (reason == StopReason::interrupted) return {}; // the Simulation sees the signal
        if (reason == StopReason::grown) announce_growth_end();
        const bool stop = (reason != StopReason::time && reason != StopReason::grown) ||
                          (reason == StopReason::grown && c_.stop_when_grown) ||
                          engine_->time() >= t_end_;
        return {stop ? reason_name(reason) : nullptr, reason == StopReason::grown};
    }

    Frame<D> frame() override {
        snapshot_ = engine_->snapshot(&images_);
        return Frame<D>{engine_->box(), snapshot_, engine_->time(), step(),
                        nullptr,        nullptr,   &images_};
    }

    void save_checkpoint(const std::filesystem::path& path) override {
        save_hard_checkpoint(path, event_checkpoint_magic, *engine_, record_);
    }

    std::vector<std::string> log_columns() const override {
        std::vector<std::string> c = out_.log_columns();
        c.push_back("list_rebuilds");
        if (growing_) c.insert(c.end(), {"packing_fraction", "growth_pressure"});
        if (engine_->falling()) c.insert(c.end(), {"potential_energy", "total_energy"});
        if (c_.driving_rate > 0.0) c.push_back("injected_energy");
        if (engine_->wall_moves()) c.insert(c.end(), {"wall_work", "wall_position"});
        return c;
    }

    void measure(std::vector<double>& values) override {
        const auto& e = *engine_;
        // the velocity profile at each row after t = 0 (P_xy: out_.measure)
        if (e.box().sheared() && e.time() > record_.last_log_time)
            record_.shear.add_profile(e.snapshot(), e.box());
        SymTensor kinetic_integral{};
        if (e.box().sheared()) kinetic_integral = e.flux_moments().kinetic_integral;
        const HardMeasurement m =
            out_.measure(e.lazy_particles(), e.box(), e.time(), e.counters(), msd(), values,
                         e.box().sheared() ? &kinetic_integral : nullptr);
        values.push_back(static_cast<double>(e.counters().list_rebuilds));
        if (growing_) values.insert(values.end(), {e.packing_fraction(), e.growth().last_pressure});
        if (e.falling()) {
            const double u = e.potential_energy();
            values.insert(values.end(), {u, u + e.kinetic_energy()});
        }
        if (c_.driving_rate > 0.0) values.push_back(e.driving().injected_energy);
        if (e.wall_moves()) values.insert(values.end(), {e.wall_work(), e.moving_wall_position()});
        progress(m.temperature, m.pressure, m.has_pressure);
    }

    void start(bool /*fresh*/) override {
        console_ << fmt::format(
            "pedesis: {}D event-driven run, N = {}, box {}, eta = {:.4f}, output in {}\n", D,
            engine_->size(), box_text(engine_->box()),
            packing_fraction(engine_->lazy_particles(), engine_->box()), o_.out_dir.string());
        // (every set gives the same trajectory; the speed differs)
        console_ << fmt::format("  CPU kernels: {}\n", simd_name(simd_level()));
        if (engine_->box().sheared())
            console_ << fmt::format("  Lees–Edwards shear at rate {:g}: flow along x, gradient "
                                    "along y, velocities peculiar\n",
                                    engine_->box().shear_rate());
        if (c_.thermostat_temperature > 0.0)
            console_ << fmt::format("  thermostat: velocities rescaled to T = {:g} every {:g}\n",
                                    c_.thermostat_temperature, c_.thermostat_interval);
        if (engine_->falling())
            console_ << fmt::format("  gravity {}: parabolic flights\n",
                                    fmt::join(c_.gravity, ", "));
        if (engine_->wall_moves()) {
            const WallMotion& m = c_.moving_wall;
            const std::string face =
                fmt::format("{} wall of {}", c_.moving_wall_upper ? "upper" : "lower",
                            "xyz"[c_.moving_wall_axis]);
            if (m.vibrated())
                console_ << fmt::format(
                    "  moving wall: the {} vibrates, amplitude {:g}, frequency {:g}\n", face,
                    m.amplitude, m.angular_frequency / (2.0 * std::numbers::pi));
            else
                console_ << fmt::format("  moving wall: the {} moves in at speed {:g}\n", face,
                                        m.speed);
        }
        if (c_.andersen_rate > 0.0)
            console_ << fmt::format(
                "  Andersen thermostat: T = {:g}, each particle redrawn at rate {:g}\n",
                c_.andersen_temperature, c_.andersen_rate);
        if (c_.driving_rate > 0.0)
            console_ << fmt::format("  white-noise driving: each particle kicked at rate {:g}, "
                                    "velocity variance {:g} per component and kick\n",
                                    c_.driving_rate, c_.driving_strength);
        wall_start_ = std::chrono::steady_clock::now();
        collisions_start_ = engine_->counters().pair_collisions;
    }

    nlohmann::json summary(const char* /*stopped_by*/) override {
        const auto& e = *engine_;
        nlohmann::json j = out_.summary(e.lazy_particles(), e.box(), e.time(), e.counters());
        j["cpu_kernels"] = simd_name(simd_level());
        j["msd"] = msd();
        this->transport_summary(j, e.box(), e.lazy_particles());
        if (e.box().sheared()) j["shear"] = record_.shear.summary(e.box().shear_rate());
        if (c_.thermostat_temperature > 0.0)
            j["thermostat"] = {{"temperature", c_.thermostat_temperature},
                               {"interval", c_.thermostat_interval},
                               {"rescales", e.thermostat().rescales},
                               {"energy_removed", e.thermostat().energy_removed}};
        driving_summary(j);
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
        return j;
    }

    void finish(const nlohmann::json& j) override {
        const auto& e = *engine_;
        out_.write_speed_histogram(e.lazy_particles());
        console_ << fmt::format(
            "pedesis: stopped by {} at t = {:.6g} after {} collisions ({:.3g} per particle)\n",
            j["stopped_by"].template get<std::string>(), e.time(), e.counters().pair_collisions,
            j["collisions_per_particle"].template get<double>());
        out_.print_summary(console_, j, e.box());
        if (e.box().sheared()) write_shear_results(o_.out_dir, record_.shear, e.box(), j, console_);
        this->write_transport(j, e.box(), e.lazy_particles());
        console_ << fmt::format("  outputs            {}\n", o_.out_dir.string());
    }

    // restitution (particle-particle) and, in a box with walls, wall_restitution: changed
    // between two collisions. The engine has no steps, so a change is tied to its time
    // (SteeringDesk).
    std::vector<std::pair<std::string, double>> steerable() const override {
        std::vector<std::pair<std::string, double>> out{
            {"restitution", engine_->params().restitution}};
        if (engine_->box().any_wall())
            out.emplace_back("wall_restitution", engine_->params().wall_restitution);
        return out;
    }

    void steer(const std::string& name, double value) override {
        if (name == "restitution")
            engine_->set_restitution(value);
        else if (name == "wall_restitution" && engine_->box().any_wall())
            engine_->set_wall_restitution(value);
        else
            Base::steer(name, value);
    }

  private:
    void driving_summary(nlohmann::json& j) const {
        const auto& e = *engine_;
        if (e.falling())
            j["gravity"] = {{"acceleration", c_.gravity},
                            {"potential_energy", e.potential_energy()},
                            {"total_energy", e.potential_energy() + e.kinetic_energy()}};
        const auto& d = e.driving();
        if (c_.andersen_rate > 0.0)
            j["andersen"] = {{"temperature", c_.andersen_temperature},
                             {"rate", c_.andersen_rate},
                             {"events", d.andersen_events},
                             {"energy_added", d.andersen_energy}};
        if (c_.driving_rate > 0.0)
            j["driving"] = {{"kind", "white_noise"},
                            {"rate", c_.driving_rate},
                            {"strength", c_.driving_strength},
                            {"kicks", d.kicks},
                            {"injected_energy", d.injected_energy},
                            {"injected_power", e.time() > 0 ? d.injected_energy / e.time() : 0.0}};
        if (e.wall_moves()) {
            const WallMotion& m = c_.moving_wall;
            nlohmann::json w = {{"axis", std::string(1, "xyz"[c_.moving_wall_axis])},
                                {"side", c_.moving_wall_upper ? "upper" : "lower"},
                                {"work", e.wall_work()},
                                {"power", e.time() > 0 ? e.wall_work() / e.time() : 0.0},
                                {"checks", e.wall_checks()}};
            if (m.vibrated()) {
                w["amplitude"] = m.amplitude;
                w["frequency"] = m.angular_frequency / (2.0 * std::numbers::pi);
            } else {
                w["speed"] = m.speed;
            }
            j["moving_wall"] = w;
        }
    }

    double msd() const {
        return mean_squared_displacement(engine_->lazy_particles(), engine_->unwrapped_now(),
                                         record_.start);
    }

    // The stop condition a restored state meets already (the clock within the rounding of
    // Simulation's time limit), or null.
    const char* stop_met() const {
        const auto& e = *engine_;
        if (e.time() >= t_end_ - 1e-9 * std::max(1.0, std::abs(t_end_)))
            return reason_name(StopReason::time);
        if (e.counters().pair_collisions >= limits_.pair_collisions)
            return reason_name(StopReason::collisions);
        if (e.kinetic_energy() <= limits_.min_kinetic_energy)
            return reason_name(StopReason::energy);
        return nullptr;
    }

    static const char* reason_name(StopReason reason) {
        return reason == StopReason::time         ? "time"
               : reason == StopReason::collisions ? "collisions_per_particle"
               : reason == StopReason::energy     ? "energy_fraction"
               : reason == StopReason::grown      ? "grown"
                                                  : "no more events";
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

    std::unique_ptr<EventEngine<D>> engine_;
    StopLimits limits_;
    double t_end_ = std::numeric_limits<double>::infinity();
    ParticleStore<D> snapshot_;         // the positions of the last frame, all at one instant
    std::vector<ImageCount<D>> images_; // and their image counts
    std::chrono::steady_clock::time_point wall_start_ = std::chrono::steady_clock::now();
    std::optional<std::chrono::steady_clock::time_point> last_progress_;
    std::uint64_t collisions_start_ = 0;
    bool growing_ = false; // growth configured: log packing fraction and pressure
};

} // namespace

template <int D>
EngineSetup<D> event_engine_setup(const RunConfig& config, const RunOptions& options,
                                  std::ostream& console) {
    return hard_engine_setup<EventRunEngine, D>(config, options, console);
}

template EngineSetup<2> event_engine_setup<2>(const RunConfig&, const RunOptions&, std::ostream&);
template EngineSetup<3> event_engine_setup<3>(const RunConfig&, const RunOptions&, std::ostream&);

} // namespace pedesis
