#include "bench_stepped.hpp"

#include "pedesis/core/error.hpp"
#include "pedesis/setup/random_placement.hpp"
#include "pedesis/setup/velocities.hpp"
#include "pedesis/stepped/stepped_engine.hpp"
#include "pedesis/stepped/time_step.hpp"

#include <fmt/core.h>

#include <chrono>
#include <cmath>
#include <ctime>
#include <memory>
#include <numbers>

namespace pedesis::cli {

namespace {

struct BenchSteppedOptions {
    int dim = 2;
    std::size_t n = 10000;
    double eta = 0.05;
    std::uint64_t steps = 1000;
    std::uint64_t warmup = 20;
    double dt = 0.0; // 0: the suggested time step
    std::uint64_t seed = 1;
};

// CPU time of the process: on a shared machine, wall time also counts the time other
// jobs held the core.
double cpu_seconds() {
    timespec t{};
    clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &t);
    return static_cast<double>(t.tv_sec) + 1e-9 * static_cast<double>(t.tv_nsec);
}

// The kinetic-theory notebook's gas (seed 003): molecules of radius 0.5 at uniform
// random positions in a walled box, each velocity component normal with standard
// deviation 1 (the notebook's "normal" start with mean 0, whose random signs change
// nothing), at packing fraction eta.
template <int D> void run_bench(const BenchSteppedOptions& o) {
    if (o.n == 0) throw InputError("bench stepped: --n must be positive");
    const double max_eta = D == 2 ? 0.5 : 0.3; // random placement jams above these
    if (!(o.eta > 0.0 && o.eta <= max_eta))
        throw InputError(fmt::format("bench stepped: --eta must lie in (0, {}]", max_eta));
    if (!(o.dt >= 0.0)) throw InputError("bench stepped: --dt must be positive");
    if (o.steps == 0) throw InputError("bench stepped: --steps must be positive");
    const double radius = 0.5;
    const double particle_volume = D == 2 ? std::numbers::pi * radius * radius
                                          : 4.0 / 3.0 * std::numbers::pi * radius * radius * radius;
    const double L = std::pow(static_cast<double>(o.n) * particle_volume / o.eta, 1.0 / D);
    std::array<bool, D> periodic{};
    const Box<D> box(Vec<D>::filled(L), periodic);

    ParticleStore<D> p;
    p.species_table = {Species{"A", radius, 1.0}};
    PlacementRequest<D> req;
    req.count = o.n;
    req.radius = radius;
    req.lo = Vec<D>::filled(-0.5 * L + radius);
    req.hi = Vec<D>::filled(0.5 * L - radius);
    req.what = "bench stepped";
    std::vector<Vec<D>> pos;
    std::vector<double> radii;
    place_randomly(pos, radii, box, req, o.seed);
    p.resize(o.n);
    VelocitySpec vs;
    vs.kind = VelocityKind::normal;
    vs.sigma = 1.0;
    for (std::size_t i = 0; i < o.n; ++i) {
        p.position[i] = pos[i];
        p.tag[i] = static_cast<std::uint32_t>(i);
        p.species[i] = 0;
        p.velocity[i] = draw_velocity<D>(vs, 1.0, o.seed, p.tag[i]);
    }

    SteppedParams params;
    // the suggested step of a run of about 100 collisions per particle
    params.dt = o.dt > 0.0 ? o.dt : suggested_time_step(p, params.max_move, 100.0 * o.n);
    SteppedEngine<D> engine(std::move(p), box, params);
    fmt::print("bench stepped: dim {} N {} eta {} L {:.4f} walls, dt {:g}, {} steps after {} "
               "warm-up\n",
               D, o.n, o.eta, L, params.dt, o.steps, o.warmup);
    for (std::uint64_t k = 0; k < o.warmup; ++k) engine.step();
    const auto c0 = engine.counters();
    const double cpu0 = cpu_seconds();
    const auto t0 = std::chrono::steady_clock::now();
    for (std::uint64_t k = 0; k < o.steps; ++k) engine.step();
    const auto t1 = std::chrono::steady_clock::now();
    const double cpu = cpu_seconds() - cpu0;
    const double wall = std::chrono::duration<double>(t1 - t0).count();
    const auto& c1 = engine.counters();
    const double steps = static_cast<double>(o.steps);
    fmt::print("pair_collisions_per_step: {:.3f}  wall_collisions_per_step: {:.3f}  "
               "late_collisions: {}\n",
               static_cast<double>(c1.pair_collisions - c0.pair_collisions) / steps,
               static_cast<double>(c1.wall_collisions - c0.wall_collisions) / steps,
               engine.stats().late_collisions);
    fmt::print("cpu_seconds: {:.3f}  wall_seconds: {:.3f}  seconds_per_step: {:.3e}\n", cpu, wall,
               cpu / steps);
    fmt::print("particle_steps_per_second: {:.0f}\n", static_cast<double>(o.n) * steps / cpu);
}

} // namespace

void add_bench_stepped(CLI::App& bench) {
    auto o = std::make_shared<BenchSteppedOptions>();
    auto* cmd = bench.add_subcommand(
        "stepped", "Particle-steps per second of the time-stepped hard-particle engine");
    cmd->add_option("--dim", o->dim, "Dimension (2 or 3)")->check(CLI::IsMember({2, 3}));
    cmd->add_option("--n", o->n, "Number of particles");
    cmd->add_option("--eta", o->eta, "Packing fraction (default 0.05, a dilute gas)");
    cmd->add_option("--steps", o->steps, "Steps measured (after the warm-up)");
    cmd->add_option("--warmup", o->warmup, "Steps run before measuring");
    cmd->add_option("--dt", o->dt, "Time step (default: the suggested one, as in runs)");
    cmd->add_option("--seed", o->seed, "Random seed");
    cmd->callback([o] {
        if (o->dim == 2)
            run_bench<2>(*o);
        else
            run_bench<3>(*o);
    });
}

} // namespace pedesis::cli
