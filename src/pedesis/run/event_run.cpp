#include "pedesis/run/event_run.hpp"

#include "pedesis/core/error.hpp"
#include "pedesis/event/event_engine.hpp"
#include "pedesis/io/atomic_file.hpp"
#include "pedesis/io/binary_stream.hpp"
#include "pedesis/io/tutorial_json.hpp"
#include "pedesis/io/xyz_writer.hpp"
#include "pedesis/observe/pressure.hpp"
#include "pedesis/observe/speed_histogram.hpp"
#include "pedesis/observe/theory.hpp"
#include "pedesis/observe/thermo.hpp"
#include "pedesis/setup/build_system.hpp"

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <fstream>
#include <memory>
#include <numbers>
#include <sstream>

namespace pedesis {

namespace {

constexpr std::uint64_t run_checkpoint_magic = 0x31304e5552444550ull; // "PEDRUN01"

// What the run directory needs besides the engine, saved in the checkpoint too.
template <int D> struct RunState {
    double initial_kinetic = 0.0;
    double integral_T_dt = 0.0; // for the kinetic part of the run-averaged pressure
    double last_log_time = 0.0;
    double last_temperature = 0.0;
    EventCounters<D> last_counters{};
    std::uint64_t frames = 0;
    SpeedHistogram histogram;

    // The plain fields in checkpoint order; one list serves saving and loading.
    template <class Self, class F> static void for_each_scalar(Self& s, F&& f) {
        f(s.initial_kinetic);
        f(s.integral_T_dt);
        f(s.last_log_time);
        f(s.last_temperature);
        f(s.last_counters);
        f(s.frames);
    }
};

template <int D> EventParams event_params(const RunConfig& c) {
    EventParams p;
    p.restitution = c.restitution;
    p.wall_restitution = c.wall_restitution;
    p.tc = c.tc;
    p.skin = c.skin;
    p.check_overlaps = c.check_overlaps;
    return p;
}

template <int D>
void save_checkpoint(const std::filesystem::path& path, const EventEngine<D>& e,
                     const RunState<D>& s) {
    write_file_atomically(
        path,
        [&](std::ostream& out) {
            binary::put(out, run_checkpoint_magic);
            e.save(out);
            RunState<D>::for_each_scalar(s, [&](const auto& v) { binary::put(out, v); });
            s.histogram.save(out);
        },
        true);
}

template <int D>
std::unique_ptr<EventEngine<D>> load_checkpoint(const std::filesystem::path& path,
                                                const RunConfig& c, RunState<D>& s) {
    std::ifstream in(path, std::ios::binary);
    if (!in) throw InputError(path.string() + ": cannot open checkpoint");
    try {
        std::uint64_t magic = 0;
        binary::get(in, magic);
        if (magic != run_checkpoint_magic) throw InputError("not a pedesis run checkpoint");
        auto e = std::make_unique<EventEngine<D>>(EventEngine<D>::load(in, event_params<D>(c)));
        RunState<D>::for_each_scalar(s, [&](auto& v) { binary::get(in, v); });
        s.histogram.load(in);
        const auto& table = e->lazy_particles().species_table;
        if (table.size() != c.species.size()) throw InputError("species do not match " + c.file);
        for (std::size_t k = 0; k < table.size(); ++k)
            if (table[k].name != c.species[k].name || table[k].radius != c.species[k].radius ||
                !(table[k].mass == c.species[k].mass))
                throw InputError("species '" + table[k].name + "' does not match " + c.file);
        for (int a = 0; a < D; ++a)
            if (e->box().length(a) != c.box_lengths[static_cast<std::size_t>(a)] ||
                e->box().periodic(a) != c.periodic[static_cast<std::size_t>(a)])
                throw InputError("box does not match " + c.file);
        return e;
    } catch (const InputError& err) {
        throw InputError(path.string() + ": " + err.what());
    }
}

template <int D> double packing_fraction(const ParticleStore<D>& p, const Box<D>& box) {
    double v = 0.0;
    for (std::size_t i = 0; i < p.size(); ++i) {
        const double r = p.radius(i);
        v += D == 2 ? std::numbers::pi * r * r : 4.0 / 3.0 * std::numbers::pi * r * r * r;
    }
    return v / box.volume();
}

template <int D> class EventRun {
  public:
    EventRun(const RunConfig& c, const RunOptions& o, std::ostream& console)
        : c_(c), o_(o), console_(console) {}

    void execute() {
        const Box<D> box = build_box<D>(c_);
        if (o_.restart) {
            engine_ = load_checkpoint<D>(*o_.restart, c_, state_);
        } else {
            engine_ = std::make_unique<EventEngine<D>>(build_particles<D>(c_, box), box,
                                                       event_params<D>(c_));
            state_.initial_kinetic = engine_->kinetic_energy();
            state_.last_temperature = measure_kinetics(engine_->lazy_particles()).temperature(D);
            state_.histogram = SpeedHistogram(c_.species.size(), c_.histogram_bins);
        }
        prepare_directory();
        const std::size_t n = engine_->size();
        mobile_ = measure_kinetics(engine_->lazy_particles()).total_mobile;

        StopLimits limits;
        const double t_end = c_.stop_time.value_or(std::numeric_limits<double>::infinity());
        if (c_.stop_collisions_per_particle)
            limits.pair_collisions = static_cast<std::uint64_t>(
                std::ceil(*c_.stop_collisions_per_particle * static_cast<double>(n)));
        if (c_.stop_energy_fraction)
            limits.min_kinetic_energy = *c_.stop_energy_fraction * state_.initial_kinetic;

        console_ << fmt::format(
            "pedesis: {}D event-driven run, N = {}, box {}, eta = {:.4f}, output in {}\n", D, n,
            box_text(), packing_fraction(engine_->lazy_particles(), engine_->box()),
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
                const bool stop = reason != StopReason::time || t >= t_end;
                if (t >= next_log || stop) {
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
            close_streams();
            throw RunError(std::string(e.what()) +
                           " (the log, the frames and the last checkpoint written so far are in " +
                           o_.out_dir.string() + ")");
        }
        finish(reason);
    }

  private:
    static const char* pressure_method(const Box<D>& box) {
        bool wall = false, periodic = false;
        for (int a = 0; a < D; ++a) (box.periodic(a) ? periodic : wall) = true;
        if (wall && periodic) return "walls on walled axes, collision virial on periodic axes";
        return wall ? "momentum delivered to the walls" : "collision virial";
    }

    static double next_multiple(double t, double step) {
        return (std::floor(t / step + 1e-9) + 1.0) * step;
    }

    std::string box_text() const {
        std::string s;
        for (int a = 0; a < D; ++a)
            s += fmt::format("{}{:g}{}", a ? " x " : "", engine_->box().length(a),
                             engine_->box().periodic(a) ? "p" : "w");
        return s;
    }

    void prepare_directory() {
        std::error_code ec;
        std::filesystem::create_directories(o_.out_dir / "snapshots", ec);
        if (ec)
            throw InputError(o_.out_dir.string() +
                             ": cannot create output directory: " + ec.message());
        // results of an earlier run in this directory must not pass for this run's
        for (const char* stale : {"summary.json", "speed_histogram.csv"})
            std::filesystem::remove(o_.out_dir / stale, ec);
        std::ifstream cfg(o_.config_path);
        std::stringstream text;
        text << cfg.rdbuf();
        write_file_atomically(o_.out_dir / "config.toml",
                              [&](std::ostream& out) { out << text.str(); });
        log_ = std::make_unique<AtomicAppendFile>(o_.out_dir / "log.csv");
        std::string header =
            "time,collisions,collisions_per_particle,wall_collisions,kinetic_energy,"
            "energy_fraction,temperature";
        for (const auto& s : c_.species)
            header += ",temperature_" + s.name + ",kinetic_energy_" + s.name;
        header += ",pressure,pressure_ideal,compressibility,mean_free_time,list_rebuilds\n";
        log_->append(header);
        if (wants("xyz"))
            trajectory_ = std::make_unique<AtomicAppendFile>(o_.out_dir / "trajectory.xyz");
    }

    bool wants(const std::string& f) const {
        return std::find(c_.formats.begin(), c_.formats.end(), f) != c_.formats.end();
    }

    void log_row() {
        const auto& e = *engine_;
        const auto k = measure_kinetics(e.lazy_particles());
        const double t = e.time();
        const double T = k.temperature(D);
        const double dt = t - state_.last_log_time;
        const double meanT = 0.5 * (T + state_.last_temperature);
        const double P = interval_pressure(e.box(), state_.last_counters, e.counters(), dt, meanT,
                                           k.total_mobile);
        state_.integral_T_dt += meanT * dt;
        const double n = static_cast<double>(e.size());
        const auto C = e.counters().pair_collisions;
        const double P_ideal = static_cast<double>(k.total_mobile) * meanT / e.box().volume();
        std::string row = fmt::format(
            "{:.10g},{},{:.6g},{},{:.10g},{:.8g},{:.8g}", t, C, static_cast<double>(C) / n,
            e.counters().wall_collisions, k.total_kinetic,
            state_.initial_kinetic > 0 ? k.total_kinetic / state_.initial_kinetic : 0.0, T);
        for (std::size_t s = 0; s < c_.species.size(); ++s)
            row += fmt::format(",{:.8g},{:.10g}", k.temperature(D, s), k.kinetic[s]);
        const double mft =
            C ? static_cast<double>(k.total_mobile) * t / (2.0 * static_cast<double>(C))
              : std::numeric_limits<double>::infinity();
        row +=
            fmt::format(",{:.8g},{:.8g},{:.8g},{:.8g},{}\n", dt > 0 ? P : 0.0, P_ideal,
                        dt > 0 && P_ideal > 0 ? P / P_ideal : 0.0, mft, e.counters().list_rebuilds);
        log_->append(row);
        if (c_.histogram_start && t >= *c_.histogram_start)
            state_.histogram.add(e.lazy_particles());
        state_.last_log_time = t;
        state_.last_temperature = T;
        state_.last_counters = e.counters();
        progress(T, P, dt > 0);
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

    void frame() {
        const ParticleStore<D> s = engine_->snapshot();
        if (trajectory_) trajectory_->append(xyz_frame(s, engine_->box(), engine_->time()));
        if (wants("json")) {
            const auto j = to_tutorial_json(s, engine_->box(), engine_->time());
            write_file_atomically(o_.out_dir / "snapshots" /
                                      fmt::format("frame_{:06d}.json", state_.frames),
                                  [&](std::ostream& out) { out << j.dump() << "\n"; });
        }
        ++state_.frames;
    }

    void close_streams() {
        if (log_) log_->commit();
        if (trajectory_) trajectory_->commit();
    }

    void finish(StopReason reason) {
        const auto& e = *engine_;
        frame();
        save_checkpoint(o_.out_dir / "checkpoint.bin", e, state_);
        // the final-state sample is not in the checkpoint, so a continued run does not count it
        // twice
        SpeedHistogram histogram = state_.histogram;
        if (!c_.histogram_start) histogram.add(e.lazy_particles());
        std::vector<std::string> names;
        std::vector<double> masses;
        for (const auto& s : c_.species) {
            names.push_back(s.name);
            masses.push_back(s.mass);
        }
        write_file_atomically(o_.out_dir / "speed_histogram.csv", [&](std::ostream& out) {
            histogram.write_csv(out, D, names, masses);
        });
        close_streams();
        write_summary(reason);
    }

    void write_summary(StopReason reason) {
        const auto& e = *engine_;
        const auto k = measure_kinetics(e.lazy_particles());
        const double t = e.time();
        const double V = e.box().volume();
        const double T_avg = t > 0 ? state_.integral_T_dt / t : k.temperature(D);
        const double P =
            interval_pressure(e.box(), EventCounters<D>{}, e.counters(), t, T_avg, k.total_mobile);
        const double P_ideal = static_cast<double>(k.total_mobile) * T_avg / V;
        const double eta = packing_fraction(e.lazy_particles(), e.box());
        const double Z_eos = theory::compressibility_factor(D, eta);
        const auto C = e.counters().pair_collisions;
        const double cpp = static_cast<double>(C) / static_cast<double>(e.size());
        const char* why = reason == StopReason::time         ? "time"
                          : reason == StopReason::collisions ? "collisions_per_particle"
                          : reason == StopReason::energy     ? "energy_fraction"
                                                             : "no more events";
        nlohmann::json j;
        j["dimension"] = D;
        j["particles"] = e.size();
        j["time"] = t;
        j["stopped_by"] = why;
        j["pair_collisions"] = C;
        j["collisions_per_particle"] = cpp;
        j["wall_collisions"] = e.counters().wall_collisions;
        j["packing_fraction"] = eta;
        j["temperature"] = k.temperature(D);
        j["time_averaged_temperature"] = T_avg;
        j["energy_fraction"] =
            state_.initial_kinetic > 0 ? k.total_kinetic / state_.initial_kinetic : 0.0;
        for (std::size_t s = 0; s < c_.species.size(); ++s)
            j["species"][c_.species[s].name] = {{"temperature", k.temperature(D, s)},
                                                {"kinetic_energy", k.kinetic[s]}};
        j["pressure"] = P;
        j["pressure_ideal_gas"] = P_ideal;
        j["compressibility"] = P_ideal > 0 ? P / P_ideal : 0.0;
        j["compressibility_equation_of_state"] = Z_eos;
        if (C)
            j["mean_free_time"] =
                static_cast<double>(k.total_mobile) * t / (2.0 * static_cast<double>(C));
        else
            j["mean_free_time"] = nullptr; // infinite: no collision yet
        write_file_atomically(o_.out_dir / "summary.json",
                              [&](std::ostream& out) { out << j.dump(2) << "\n"; });

        console_ << fmt::format(
            "pedesis: stopped by {} at t = {:.6g} after {} collisions ({:.3g} per particle)\n", why,
            t, C, cpp);
        console_ << fmt::format("  temperature        {:.6g} (time average {:.6g}); energy "
                                "remaining {:.4g} of initial\n",
                                k.temperature(D), T_avg,
                                j["energy_fraction"].template get<double>());
        if (c_.species.size() > 1)
            for (std::size_t s = 0; s < c_.species.size(); ++s)
                console_ << fmt::format("  temperature of {:<4s} {:.6g}\n", c_.species[s].name,
                                        k.temperature(D, s));
        console_ << fmt::format("  pressure           {:.6g} ({})\n", P, pressure_method(e.box()));
        console_ << fmt::format("  ideal gas N T / V  {:.6g}  ->  Z = P V / (N T) = {:.4f}\n",
                                P_ideal, P_ideal > 0 ? P / P_ideal : 0.0);
        console_ << fmt::format(
            "  {} at eta = {:.4f}: Z = {:.4f}{}\n",
            D == 2 ? "hard-disk EOS (Henderson)" : "hard-sphere EOS (Carnahan-Starling)", eta,
            Z_eos, e.box().any_wall() ? " (walls shift this by O(sigma/L))" : "");
        if (C)
            console_ << fmt::format("  mean free time     {:.6g}\n",
                                    j["mean_free_time"].template get<double>());
        console_ << fmt::format("  outputs            {}\n", o_.out_dir.string());
    }

    const RunConfig& c_;
    const RunOptions& o_;
    std::ostream& console_;
    std::unique_ptr<EventEngine<D>> engine_;
    RunState<D> state_;
    std::size_t mobile_ = 0;
    std::unique_ptr<AtomicAppendFile> log_;
    std::unique_ptr<AtomicAppendFile> trajectory_;
    std::chrono::steady_clock::time_point wall_start_;
    std::optional<std::chrono::steady_clock::time_point> last_progress_;
    std::uint64_t collisions_start_ = 0;
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
