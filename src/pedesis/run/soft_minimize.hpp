#pragma once
// dynamics = "minimize" in the soft run (run/soft_run.cpp): FIRE (soft/fire.hpp) as the
// evolver's one integrator, stopping at [minimize] force_tolerance (or energy_tolerance)
// or at run.steps, and what it adds to the log, summary.json and the console. Both stops
// end the run normally (exit 0); summary.json's stopped_by says which it was
// ("force_tolerance", "energy_tolerance" or "steps"), as LAMMPS' minimize reports its
// stopping criterion.
#include "pedesis/core/error.hpp"
#include "pedesis/run/run_options.hpp"
#include "pedesis/run/soft_run.hpp"
#include "pedesis/setup/run_config.hpp"
#include "pedesis/soft/evolver.hpp"
#include "pedesis/soft/fire.hpp"

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include <algorithm>
#include <filesystem>
#include <limits>
#include <memory>
#include <ostream>
#include <string>
#include <vector>

namespace pedesis {

template <int D> class SoftMinimization {
  public:
    // What FIRE does not run with, refused before the state is built: a restart (FIRE's
    // dt, alpha and counters are not in the checkpoint: a minimisation that stopped is
    // continued from its final frame instead), processes, the GPU and shear.
    static void refuse(const RunConfig& c, const RunOptions& o, bool on_gpu) {
        const std::string head = c.file + ": dynamics = \"minimize\"";
        if (o.restart)
            throw InputError(head + " does not continue from a checkpoint (--restart, --resume): "
                                    "start a new run from its final frame ([initial] file = a "
                                    "GSD or XYZ trajectory of it)");
        if (o.comm && o.comm->size() > 1)
            throw InputError(head + " runs on one process: start it without mpirun");
        if (on_gpu)
            throw InputError(head +
                             " runs on the CPU, not with device = \"gpu\" (nor --device gpu)");
        if (c.shear_rate > 0.0)
            throw InputError(head + " minimises in a fixed box: remove [box] shear_rate");
    }

    // Registers FIRE with the evolver and puts the particles at rest.
    SoftMinimization(const RunConfig& c, SoftState<D>& s, Evolver<D>& e) : c_(c) {
        auto fire = std::make_unique<FireMinimizer<D>>(c.minimize);
        fire_ = fire.get();
        fire_->start(s);
        e.add_integrator(std::move(fire));
    }

    // Once the first forces are there (RunEngine::start).
    void start(const SoftState<D>& s) {
        fire_->measure(s);
        if (fire_->forces_converged()) stop_ = "force_tolerance";
    }

    // Steps until `target`, `until_time`, a caught signal or a tolerance met; the
    // tolerance's name then, else nullptr.
    const char* advance(SoftState<D>& s, Evolver<D>& e, const SoftClock& clock,
                        std::uint64_t target, double until_time) {
        while (!stop_ && s.step < target) {
            const std::uint64_t before = s.step;
            evolve_until(s, e, clock, before + 1, until_time);
            if (s.step == before) break; // a signal, or until_time
            if (fire_->forces_converged())
                stop_ = "force_tolerance";
            else if (c_.minimize.energy_tolerance > 0.0 &&
                     fire_->energy_settled(e.pair_totals().energy))
                stop_ = "energy_tolerance";
        }
        return stop_;
    }
    const char* stopped_by() const { return stop_; }

    static std::vector<std::string> log_columns() { return {"max_force", "force_norm", "fire_dt"}; }
    void add_values(std::vector<double>& values) const {
        values.insert(values.end(), {fire_->max_force(), fire_->force_norm(), fire_->dt()});
    }

    void add_summary(nlohmann::json& j) const {
        const FireParams& p = fire_->params();
        j["minimize"] = {{"converged", stop_ != nullptr},
                         {"max_force", fire_->max_force()},
                         {"force_norm", fire_->force_norm()},
                         {"force_tolerance", p.force_tolerance},
                         {"energy_tolerance", p.energy_tolerance},
                         {"fire_dt", fire_->dt()},
                         {"fire_alpha", fire_->alpha()}};
    }

    // The console's line on how the minimisation ended.
    void print_end(std::ostream& out, const nlohmann::json& j,
                   const std::filesystem::path& out_dir) const {
        const auto step = j["steps"].template get<std::uint64_t>();
        const double f = fire_->max_force();
        const double tol = fire_->params().force_tolerance;
        if (stop_ && std::string(stop_) == "force_tolerance")
            out << fmt::format("  minimised (FIRE) at step {}: largest force {:.4g} < "
                               "force_tolerance {:g}\n",
                               step, f, tol);
        else if (stop_)
            out << fmt::format("  minimised (FIRE) at step {}: the energy changed by less than "
                               "energy_tolerance {:g} (relative); largest force {:.3g}\n",
                               step, fire_->params().energy_tolerance, f);
        else if (j["stopped_by"] == "steps")
            out << fmt::format("  not minimised: run.steps = {} reached with the largest force "
                               "{:.3g} above force_tolerance {:g}; raise run.steps, or go on "
                               "from the final frame ({})\n",
                               c_.steps, f, tol, final_frame_hint(out_dir));
    }

    std::string progress() const {
        return fmt::format("max force = {:<10.4g}", fire_->max_force());
    }

  private:
    // Where the run's final frame is, as [initial] takes it.
    std::string final_frame_hint(const std::filesystem::path& out_dir) const {
        for (const char* format : {"gsd", "xyz"})
            if (std::find(c_.formats.begin(), c_.formats.end(), format) != c_.formats.end())
                return fmt::format("[initial] file = \"{}\"",
                                   (out_dir / (std::string("trajectory.") + format)).string());
        return "add \"gsd\" to [output] formats to keep it";
    }

    const RunConfig& c_;
    FireMinimizer<D>* fire_ = nullptr; // (the evolver owns it)
    const char* stop_ = nullptr;
};

} // namespace pedesis
