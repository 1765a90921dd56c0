#include "soft_model.hpp"

#include "pedesis/core/error.hpp"
#include "pedesis/io/atomic_file.hpp"
#include "pedesis/io/particle_file.hpp"
#include "pedesis/io/tutorial_json.hpp"
#include "pedesis/io/vtp_writer.hpp"
#include "pedesis/observe/soft_observables.hpp"
#include "pedesis/run/script_engine.hpp"
#include "pedesis/run/simulation.hpp"
#include "pedesis/run/soft_run.hpp"
#include "pedesis/setup/build_soft_state.hpp"
#include "pedesis/setup/run_config.hpp"
#include "pedesis/soft/integrator_set.hpp"
#include "pedesis/soft/plugin_registry.hpp"

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include <cmath>
#include <cstring>
#include <fstream>

namespace pedesis::python {

namespace {

// Vec<D> is D doubles with no padding (checked below), so a vector of them is an N x D
// array of doubles that numpy can view.
template <int K> double* raw(std::vector<Vec<K>>& v) {
    static_assert(sizeof(Vec<K>) == K * sizeof(double));
    return v.empty() ? nullptr : &v[0][0];
}

template <int D> class System final : public SystemModel {
  public:
    explicit System(SoftState<D> s) : state(std::move(s)) {}

    int dim() const override { return D; }
    std::size_t size() const override { return state.size(); }
    double* positions() override { return raw(state.p.position); }
    double* velocities() override { return raw(state.p.velocity); }
    double* directors() override { return raw(state.director); }
    double* forces() override { return raw(state.force); }
    double* torques() override { return raw(state.torque); }
    std::int32_t* images() override { return state.image.data()->data(); }
    std::uint32_t* tags() override { return state.p.tag.data(); }
    std::uint16_t* types() override { return state.p.species.data(); }
    std::vector<double> box() const override {
        std::vector<double> L;
        for (int a = 0; a < D; ++a) L.push_back(state.box.length(a));
        return L;
    }
    std::vector<bool> periodic() const override {
        std::vector<bool> p;
        for (int a = 0; a < D; ++a) p.push_back(state.box.periodic(a));
        return p;
    }
    const std::vector<Species>& species() const override { return state.p.species_table; }
    double time() const override { return state.time; }
    std::uint64_t step() const override { return state.step; }
    double polar_order() const override { return pedesis::polar_order(state); }
    double kinetic_energy() const override { return pedesis::kinetic_energy(state); }
    void write_vtp(const std::filesystem::path& path) const override {
        pedesis::write_vtp(path, state.frame());
    }
    void write_json(const std::filesystem::path& path) const override {
        const std::string text = to_tutorial_json(state.frame()).dump() + "\n";
        write_file_atomically(path, [&](std::ostream& out) { out << text; });
    }

    void check_arrays(const std::string& context) const override {
        for (std::size_t i = 0; i < state.size(); ++i) {
            for (int a = 0; a < D; ++a)
                if (!std::isfinite(state.p.position[i][a]) ||
                    !std::isfinite(state.director[i][a]) || !std::isfinite(state.p.velocity[i][a]))
                    throw RunError(fmt::format(
                        "{}: particle {} has a non-finite position, velocity or director", context,
                        state.p.tag[i]));
            const double n2 = norm2(state.director[i]);
            if (!(n2 > 0.0))
                throw RunError(
                    fmt::format("{}: particle {} has a zero director", context, state.p.tag[i]));
        }
    }

    SoftState<D> state;
};

template <int D>
std::unique_ptr<SystemModel> read_system_d(const std::filesystem::path& path, std::uint64_t seed,
                                           std::optional<std::int64_t> frame) {
    // the same path as `pedesis run` with [initial] file and no [[species]]: one species
    // per type, named A, B, ..., so that a config and a script give the same state
    RunConfig c;
    c.file = "System.read_init";
    c.dimension = D;
    c.dynamics = "brownian";
    c.seed = seed;
    c.initial_file = path.string();
    c.initial_frame = frame;
    c.species_defaults.positions = "file";
    c.species_defaults.velocities = "zero";
    auto system = std::make_unique<System<D>>(build_soft_state<D>(c));
    // as `pedesis run` refuses walls for the soft engines (run/soft_run.cpp)
    for (int a = 0; a < D; ++a)
        if (!system->state.box.periodic(a))
            throw InputError(fmt::format("System.read_init: {} has a wall on axis {} (its box's "
                                         "boundaries); the soft/active engine runs in periodic "
                                         "boxes only",
                                         path.string(), a));
    return system;
}

// The tutorial's System and Evolver as an engine of the one run loop (run/simulation.hpp),
// run without a run directory: the script's Dump and callbacks are its output. The clock
// is t0 + (step - step0) dt, as the CLI counts it.
template <int D> class TutorialEngine final : public ScriptEngine<D> {
  public:
    TutorialEngine(SoftState<D>& state, Evolver<D>& evolver, SoftClock clock)
        : s_(state), evolver_(evolver), clock_(clock) {}

    std::uint64_t step() const override { return s_.step; }
    double time() const override { return s_.time; }
    Advance advance(std::uint64_t until_step, double) override {
        evolve_until(s_, evolver_, clock_, until_step);
        return {};
    }
    Frame<D> frame() override { return s_.frame(); }

  private:
    SoftState<D>& s_;
    Evolver<D>& evolver_;
    SoftClock clock_;
};

template <int D> class EvolverD final : public EvolverModel {
  public:
    EvolverD(System<D>& sys, double rcut, double pad, std::uint64_t seed, std::uint64_t sort_every)
        : sys_(sys), evolver_(sys.state, pad, rcut), seed_(seed) {
        evolver_.set_sort_interval(sort_every);
    }

    void add(const PluginSpec& spec) override {
        // the config's rule (soft/integrator_set.hpp): what can never fit is refused here,
        // what is still missing when a step is asked for
        if (spec.kind == PluginKind::integrator)
            check_integrator_added(integrators_, spec, PluginNaming::python);
        add_plugin(evolver_, spec, sys_.state.p.species_table, seed_);
        if (spec.kind == PluginKind::integrator) integrators_.push_back(spec);
        if (spec.kind == PluginKind::torque) torques_.push_back(spec);
    }

    void run(std::uint64_t steps, double dt, const RunHooks& hooks) override {
        if (!(dt > 0.0 && std::isfinite(dt)))
            throw InputError(fmt::format("dt must be a positive finite number, got {}", dt));
        check_integrators_complete(
            integrators_, torques_,
            "Evolver: nothing moves the particles: add a position integrator (one of " +
                position_integrators(PluginNaming::python) +
                ") with Evolver.add_integrator before evolve or run",
            PluginNaming::python);
        auto& s = sys_.state;
        take_outside_changes("before the run");
        if (dt != dt_) { // a new time origin: t = t0 + (step - step0) dt, as the CLI counts
            t0_ = s.time;
            step0_ = s.step;
            dt_ = dt;
        }
        // back to the storage order the last call ended in: a list rebuilt from another
        // order would scan the cells in another order, and the forces would differ from
        // the CLI's in the last bits
        if (!sorted_order_.empty()) evolver_.reorder(sorted_order_);
        sorted_order_.clear();
        // as `pedesis run` sorts before a fresh run's first step, for the same trajectory
        if (!started_ && evolver_.sort_interval() > 0) evolver_.sort_storage_at_start();
        started_ = true;
        TutorialEngine<D> engine(s, evolver_, SoftClock{t0_, step0_, dt_});
        const RunOptions no_directory;
        Simulation<D> sim(engine, Schedule{}, OutputChoice{}, no_directory);
        if (hooks.every && hooks.between)
            sim.add_operation(Trigger::every_steps(hooks.every), [&] {
                const auto order = evolver_.restore_tag_order();
                remember_positions();
                hooks.between(s.step);
                take_outside_changes("after the callback");
                if (!order.empty()) evolver_.reorder(inverse(order));
            });
        try {
            sim.advance(s.step + steps);
        } catch (...) {
            back_to_tag_order();
            throw;
        }
        back_to_tag_order();
    }

    std::uint64_t list_builds() const override { return evolver_.list_builds(); }
    double list_cutoff() const override { return evolver_.list_cutoff(); }
    double potential_energy() override {
        take_outside_changes("potential_energy");
        const double u = evolver_.pair_totals().energy;
        evolver_.restore_tag_order();
        return u;
    }
    std::vector<std::string> terms() const override {
        std::vector<std::string> t;
        for (const auto& f : evolver_.forces()) t.push_back(f->name());
        for (const auto& f : evolver_.torques()) t.push_back(f->name());
        for (const auto& i : evolver_.integrators()) t.push_back(i->name());
        return t;
    }

  private:
    static std::vector<std::uint32_t> inverse(const std::vector<std::uint32_t>& order) {
        std::vector<std::uint32_t> inv(order.size());
        for (std::size_t i = 0; i < order.size(); ++i)
            inv[order[i]] = static_cast<std::uint32_t>(i);
        return inv;
    }

    void back_to_tag_order() {
        const auto order = evolver_.restore_tag_order();
        if (!order.empty()) sorted_order_ = inverse(order);
        remember_positions();
    }

    void remember_positions() {
        if (evolver_.needs_initial_forces()) seen_ = sys_.state.p.position;
    }

    // What Python may have written into the arrays since it last had them: positions
    // outside the box are wrapped (the image counters follow), and a velocity-Verlet
    // pre-step gets the forces of the new positions. Unchanged arrays change nothing, so
    // a script that only reads them follows the CLI's trajectory bit for bit.
    void take_outside_changes(const char* when) {
        auto& s = sys_.state;
        sys_.check_arrays(when);
        for (std::size_t i = 0; i < s.size(); ++i) {
            const Vec<D> shift = s.box.wrap(s.p.position[i]);
            for (int a = 0; a < D; ++a) s.image[i][a] += static_cast<std::int32_t>(shift[a]);
        }
        if (evolver_.needs_initial_forces() &&
            (seen_.size() != s.size() ||
             std::memcmp(seen_.data(), s.p.position.data(), s.size() * sizeof(Vec<D>)) != 0))
            evolver_.invalidate_forces();
    }

    System<D>& sys_;
    Evolver<D> evolver_;
    std::vector<PluginSpec> integrators_, torques_; // as added, for the integrator rule
    std::uint64_t seed_;
    double t0_ = 0.0, dt_ = 0.0;
    std::uint64_t step0_ = 0;
    std::vector<Vec<D>> seen_;
    std::vector<std::uint32_t> sorted_order_; // re-applied at the next call
    bool started_ = false;                    // (sorted once, before the first step)
};

} // namespace

std::unique_ptr<SystemModel> read_system(const std::filesystem::path& path, int dim,
                                         std::uint64_t seed, std::optional<std::int64_t> frame) {
    if (dim == 0) dim = particle_file_dimension(path, frame);
    if (dim == 2) return read_system_d<2>(path, seed, frame);
    if (dim == 3) return read_system_d<3>(path, seed, frame);
    throw InputError(fmt::format("System: dim must be 2 or 3, got {}", dim));
}

std::unique_ptr<EvolverModel> make_evolver(SystemModel& system, double rcut, double pad,
                                           std::uint64_t seed, std::uint64_t sort_every) {
    if (system.dim() == 2)
        return std::make_unique<EvolverD<2>>(static_cast<System<2>&>(system), rcut, pad, seed,
                                             sort_every);
    return std::make_unique<EvolverD<3>>(static_cast<System<3>&>(system), rcut, pad, seed,
                                         sort_every);
}

} // namespace pedesis::python
