#include "pedesis/run/stepped_run.hpp"

#include "pedesis/run/engine_params.hpp"

#include "pedesis/core/error.hpp"
#include "pedesis/io/atomic_file.hpp"
#include "pedesis/io/binary_stream.hpp"
#include "pedesis/observe/pressure.hpp"
#include "pedesis/observe/thermo.hpp"
#include "pedesis/run/hard_checkpoint.hpp"
#include "pedesis/run/hard_run_engine.hpp"
#include "pedesis/run/hard_run_output.hpp"
#include "pedesis/run/shear_output.hpp"
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

template <int D>
std::unique_ptr<SteppedEngine<D>> load_checkpoint(const std::filesystem::path& path,
                                                  const RunConfig& c, HardRunRecord<D>& s) {
    return load_hard_checkpoint<SteppedEngine<D>>(
        path, stepped_checkpoint_magic, stepped_engine, stepped_params(c), c, s,
        [](const SteppedEngine<D>& e) -> const ParticleStore<D>& { return e.particles(); });
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

// The time-stepped hard-particle engine as the Simulation drives it: one step per
// advance, so that every step is checked against the stop conditions and triggers.
template <int D> class SteppedRunEngine final : public HardRunEngine<D> {
    using Base = HardRunEngine<D>;
    using Base::c_, Base::o_, Base::console_, Base::record_, Base::out_;

  public:
    SteppedRunEngine(const RunConfig& c, const RunOptions& o, std::ostream& console)
        : HardRunEngine<D>(c, o, console) {
        Box<D> box = build_box<D>(c_);
        if (c_.shear_rate > 0.0) box.set_shear_rate(c_.shear_rate);
        if (o_.restart) {
            engine_ = load_checkpoint<D>(*o_.restart, c_, record_);
            const auto& e = *engine_;
            if (e.box().shear_rate() != c_.shear_rate)
                throw InputError(
                    fmt::format("{}: [box] shear_rate = {:g} does not match the checkpoint's {:g}",
                                c_.shear_where.empty() ? c_.file : c_.shear_where, c_.shear_rate,
                                e.box().shear_rate()));
            samples_ = run_speed_samples(e.particles(), e.box(), c_, e.time(), e.steps(),
                                         e.counters().pair_collisions);
            check_time_step(e.particles(), c_.dt, c_.max_move, c_.dt_where, samples_);
        } else {
            ParticleStore<D> p = build_particles<D>(c_, box);
            samples_ = run_speed_samples(p, box, c_, 0.0, 0, 0);
            check_time_step(p, c_.dt, c_.max_move, c_.dt_where, samples_);
            engine_ = this->with_source([&] {
                return std::make_unique<SteppedEngine<D>>(std::move(p), box, stepped_params(c_));
            });
            record_.initial_kinetic = engine_->kinetic_energy();
            record_.start_from(measure_kinetics(engine_->particles(), box, hard_particle_dynamics));
            record_.histogram = SpeedHistogram(c_.species.size(), c_.histogram_bins);
        }
        this->keep_msd_origin(unwrapped_now(), engine_->time());
        this->start_transport_if_asked(*engine_, engine_->particles(), engine_->dt());
        if (c_.stop_collisions_per_particle)
            collision_limit_ = static_cast<std::uint64_t>(
                std::ceil(*c_.stop_collisions_per_particle * static_cast<double>(engine_->size())));
        // (a fresh run always makes at least one step)
        if (const char* why = o_.restart ? stop_reason() : nullptr)
            throw InputError(fmt::format(
                "{}: the checkpoint {} is at t = {:g} (step {}), which already meets the {}",
                c_.file, o_.restart->string(), engine_->time(), engine_->steps(),
                raise_stop(o_, why)));
    }

    std::uint64_t step() const override { return engine_->steps(); }
    double time() const override { return engine_->time(); }

    Advance advance(std::uint64_t, double) override {
        // [transport]'s samples fall on steps (its interval is a whole number of them)
        if (this->transport_due(engine_->time(), engine_->dt())) this->sample_transport(*engine_);
        engine_->step();
        if (this->transport_due(engine_->time(), engine_->dt())) this->sample_transport(*engine_);
        return {stop_reason(), false};
    }

    Frame<D> frame() override {
        const auto& e = *engine_;
        return Frame<D>{e.box(), e.particles(), e.time(), e.steps(), nullptr, nullptr, &e.images()};
    }

    void save_checkpoint(const std::filesystem::path& path) override {
        save_hard_checkpoint(path, stepped_checkpoint_magic, *engine_, record_);
    }

    std::vector<std::string> log_columns() const override {
        std::vector<std::string> c = out_.log_columns();
        c.insert(c.end(), {"step", "v_rms", "mean_speed", "pressure_running"});
        if (engine_->falling()) c.insert(c.end(), {"potential_energy", "total_energy"});
        return c;
    }

    void measure(std::vector<double>& values) override {
        const auto& e = *engine_;
        // the velocity profile at each row after t = 0 (P_xy, from the exact kinetic
        // integral: out_.measure)
        if (e.box().sheared() && e.time() > record_.last_log_time)
            record_.shear.add_profile(e.particles(), e.box());
        SymTensor kinetic_integral{};
        if (e.box().sheared()) kinetic_integral = e.flux_moments().kinetic_integral;
        const HardMeasurement m =
            out_.measure(e.particles(), e.box(), e.time(), e.counters(), msd(), values,
                         e.box().sheared() ? &kinetic_integral : nullptr);
        double sum_v2 = 0.0, sum_v = 0.0;
        for (std::size_t i = 0; i < e.size(); ++i) {
            if (std::isinf(e.particles().mass(i))) continue;
            const double v2 = norm2(e.particles().velocity[i]);
            sum_v2 += v2;
            sum_v += std::sqrt(v2);
        }
        const auto mobile = static_cast<double>(std::max<std::size_t>(m.kinetics.total_mobile, 1));
        const double v_rms = std::sqrt(sum_v2 / mobile);
        const double P_run = running_pressure();
        // the notebook's line, once per log row
        if (c_.progress)
            console_ << fmt::format("  Iteration: {:<9d} Time: {:<11.4E} V_RMS: {:<11.4E} {}: {}\n",
                                    e.steps(), e.time(), v_rms,
                                    all_walls(e.box()) ? "Wall Pressure" : "Pressure",
                                    e.time() > 0 ? fmt::format("{:.6g}", P_run) : "-");
        values.insert(values.end(), {static_cast<double>(e.steps()), v_rms, sum_v / mobile, P_run});
        if (e.falling()) {
            const double u = e.potential_energy();
            values.insert(values.end(), {u, u + e.kinetic_energy()});
        }
    }

    void start(bool /*fresh*/) override {
        const auto& e = *engine_;
        const double suggested = suggested_time_step(e.particles(), c_.max_move, samples_);
        console_ << fmt::format("pedesis: {}D stepped run, N = {}, box {}, eta = {:.4f}, dt = {:g} "
                                "(at most {:g} radii per step), output in {}\n",
                                D, e.size(), box_text(e.box()),
                                packing_fraction(e.particles(), e.box()), c_.dt, c_.max_move,
                                o_.out_dir.string());
        if (e.box().sheared())
            console_ << fmt::format("  Lees–Edwards shear at rate {:g}: flow along x, gradient "
                                    "along y, frames' velocities peculiar\n",
                                    e.box().shear_rate());
        if (c_.dt > suggested)
            console_ << fmt::format(
                "  note: dt is above {:.2g}, the largest that also suits the fastest particles "
                "this run is likely to see; if one of them gets that fast the run stops (exit "
                "3)\n",
                suggested);
    }

    nlohmann::json summary(const char* /*stopped_by*/) override {
        const auto& e = *engine_;
        nlohmann::json j = out_.summary(e.particles(), e.box(), e.time(), e.counters());
        const auto C = e.counters().pair_collisions;
        j["dynamics"] = "stepped";
        j["msd"] = msd();
        this->transport_summary(j, e.box(), e.particles());
        j["dt"] = e.dt();
        j["steps"] = e.steps();
        j["max_move"] = c_.max_move;
        j["late_collisions"] = e.stats().late_collisions;
        j["late_fraction"] =
            C ? static_cast<double>(e.stats().late_collisions) / static_cast<double>(C) : 0.0;
        j["chained_events"] = e.stats().chained_events;
        j["most_events_in_step"] = e.stats().most_events_in_step;
        if (e.falling())
            j["gravity"] = {{"acceleration", c_.gravity},
                            {"potential_energy", e.potential_energy()},
                            {"total_energy", e.potential_energy() + e.kinetic_energy()}};
        if (e.box().sheared()) j["shear"] = record_.shear.summary(e.box().shear_rate());
        return j;
    }

    void finish(const nlohmann::json& j) override {
        const auto& e = *engine_;
        out_.write_speed_histogram(e.particles());
        console_ << fmt::format("pedesis: stopped by {} at t = {:.6g} (step {}) after {} "
                                "collisions ({:.3g} per particle)\n",
                                j["stopped_by"].template get<std::string>(), e.time(), e.steps(),
                                e.counters().pair_collisions,
                                j["collisions_per_particle"].template get<double>());
        out_.print_summary(console_, j, e.box());
        if (e.box().sheared()) write_shear_results(o_.out_dir, record_.shear, e.box(), j, console_);
        this->write_transport(j, e.box(), e.particles());
        console_ << fmt::format(
            "  late collisions    {} ({:.3g} of all: from an overlap left by a grazing "
            "collision missed within a step; fewer with a smaller dt)\n",
            e.stats().late_collisions, j["late_fraction"].template get<double>());
        console_ << fmt::format("  outputs            {}\n", o_.out_dir.string());
    }

  private:
    std::vector<Vec<D>> unwrapped_now() const {
        const auto& e = *engine_;
        return unwrapped_positions<D>(e.box(), e.particles().position, e.images());
    }
    double msd() const {
        return mean_squared_displacement(engine_->particles(), unwrapped_now(), record_.start);
    }

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
    double running_pressure() const {
        const auto& e = *engine_;
        const double t = e.time();
        if (!(t > 0)) return 0.0;
        return interval_pressure(e.box(), EventCounters<D>{}, e.counters(), t,
                                 record_.mean_thermal(t));
    }

    std::unique_ptr<SteppedEngine<D>> engine_;
    std::uint64_t collision_limit_ = std::numeric_limits<std::uint64_t>::max();
    double samples_ = 1.0; // independent speeds the run will draw, for the suggested dt
};

} // namespace

template <int D>
EngineSetup<D> stepped_engine_setup(const RunConfig& config, const RunOptions& options,
                                    std::ostream& console) {
    return hard_engine_setup<SteppedRunEngine, D>(config, options, console);
}

template EngineSetup<2> stepped_engine_setup<2>(const RunConfig&, const RunOptions&, std::ostream&);
template EngineSetup<3> stepped_engine_setup<3>(const RunConfig&, const RunOptions&, std::ostream&);

} // namespace pedesis
