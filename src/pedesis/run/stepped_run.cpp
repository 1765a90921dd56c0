#include "pedesis/run/stepped_run.hpp"

#include "pedesis/run/engine_params.hpp"

#include "pedesis/core/error.hpp"
#include "pedesis/io/atomic_file.hpp"
#include "pedesis/io/binary_stream.hpp"
#include "pedesis/observe/pressure.hpp"
#include "pedesis/observe/thermo.hpp"
#include "pedesis/run/hard_checkpoint.hpp"
#include "pedesis/run/hard_run_output.hpp"
#include "pedesis/setup/build_system.hpp"
#include "pedesis/stepped/stepped_engine.hpp"
#include "pedesis/stepped/time_step.hpp"

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include <cmath>
#include <fstream>
#include <limits>
#include <memory>

namespace pedesis {

namespace {

constexpr std::uint64_t stepped_checkpoint_magic = 0x31305054535f4550ull; // "PE_STP01"

template <int D>
void save_checkpoint(const std::filesystem::path& path, const SteppedEngine<D>& e,
                     const HardRunRecord<D>& s) {
    save_hard_checkpoint(path, stepped_checkpoint_magic, e, s);
}

template <int D>
std::unique_ptr<SteppedEngine<D>> load_checkpoint(const std::filesystem::path& path,
                                                  const RunConfig& c, HardRunRecord<D>& s) {
    return load_hard_checkpoint<SteppedEngine<D>>(
        path, stepped_checkpoint_magic, "not a checkpoint of a stepped run", stepped_params(c), c,
        s, [](const SteppedEngine<D>& e) -> const std::vector<Species>& {
            return e.particles().species_table;
        });
}

// Independent speeds the rest of the run will draw, for the suggested dt: N at the
// start and N again per collision per particle, up to the first stop condition.
template <int D>
double run_speed_samples(const ParticleStore<D>& p, const Box<D>& box, const RunConfig& c,
                         double now, std::uint64_t step, std::uint64_t pair_collisions) {
    double collisions = std::numeric_limits<double>::infinity();
    if (c.stop_time) collisions = expected_collisions_per_particle(p, box, *c.stop_time - now);
    if (c.stop_steps && *c.stop_steps > step)
        collisions =
            std::min(collisions, expected_collisions_per_particle(
                                     p, box, static_cast<double>(*c.stop_steps - step) * c.dt));
    if (c.stop_collisions_per_particle)
        collisions = std::min(collisions, 2.0 * (*c.stop_collisions_per_particle -
                                                 static_cast<double>(pair_collisions) /
                                                     static_cast<double>(p.size())));
    return static_cast<double>(p.size()) * (1.0 + std::max(collisions, 0.0));
}

// Only then is the running pressure the notebook's wall pressure on every axis.
template <int D> bool all_walls(const Box<D>& box) {
    for (int a = 0; a < D; ++a)
        if (box.periodic(a)) return false;
    return true;
}

template <int D> class SteppedRun {
  public:
    SteppedRun(const RunConfig& c, const RunOptions& o, std::ostream& console)
        : c_(c), o_(o), console_(console), out_(c, o, state_) {}

    void execute() {
        const Box<D> box = build_box<D>(c_);
        if (o_.restart) {
            engine_ = load_checkpoint<D>(*o_.restart, c_, state_);
            const auto& e = *engine_;
            samples_ = run_speed_samples(e.particles(), e.box(), c_, e.time(), e.steps(),
                                         e.counters().pair_collisions);
            check_time_step(e.particles(), c_.dt, c_.max_move, c_.dt_where, samples_);
        } else {
            ParticleStore<D> p = build_particles<D>(c_, box);
            samples_ = run_speed_samples(p, box, c_, 0.0, 0, 0);
            check_time_step(p, c_.dt, c_.max_move, c_.dt_where, samples_);
            engine_ = std::make_unique<SteppedEngine<D>>(std::move(p), box, stepped_params(c_));
            state_.initial_kinetic = engine_->kinetic_energy();
            state_.last_temperature =
                measure_kinetics(engine_->particles(), box, hard_particle_dynamics).temperature();
            state_.histogram = SpeedHistogram(c_.species.size(), c_.histogram_bins);
        }
        const std::size_t n = engine_->size();
        if (c_.stop_collisions_per_particle)
            collision_limit_ = static_cast<std::uint64_t>(
                std::ceil(*c_.stop_collisions_per_particle * static_cast<double>(n)));
        // (a fresh run always makes at least one step)
        if (const char* why = o_.restart ? stop_reason() : nullptr)
            throw InputError(fmt::format(
                "{}: the checkpoint {} is at t = {:g} (step {}), which already meets the stop "
                "condition ({}); raise it in [run] to continue",
                c_.file, o_.restart->string(), engine_->time(), engine_->steps(), why));
        out_.open(",step,v_rms,mean_speed,pressure_running");

        const auto& e = *engine_;
        const double suggested = suggested_time_step(e.particles(), c_.max_move, samples_);
        console_ << fmt::format("pedesis: {}D stepped run, N = {}, box {}, eta = {:.4f}, dt = {:g} "
                                "(at most {:g} radii per step), output in {}\n",
                                D, n, box_text(e.box()), packing_fraction(e.particles(), e.box()),
                                c_.dt, c_.max_move, o_.out_dir.string());
        if (c_.dt > suggested)
            console_ << fmt::format(
                "  note: dt is above {:.2g}, the largest that also suits the fastest particles "
                "this run is likely to see; if one of them gets that fast the run stops (exit "
                "3)\n",
                suggested);
        if (!o_.restart) {
            log_row();
            frame();
        }
        const double t_end = c_.stop_time.value_or(std::numeric_limits<double>::infinity());
        double next_log = next_multiple(e.time(), c_.log_interval);
        double next_snap =
            c_.snapshot_interval > 0 ? next_multiple(e.time(), c_.snapshot_interval) : t_end;
        double next_ckpt =
            c_.checkpoint_interval > 0 ? next_multiple(e.time(), c_.checkpoint_interval) : t_end;
        // a step whose time is within rounding of a multiple belongs to it
        auto reached = [&](double t, double target, double interval) {
            return t >= target - 1e-9 * interval;
        };
        const char* why = nullptr;
        try {
            while (!why) {
                engine_->step();
                why = stop_reason();
                const double t = e.time();
                if (reached(t, next_log, c_.log_interval) || why) {
                    log_row();
                    next_log = next_multiple(t, c_.log_interval);
                }
                if (c_.snapshot_interval > 0 && reached(t, next_snap, c_.snapshot_interval) &&
                    !why) {
                    frame();
                    next_snap = next_multiple(t, c_.snapshot_interval);
                }
                if (c_.checkpoint_interval > 0 && reached(t, next_ckpt, c_.checkpoint_interval) &&
                    !why) {
                    save_checkpoint(o_.out_dir / "checkpoint.bin", e, state_);
                    next_ckpt = next_multiple(t, c_.checkpoint_interval);
                }
            }
        } catch (const RunError& err) {
            // keep what is good: frames so far, the log, and the last checkpoint
            out_.close();
            throw RunError(std::string(err.what()) +
                           " (the log, the frames and the last checkpoint written so far are in " +
                           o_.out_dir.string() + ")");
        }
        finish(why);
    }

  private:
    // The first stop condition of [run] that the engine has met, or nullptr.
    const char* stop_reason() const {
        const auto& e = *engine_;
        if (c_.stop_steps && e.steps() >= *c_.stop_steps) return "steps";
        if (c_.stop_time && e.time() >= *c_.stop_time - 1e-9 * e.dt()) return "time";
        if (c_.stop_collisions_per_particle && e.counters().pair_collisions >= collision_limit_)
            return "collisions_per_particle";
        return nullptr;
    }

    // The running pressure of the notebook: everything the walls (or, on periodic axes,
    // the collisions) have received since t = 0, over the whole time.
    double running_pressure(double degrees_of_freedom) const {
        const auto& e = *engine_;
        const double t = e.time();
        if (!(t > 0)) return 0.0;
        return interval_pressure(e.box(), EventCounters<D>{}, e.counters(), t,
                                 state_.integral_T_dt / t, degrees_of_freedom);
    }

    void frame() {
        const auto& e = *engine_;
        out_.frame(Frame<D>{e.box(), e.particles(), e.time(), e.steps()});
    }

    void log_row() {
        const auto& e = *engine_;
        const LogRow row = out_.measure(e.particles(), e.box(), e.time(), e.counters());
        double sum_v2 = 0.0, sum_v = 0.0;
        for (std::size_t i = 0; i < e.size(); ++i) {
            if (std::isinf(e.particles().mass(i))) continue;
            const double v2 = norm2(e.particles().velocity[i]);
            sum_v2 += v2;
            sum_v += std::sqrt(v2);
        }
        const auto mobile =
            static_cast<double>(std::max<std::size_t>(row.kinetics.total_mobile, 1));
        const double v_rms = std::sqrt(sum_v2 / mobile);
        const double P_run = running_pressure(row.kinetics.total_freedom);
        out_.append_log(row.csv + fmt::format(",{},{:.8g},{:.8g},{:.8g}\n", e.steps(), v_rms,
                                              sum_v / mobile, P_run));
        // the notebook's line, once per log row
        if (c_.progress)
            console_ << fmt::format("  Iteration: {:<9d} Time: {:<11.4E} V_RMS: {:<11.4E} {}: {}\n",
                                    e.steps(), e.time(), v_rms,
                                    all_walls(e.box()) ? "Wall Pressure" : "Pressure",
                                    e.time() > 0 ? fmt::format("{:.6g}", P_run) : "-");
    }

    void finish(const char* why) {
        const auto& e = *engine_;
        frame();
        save_checkpoint(o_.out_dir / "checkpoint.bin", e, state_);
        out_.write_speed_histogram(e.particles());
        out_.close();

        nlohmann::json j = out_.summary(e.particles(), e.box(), e.time(), e.counters());
        const auto C = e.counters().pair_collisions;
        j["dynamics"] = "stepped";
        j["stopped_by"] = why;
        j["dt"] = e.dt();
        j["steps"] = e.steps();
        j["max_move"] = c_.max_move;
        j["late_collisions"] = e.stats().late_collisions;
        j["late_fraction"] =
            C ? static_cast<double>(e.stats().late_collisions) / static_cast<double>(C) : 0.0;
        j["chained_events"] = e.stats().chained_events;
        j["most_events_in_step"] = e.stats().most_events_in_step;
        out_.write_summary(j);

        console_ << fmt::format("pedesis: stopped by {} at t = {:.6g} (step {}) after {} "
                                "collisions ({:.3g} per particle)\n",
                                why, e.time(), e.steps(), C,
                                j["collisions_per_particle"].template get<double>());
        out_.print_summary(console_, j, e.box());
        console_ << fmt::format(
            "  late collisions    {} ({:.3g} of all: from an overlap left by a grazing "
            "collision missed within a step; fewer with a smaller dt)\n",
            e.stats().late_collisions, j["late_fraction"].template get<double>());
        console_ << fmt::format("  outputs            {}\n", o_.out_dir.string());
    }

    const RunConfig& c_;
    const RunOptions& o_;
    std::ostream& console_;
    std::unique_ptr<SteppedEngine<D>> engine_;
    HardRunRecord<D> state_;
    HardRunOutput<D> out_;
    std::uint64_t collision_limit_ = std::numeric_limits<std::uint64_t>::max();
    double samples_ = 1.0; // independent speeds the run will draw, for the suggested dt
};

} // namespace

void run_stepped_simulation(const RunConfig& config, const RunOptions& options,
                            std::ostream& console) {
    if (config.dimension == 2)
        SteppedRun<2>(config, options, console).execute();
    else
        SteppedRun<3>(config, options, console).execute();
}

} // namespace pedesis
