#include "pedesis/run/run.hpp"

#include "pedesis/core/error.hpp"
#include "pedesis/core/interrupt.hpp"
#include "pedesis/io/trajectory_file.hpp"
#include "pedesis/run/event_run.hpp"
#include "pedesis/run/simulation.hpp"
#include "pedesis/run/soft_run.hpp"
#include "pedesis/run/stepped_run.hpp"

namespace pedesis {

namespace {

template <int D>
EngineSetup<D> engine_setup(const RunConfig& c, const RunOptions& o, std::ostream& out) {
    if (c.soft()) return soft_engine_setup<D>(c, o, out);
    if (o.device && *o.device == "gpu")
        throw InputError(c.file +
                         ": only the soft engines (brownian, langevin, nve) run on the "
                         "GPU, and this config's dynamics is '" +
                         c.dynamics + "'");
    if (c.dynamics == "stepped") return stepped_engine_setup<D>(c, o, out);
    return event_engine_setup<D>(c, o, out);
}

RunOptions with_clock(RunOptions o, const RunConfig& c) {
    o.checkpoint_seconds = c.checkpoint_seconds;
    return o;
}

template <int D> class RunOf final : public Run {
  public:
    // The engines keep references to the config and options: the run owns both.
    RunOf(const RunConfig& c, const RunOptions& o, std::ostream& out)
        : config_(c), options_(with_clock(o, c)), setup_(engine_setup<D>(config_, options_, out)),
          sim_(*setup_.engine, setup_.schedule, setup_.outputs, options_),
          has_steps_(c.dynamics != "event") {}

    int dimension() const override { return D; }
    std::uint64_t step() const override { return setup_.engine->step(); }
    double time() const override { return setup_.engine->time(); }
    bool has_steps() const override { return has_steps_; }

    void run() override {
        guarded([&] { sim_.run(); });
        if (sim_.closed()) write_last_frames();
    }
    const char* advance(std::uint64_t max_step, double max_time) override {
        const char* why = nullptr;
        guarded([&] { why = sim_.advance(max_step, max_time); });
        return why;
    }
    void close(const char* ended_by) override {
        const bool was_open = !sim_.closed();
        guarded([&] { sim_.close(ended_by); });
        if (was_open) write_last_frames();
        commit_trajectories();
    }
    bool closed() const override { return sim_.closed(); }
    const char* stopped_by() const override { return sim_.stopped_by(); }

    void add_operation(Trigger trigger, std::function<void()> act) override {
        sim_.add_operation(trigger, std::move(act));
    }
    void add_trajectory(const std::filesystem::path& path, const std::string& format,
                        Trigger trigger) override {
        auto t = std::make_shared<ScriptTrajectory>(path, format);
        trajectories_.push_back(t);
        RunEngine<D>& engine = *setup_.engine;
        t->append(engine); // the start, as the run's own trajectory has it
        sim_.add_operation(trigger, [t, &engine] { t->append(engine); });
    }

    const std::vector<std::string>& log_names() const override { return sim_.log_names(); }
    const std::vector<double>& last_log_row() const override { return sim_.last_log_row(); }

    FrameArrays frame() override {
        const Frame<D> f = setup_.engine->frame();
        const ParticleStore<D>& p = f.particles;
        FrameArrays a;
        a.dimension = D;
        a.time = f.time;
        a.step = f.step;
        for (int d = 0; d < D; ++d) {
            a.box[static_cast<std::size_t>(d)] = f.box.length(d);
            a.periodic[static_cast<std::size_t>(d)] = f.box.periodic(d);
        }
        for (const Species& s : p.species_table) a.species.push_back(s.name);
        const std::size_t n = f.size();
        a.type.resize(n);
        a.position.assign(3 * n, 0.0);
        a.velocity.assign(3 * n, 0.0);
        a.radius.resize(n);
        a.mass.resize(n);
        a.image.assign(3 * n, 0);
        if (f.has_director()) a.director.assign(3 * n, 0.0);
        for (std::size_t i = 0; i < n; ++i) {
            const std::size_t k = p.tag[i];
            a.type[k] = p.species[i];
            a.radius[k] = p.radius(i);
            a.mass[k] = p.mass(i);
            const auto img = f.image(i);
            for (int d = 0; d < D; ++d) {
                a.position[3 * k + d] = p.position[i][d];
                a.velocity[3 * k + d] = p.velocity[i][d];
                a.image[3 * k + d] = img[static_cast<std::size_t>(d)];
                if (f.has_director()) a.director[3 * k + d] = f.director(i)[d];
            }
        }
        return a;
    }

    std::vector<std::pair<std::string, double>> steerable() const override {
        return setup_.engine->steerable();
    }
    void steer(const std::string& name, double value) override {
        setup_.engine->steer(name, value);
    }

    ~RunOf() override { commit_trajectories(); }

  private:
    // A script's trajectory file, and the clock of its last frame.
    struct ScriptTrajectory {
        ScriptTrajectory(const std::filesystem::path& path, const std::string& format)
            : file(path, format) {}
        void append(RunEngine<D>& engine) {
            file.append(engine.frame());
            step = engine.step();
            time = engine.time();
        }
        TrajectoryFile<D> file;
        std::uint64_t step = 0;
        double time = 0.0;
    };

    // The triggers fire before the stop, as the run's own frames; like them, each script
    // trajectory ends with the final state (once: not twice where a trigger fired there).
    void write_last_frames() {
        RunEngine<D>& engine = *setup_.engine;
        for (auto& t : trajectories_)
            if (t->step != engine.step() || t->time != engine.time()) t->append(engine);
    }

    // A failed run (RunError) keeps the script's trajectories too, as the run's own.
    template <class F> void guarded(F&& f) {
        try {
            f();
        } catch (const RunError&) {
            commit_trajectories();
            throw;
        }
    }
    void commit_trajectories() {
        for (auto& t : trajectories_) t->file.commit();
    }

    RunConfig config_;
    RunOptions options_;
    EngineSetup<D> setup_;
    Simulation<D> sim_;
    bool has_steps_;
    std::vector<std::shared_ptr<ScriptTrajectory>> trajectories_;
};

} // namespace

std::unique_ptr<Run> make_run(const RunConfig& config, const RunOptions& options,
                              std::ostream& console) {
    // nothing of a run exists yet that a clean stop could close (core/interrupt.hpp)
    const SetUpStretch set_up;
    if (config.dimension == 2) return std::make_unique<RunOf<2>>(config, options, console);
    return std::make_unique<RunOf<3>>(config, options, console);
}

} // namespace pedesis
