#include "gas_model.hpp"

#include "pedesis/core/error.hpp"
#include "pedesis/observe/pressure.hpp"
#include "pedesis/run/engine_params.hpp"
#include "pedesis/run/hard_run_output.hpp"
#include "pedesis/run/script_engine.hpp"
#include "pedesis/run/simulation.hpp"
#include "pedesis/setup/build_system.hpp"
#include "pedesis/stepped/stepped_engine.hpp"
#include "pedesis/stepped/time_step.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <limits>

namespace pedesis::python {

namespace {

template <int D>
std::vector<double> flatten(const std::vector<Vec<D>>& v, const ParticleStore<D>& p) {
    std::vector<double> out(v.size() * D);
    for (std::size_t i = 0; i < v.size(); ++i)
        for (int a = 0; a < D; ++a) out[p.tag[i] * D + a] = v[i][a];
    return out;
}

// What the two engines share: the particle table, the counters and the pressure.
template <int D, class Engine> class Gas : public GasModel {
  public:
    int dim() const override { return D; }
    std::size_t size() const override { return engine_->size(); }
    std::vector<double> velocities() const override {
        const auto p = store();
        return flatten<D>(p.velocity, p);
    }
    std::vector<double> positions() const override {
        const auto p = store();
        return flatten<D>(p.position, p);
    }
    std::vector<std::uint16_t> types() const override {
        const auto p = store();
        std::vector<std::uint16_t> t(p.size());
        for (std::size_t i = 0; i < p.size(); ++i) t[p.tag[i]] = p.species[i];
        return t;
    }
    std::vector<double> box() const override {
        std::vector<double> L;
        for (int a = 0; a < D; ++a) L.push_back(engine_->box().length(a));
        return L;
    }
    std::vector<bool> periodic() const override {
        std::vector<bool> p;
        for (int a = 0; a < D; ++a) p.push_back(engine_->box().periodic(a));
        return p;
    }
    // the engine's table now: radii change while Lubachevsky-Stillinger growth runs
    const std::vector<Species>& species() const override {
        table_ = store().species_table;
        return table_;
    }
    std::uint64_t pair_collisions() const override { return engine_->counters().pair_collisions; }
    std::uint64_t wall_collisions() const override { return engine_->counters().wall_collisions; }
    double kinetic_energy() const override { return engine_->kinetic_energy(); }
    double temperature() const override { return kinetics().temperature(); }
    double degrees_of_freedom() const override { return kinetics().total_freedom; }
    SymTensor pressure_tensor() override {
        const double t = engine_->time();
        const SpeciesKinetics k = kinetics();
        const SymTensor P =
            interval_pressure_tensor(engine_->box(), last_counters_, engine_->counters(),
                                     t - last_time_, sym_midpoint(last_thermal_, k.thermal_tensor));
        last_counters_ = engine_->counters();
        last_time_ = t;
        last_thermal_ = k.thermal_tensor;
        return P;
    }

    // Through the one run loop (run/simulation.hpp), without a run directory: the time and
    // step limits are the loop's, the collision count is the engine's own stop.
    std::string run(const GasLimits& limits) override {
        if (limits.steps && !has_steps())
            throw InputError("run: steps is a limit of the stepped engine; the event engine "
                             "stops at a time or a collision count");
        if (!limits.time && !limits.steps && !limits.collisions_per_particle)
            throw InputError("run: give time, collisions_per_particle or steps");
        Loop loop(*this, limits.collisions_per_particle
                             ? collision_limit(*limits.collisions_per_particle)
                             : std::numeric_limits<std::uint64_t>::max());
        const RunOptions no_directory;
        Simulation<D> sim(loop, Schedule{}, OutputChoice{}, no_directory);
        for (const auto& op : this->operations_) sim.add_operation(op.trigger, op.act);
        const std::uint64_t end_step =
            limits.steps ? steps() + *limits.steps : std::numeric_limits<std::uint64_t>::max();
        if (const char* why = sim.advance(
                end_step, limits.time.value_or(std::numeric_limits<double>::infinity())))
            return why;
        return limits.steps && steps() >= end_step ? "steps" : "time";
    }

  protected:
    // The engine as the loop drives it.
    class Loop final : public ScriptEngine<D> {
      public:
        Loop(Gas& gas, std::uint64_t collision_target)
            : gas_(gas), collision_target_(collision_target) {}
        std::uint64_t step() const override { return gas_.steps(); }
        double time() const override { return gas_.time(); }
        Advance advance(std::uint64_t until_step, double until_time) override {
            return {gas_.advance_engine(until_step, until_time, collision_target_), false};
        }
        Frame<D> frame() override {
            snapshot_ = gas_.store();
            return frame_of(snapshot_, gas_.engine_->box(), gas_.time(), gas_.steps());
        }

      private:
        Gas& gas_;
        std::uint64_t collision_target_;
        ParticleStore<D> snapshot_;
    };

    virtual bool has_steps() const = 0;
    // Advances toward step `until_step` / time `until_time` (it may return earlier), and
    // stops at `collision_target` pair collisions since t = 0; the name of the stop met,
    // or null.
    virtual const char* advance_engine(std::uint64_t until_step, double until_time,
                                       std::uint64_t collision_target) = 0;

    // The particles and box of the config, handed to `make` for the engine.
    template <class Make> void start(const RunConfig& c, Make make) {
        Box<D> box = build_box<D>(c);
        if (c.shear_rate > 0.0) box.set_shear_rate(c.shear_rate); // as `pedesis run` does
        ParticleStore<D> p = build_particles<D>(c, box);
        engine_ = make(std::move(p), box);
        last_time_ = engine_->time();
        last_thermal_ = kinetics().thermal_tensor;
    }
    SpeciesKinetics kinetics() const {
        return measure_kinetics(store(), engine_->box(), hard_particle_dynamics);
    }
    std::uint64_t collision_limit(double per_particle) const {
        return static_cast<std::uint64_t>(std::ceil(per_particle * static_cast<double>(size())));
    }
    virtual ParticleStore<D> store() const = 0;

    std::unique_ptr<Engine> engine_;
    mutable std::vector<Species> table_; // the latest species(), kept for its reference
    EventCounters<D> last_counters_{};
    double last_time_ = 0.0;
    SymTensor last_thermal_{}; // sum m u_a u_b at the last pressure() (thermo.hpp)
};

template <int D> class EventGas final : public Gas<D, EventEngine<D>> {
  public:
    explicit EventGas(const RunConfig& c) {
        this->start(c, [&](ParticleStore<D> p, const Box<D>& box) {
            return std::make_unique<EventEngine<D>>(std::move(p), box, event_params(c));
        });
    }
    std::string dynamics() const override { return "event"; }
    double time() const override { return this->engine_->time(); }
    std::uint64_t steps() const override { return 0; }

    bool has_steps() const override { return false; }
    const char* advance_engine(std::uint64_t, double until_time,
                               std::uint64_t collision_target) override {
        StopLimits l;
        l.time = until_time;
        l.pair_collisions = collision_target;
        switch (this->engine_->run(l)) {
        case StopReason::collisions:
            return "collisions_per_particle";
        // the names of `pedesis run` (summary.json's stopped_by, event_run.cpp), so that a
        // script and a run directory say the same; python/pedesis/_engines.py keeps the
        // earlier "no_events" and "energy" comparing equal, with a DeprecationWarning
        case StopReason::no_events:
            return "no more events";
        case StopReason::energy:
            return "energy_fraction";
        case StopReason::grown:
            return "grown"; // run again to go on at these radii
        case StopReason::time:
        case StopReason::interrupted:
            return nullptr; // the loop sees either
        }
        return nullptr;
    }

  private:
    ParticleStore<D> store() const override { return this->engine_->snapshot(); }
};

template <int D> class SteppedGas final : public Gas<D, SteppedEngine<D>> {
  public:
    explicit SteppedGas(const RunConfig& c) {
        this->start(c, [&](ParticleStore<D> p, const Box<D>& box) {
            check_time_step(p, c.dt, c.max_move, c.dt_where, static_cast<double>(p.size()));
            return std::make_unique<SteppedEngine<D>>(std::move(p), box, stepped_params(c));
        });
    }
    std::string dynamics() const override { return "stepped"; }
    double time() const override { return this->engine_->time(); }
    std::uint64_t steps() const override { return this->engine_->steps(); }

    bool has_steps() const override { return true; }
    const char* advance_engine(std::uint64_t, double, std::uint64_t collision_target) override {
        auto& e = *this->engine_;
        if (e.counters().pair_collisions < collision_target) e.step(); // one step a call
        return e.counters().pair_collisions >= collision_target ? "collisions_per_particle"
                                                                : nullptr;
    }

  private:
    ParticleStore<D> store() const override { return this->engine_->particles(); }
};

template <int D> std::unique_ptr<GasModel> make_gas_d(const RunConfig& c) {
    if (c.dynamics == "event") return std::make_unique<EventGas<D>>(c);
    if (c.dynamics == "stepped") return std::make_unique<SteppedGas<D>>(c);
    throw InputError(fmt::format("{}: dynamics = \"{}\" is a soft engine; script it with "
                                 "pedesis.System and pedesis.Evolver",
                                 c.file, c.dynamics));
}

} // namespace

std::unique_ptr<GasModel> make_gas(const RunConfig& c) {
    return c.dimension == 2 ? make_gas_d<2>(c) : make_gas_d<3>(c);
}

} // namespace pedesis::python
