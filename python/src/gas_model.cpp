#include "gas_model.hpp"

#include "pedesis/core/error.hpp"
#include "pedesis/observe/pressure.hpp"
#include "pedesis/run/engine_params.hpp"
#include "pedesis/run/hard_run_output.hpp"
#include "pedesis/setup/build_system.hpp"
#include "pedesis/stepped/stepped_engine.hpp"
#include "pedesis/stepped/time_step.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>

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
    double pressure() override {
        const double t = engine_->time();
        const SpeciesKinetics k = kinetics();
        const double T = k.temperature();
        const double P = interval_pressure(engine_->box(), last_counters_, engine_->counters(),
                                           t - last_time_, 0.5 * (last_T_ + T), k.total_freedom);
        last_counters_ = engine_->counters();
        last_time_ = t;
        last_T_ = T;
        return P;
    }

  protected:
    // The particles and box of the config, handed to `make` for the engine.
    template <class Make> void start(const RunConfig& c, Make make) {
        const Box<D> box = build_box<D>(c);
        ParticleStore<D> p = build_particles<D>(c, box);
        engine_ = make(std::move(p), box);
        last_time_ = engine_->time();
        last_T_ = temperature();
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
    double last_time_ = 0.0, last_T_ = 0.0;
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

    std::string run(const GasLimits& limits, const std::function<void()>& check) override {
        if (limits.steps)
            throw InputError("run: steps is a limit of the stepped engine; the event engine "
                             "stops at a time or a collision count");
        auto& e = *this->engine_;
        const std::uint64_t target = limits.collisions_per_particle
                                         ? this->collision_limit(*limits.collisions_per_particle)
                                         : std::numeric_limits<std::uint64_t>::max();
        // chunks of about N collisions, so that Ctrl-C is felt within a few milliseconds
        const std::uint64_t chunk = std::max<std::uint64_t>(1000, this->size());
        for (;;) {
            if (check) check();
            StopLimits l;
            l.time = limits.time.value_or(std::numeric_limits<double>::infinity());
            l.pair_collisions = std::min(target, e.counters().pair_collisions + chunk);
            const StopReason r = e.run(l);
            if (r == StopReason::time) return "time";
            if (r == StopReason::no_events) return "no_events";
            if (r == StopReason::energy) return "energy";
            if (r == StopReason::grown) return "grown"; // run again to go on at these radii
            if (e.counters().pair_collisions >= target) return "collisions_per_particle";
        }
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

    std::string run(const GasLimits& limits, const std::function<void()>& check) override {
        auto& e = *this->engine_;
        const std::uint64_t end_step =
            limits.steps ? e.steps() + *limits.steps : std::numeric_limits<std::uint64_t>::max();
        const std::uint64_t target = limits.collisions_per_particle
                                         ? this->collision_limit(*limits.collisions_per_particle)
                                         : std::numeric_limits<std::uint64_t>::max();
        if (!limits.time && !limits.steps && !limits.collisions_per_particle)
            throw InputError("run: give time, collisions_per_particle or steps");
        for (;;) {
            if (limits.time && e.time() >= *limits.time - 1e-9 * e.dt()) return "time";
            if (e.steps() >= end_step) return "steps";
            if (e.counters().pair_collisions >= target) return "collisions_per_particle";
            if (check) check();
            e.step();
        }
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
