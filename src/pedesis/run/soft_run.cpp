#include "pedesis/run/soft_run.hpp"

#include "pedesis/core/error.hpp"
#include "pedesis/io/atomic_file.hpp"
#include "pedesis/io/frame_writers.hpp"
#include "pedesis/observe/soft_observables.hpp"
#include "pedesis/observe/thermo.hpp"
#include "pedesis/run/run_directory.hpp"
#include "pedesis/run/soft_checkpoint.hpp"
#include "pedesis/setup/build_soft_state.hpp"
#include "pedesis/setup/build_system.hpp"
#include "pedesis/soft/plugin_registry.hpp"

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <fstream>
#include <memory>
#include <optional>
#include <sstream>

namespace pedesis {

namespace {

std::vector<Species> species_table(const RunConfig& c) {
    std::vector<Species> t;
    for (const auto& s : c.species) t.push_back(Species{s.name, s.radius, s.mass});
    return t;
}

template <int D> class SoftRun {
  public:
    SoftRun(const RunConfig& c, const RunOptions& o, std::ostream& console)
        : c_(complete_from_initial_file<D>(c)), o_(o), console_(console) {}

    void execute() {
        for (std::size_t a = 0; a < c_.periodic.size(); ++a)
            if (!c_.periodic[a])
                throw InputError(c_.file + ": [box] boundary: the " + c_.dynamics +
                                 " engine needs periodic axes (axis " + std::to_string(a) +
                                 " is a wall)");
        const std::vector<Species> table = species_table(c_);
        if (!o_.restart) state_ = build_soft_state<D>(c_);
        evolver_ = std::make_unique<Evolver<D>>(state_, c_.list_skin, c_.list_r_cut);
        evolver_->set_sort_interval(c_.sort_every);
        for (const auto* list : {&c_.forces, &c_.torques, &c_.integrators})
            for (const auto& spec : *list) add_plugin(*evolver_, spec, table, c_.seed);
        if (o_.restart) {
            load_soft_checkpoint(*o_.restart, c_, state_, *evolver_, book_);
            if (state_.step >= c_.steps)
                throw InputError(fmt::format(
                    "{}: the checkpoint {} is at step {}, and run.steps = {} asks for no more; "
                    "raise run.steps to continue",
                    c_.file, o_.restart->string(), state_.step, c_.steps));
        } else {
            book_.start.resize(state_.size());
            for (std::size_t i = 0; i < state_.size(); ++i)
                book_.start[state_.p.tag[i]] = state_.unwrapped(i);
        }
        read_observable_parameters(table);
        // built here so that a box too small for the cutoff is reported before any output
        // exists; a restored run has its list already (building now could rebuild it at
        // another point of the step than the continuous run did)
        if (!o_.restart) evolver_->neighbor_list();
        prepare_directory();

        console_ << fmt::format(
            "pedesis: {}D {} run, N = {}, box {}, dt = {:g}, {} steps, list cutoff {:g} + "
            "skin {:g}, output in {}\n",
            D, c_.dynamics, state_.size(), box_text(), c_.dt, c_.steps, evolver_->list_cutoff(),
            evolver_->skin(), o_.out_dir.string());
        if (!o_.restart) {
            evolver_->compute_forces(); // so that frame 0 shows them; the step reuses them
            log_row();
            frame();
        }
        wall_start_ = std::chrono::steady_clock::now();
        step_start_ = state_.step;
        time_start_ = state_.time;
        try {
            while (state_.step < c_.steps) {
                evolver_->evolve(c_.dt);
                // a multiple of dt, not a running sum: t = 10 after 1000 steps of 0.01
                state_.time = time_start_ + static_cast<double>(state_.step - step_start_) * c_.dt;
                const std::uint64_t k = state_.step;
                if (k % c_.log_every == 0 || k == c_.steps) log_row();
                if (c_.snapshot_every && k % c_.snapshot_every == 0 && k != c_.steps) frame();
                if (c_.checkpoint_every && k % c_.checkpoint_every == 0 && k != c_.steps)
                    save_soft_checkpoint(o_.out_dir / "checkpoint.bin", state_, *evolver_, book_);
            }
        } catch (const RunError& e) {
            // the state is broken: keep what was written while it was good
            close_streams();
            if (frames_written_ == 0)
                throw RunError(fmt::format(
                    "{} (no snapshot was written by this run; the last good state is the "
                    "checkpoint it started from, {})",
                    e.what(), o_.restart ? o_.restart->string() : std::string("-")));
            throw RunError(fmt::format(
                "{} (the last good snapshot is frame {} at step {}; it, the log and the last "
                "checkpoint are in {})",
                e.what(), book_.frames - 1, last_frame_step_, o_.out_dir.string()));
        }
        finish();
    }

  private:
    // The plug-ins say what the logs need: an overdamped position integrator (its bath
    // temperature gives the ideal-gas pressure) and the forces' swim pressure.
    void read_observable_parameters(const std::vector<Species>& table) {
        overdamped_ = nullptr;
        for (const auto& i : evolver_->integrators())
            if (i->overdamped_positions()) overdamped_ = i.get();
        if (overdamped_) {
            bath_T_.resize(table.size());
            for (std::size_t s = 0; s < table.size(); ++s)
                bath_T_[s] = overdamped_->bath_temperature(s, table.size());
        }
    }

    std::string box_text() const {
        std::string s;
        for (int a = 0; a < D; ++a)
            s += fmt::format("{}{:g}", a ? " x " : "", state_.box.length(a));
        return s;
    }

    void prepare_directory() {
        prepare_run_directory(o_.out_dir, o_.config_path, {"summary.json"});
        log_ = std::make_unique<AtomicAppendFile>(o_.out_dir / "log.csv");
        std::string header = "step,time,polar_order,msd,potential_energy,";
        if (inertial()) header += "kinetic_energy,temperature,";
        header += "pressure,pressure_ideal,pressure_virial,pressure_active,list_rebuilds\n";
        log_->append(header);
        frames_ = std::make_unique<FrameWriters<D>>(o_.out_dir, c_.formats);
    }

    bool inertial() const { return overdamped_ == nullptr; }

    void log_row() {
        const auto& s = state_;
        const PairTotals pair = evolver_->pair_totals();
        const double V = s.box.volume();
        double ideal = 0.0;
        SpeciesKinetics k;
        if (inertial()) {
            // the kinetic part of P V is 2 K / d in the centre-of-mass frame, f T / d
            k = measure_kinetics(s.p, s.box, momentum_);
            ideal = 2.0 * k.total_thermal / (D * V);
        } else {
            for (std::size_t i = 0; i < s.size(); ++i) ideal += bath_T_[s.p.species[i]];
            ideal /= V;
        }
        const double virial = pair.virial / (D * V);
        double active = 0.0;
        for (const auto& f : evolver_->forces()) active += f->swim_pressure(s, book_.start);
        const double pressure = ideal + virial + active;
        const double order = polar_order(s);
        std::string row = fmt::format("{},{:.10g},{:.8g},{:.10g},{:.10g},", s.step, s.time, order,
                                      mean_squared_displacement(s, book_.start), pair.energy);
        if (inertial()) row += fmt::format("{:.10g},{:.10g},", k.total_kinetic, k.temperature());
        row += fmt::format("{:.10g},{:.10g},{:.10g},{:.10g},{}\n", pressure, ideal, virial, active,
                           evolver_->list_builds());
        log_->append(row);
        if (s.step > 0) {
            ++book_.samples;
            book_.sum_pressure += pressure;
            book_.sum_polar_order += order;
            book_.sum_temperature += k.temperature();
        }
        progress(order, pressure);
    }

    void progress(double order, double pressure) {
        if (!c_.progress) return;
        const auto now = std::chrono::steady_clock::now();
        if (last_progress_ && now - *last_progress_ < std::chrono::seconds(1)) return;
        last_progress_ = now;
        console_ << fmt::format("  step {:<10} t = {:<10.5g} polar order = {:<8.4f} P = {:<10.5g} "
                                "{:.3g} particle-steps/s\n",
                                state_.step, state_.time, order, pressure, rate());
    }

    double rate() const {
        const double wall =
            std::chrono::duration<double>(std::chrono::steady_clock::now() - wall_start_).count();
        return wall > 0 ? static_cast<double>(state_.step - step_start_) *
                              static_cast<double>(state_.size()) / wall
                        : 0.0;
    }

    void frame() {
        frames_->write(state_.frame(), book_.frames);
        ++book_.frames;
        ++frames_written_;
        last_frame_step_ = state_.step;
    }

    void close_streams() {
        if (log_) log_->commit();
        if (frames_) frames_->commit();
    }

    void finish() {
        if (frames_written_ == 0 || last_frame_step_ != state_.step) frame();
        save_soft_checkpoint(o_.out_dir / "checkpoint.bin", state_, *evolver_, book_);
        close_streams();
        const double wall =
            std::chrono::duration<double>(std::chrono::steady_clock::now() - wall_start_).count();
        const double rate_now = rate();
        nlohmann::json j;
        j["dimension"] = D;
        j["dynamics"] = c_.dynamics;
        j["particles"] = state_.size();
        j["steps"] = state_.step;
        j["time"] = state_.time;
        j["dt"] = c_.dt;
        j["polar_order"] = polar_order(state_);
        j["msd"] = mean_squared_displacement(state_, book_.start);
        j["mean_pressure"] = book_.samples ? book_.sum_pressure / book_.samples : 0.0;
        j["mean_polar_order"] = book_.samples ? book_.sum_polar_order / book_.samples : 0.0;
        j["logged_samples"] = book_.samples;
        if (inertial()) {
            const SpeciesKinetics k = measure_kinetics(state_.p, state_.box, momentum_);
            j["temperature"] = k.temperature();
            j["mean_temperature"] = book_.samples ? book_.sum_temperature / book_.samples : 0.0;
            j["degrees_of_freedom"] = k.total_freedom;
        }
        j["list_rebuilds"] = evolver_->list_builds();
        j["frames"] = book_.frames;
        j["wall_seconds"] = wall;
        j["particle_steps_per_second"] = rate_now;
        write_file_atomically(o_.out_dir / "summary.json",
                              [&](std::ostream& out) { out << j.dump(2) << "\n"; });
        console_ << fmt::format("pedesis: done at step {} (t = {:.6g}) in {:.3g} s, {:.3g} "
                                "particle-steps/s, {} list rebuilds\n",
                                state_.step, state_.time, wall, rate_now, evolver_->list_builds());
        console_ << fmt::format("  polar order {:.4f} (run mean {:.4f}), MSD {:.6g}, mean pressure "
                                "{:.6g}\n",
                                polar_order(state_), j["mean_polar_order"].template get<double>(),
                                j["msd"].template get<double>(),
                                j["mean_pressure"].template get<double>());
        console_ << fmt::format("  outputs            {}\n", o_.out_dir.string());
    }

    const RunConfig c_;
    const RunOptions& o_;
    std::ostream& console_;
    SoftState<D> state_;
    std::unique_ptr<Evolver<D>> evolver_;
    SoftRunBook<D> book_;
    const Integrator<D>* overdamped_ = nullptr;
    std::vector<double> bath_T_; // per species, of the overdamped integrator
    const Momentum momentum_ = momentum_of(c_);
    std::unique_ptr<AtomicAppendFile> log_;
    std::unique_ptr<FrameWriters<D>> frames_;
    std::uint64_t last_frame_step_ = 0;
    std::uint64_t frames_written_ = 0; // by this invocation (a restart starts at 0)
    std::uint64_t step_start_ = 0;
    double time_start_ = 0.0;
    std::chrono::steady_clock::time_point wall_start_ = std::chrono::steady_clock::now();
    std::optional<std::chrono::steady_clock::time_point> last_progress_;
};

} // namespace

void run_soft_simulation(const RunConfig& config, const RunOptions& options,
                         std::ostream& console) {
    if (config.dimension == 2)
        SoftRun<2>(config, options, console).execute();
    else
        SoftRun<3>(config, options, console).execute();
}

} // namespace pedesis
