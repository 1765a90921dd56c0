#include "bench_event.hpp"

#include "pedesis/core/error.hpp"
#include "pedesis/event/event_engine.hpp"
#include "pedesis/setup/lattice.hpp"
#include "pedesis/setup/velocities.hpp"

#include <fmt/core.h>

#include <chrono>
#include <cmath>
#include <memory>
#include <numbers>

namespace pedesis::cli {

namespace {

struct BenchEventOptions {
    int dim = 3;
    std::size_t n = 32000;
    double eta = 0.45;
    double time = 20.0;
    double warmup = 2.0;
    double skin = -1.0;
    std::uint64_t seed = 1;
};

template <int D> void run_bench(const BenchEventOptions& o) {
    if (o.n == 0) throw InputError("bench event: --n must be positive");
    const double max_eta = D == 2 ? 0.85 : 0.70;
    if (!(o.eta > 0.0 && o.eta < max_eta))
        throw InputError(fmt::format("bench event: --eta must lie in (0, {})", max_eta));
    const double sigma = 1.0;
    const double particle_volume = D == 2 ? std::numbers::pi * sigma * sigma / 4.0
                                          : std::numbers::pi * sigma * sigma * sigma / 6.0;
    const double L = std::pow(static_cast<double>(o.n) * particle_volume / o.eta, 1.0 / D);
    Box<D> box(Vec<D>::filled(L), [] {
        std::array<bool, D> p;
        p.fill(true);
        return p;
    }());

    ParticleStore<D> p;
    p.species_table = {Species{"A", 0.5 * sigma, 1.0}};
    const auto kind = D == 2 ? LatticeKind::hexagonal : LatticeKind::fcc;
    std::array<bool, D> open{};
    p.resize(o.n);
    p.position =
        lattice_sites<D>(kind, Vec<D>::filled(-0.5 * L), Vec<D>::filled(0.5 * L), open, o.n);
    VelocitySpec vs;
    vs.kind = VelocityKind::maxwell_boltzmann;
    vs.temperature = 1.0;
    std::vector<std::size_t> all(o.n);
    for (std::size_t i = 0; i < o.n; ++i) {
        p.tag[i] = static_cast<std::uint32_t>(i);
        p.species[i] = 0;
        p.velocity[i] = draw_velocity<D>(vs, 1.0, o.seed, p.tag[i]);
        all[i] = i;
    }
    remove_drift(p, all);
    // periodic and momentum-free: d degrees of freedom go with the fixed momentum
    rescale_temperature(p, all, 1.0, D);

    EventParams params;
    params.skin = o.skin;
    auto engine = std::make_unique<EventEngine<D>>(std::move(p), box, params);
    fmt::print("bench event: dim {} N {} eta {} L {:.4f} skin {:.3f} time {} (after {} warm-up)\n",
               D, o.n, o.eta, L, engine->skin(), o.time, o.warmup);
    StopLimits warm;
    warm.time = o.warmup;
    engine->run(warm);
    const auto c0 = engine->counters();
    const auto t0 = std::chrono::steady_clock::now();
    StopLimits limits;
    limits.time = o.warmup + o.time;
    engine->run(limits);
    const auto t1 = std::chrono::steady_clock::now();
    const auto& c1 = engine->counters();
    const double seconds = std::chrono::duration<double>(t1 - t0).count();
    const double collisions = static_cast<double>(c1.pair_collisions - c0.pair_collisions);
    fmt::print("collisions: {:.0f}  collisions_per_particle: {:.2f}  wall_seconds: {:.3f}\n",
               collisions, collisions / static_cast<double>(o.n), seconds);
    fmt::print("list_rebuilds_per_collision: {:.4f}  stale_events_per_collision: {:.4f}\n",
               static_cast<double>(c1.list_rebuilds - c0.list_rebuilds) / collisions,
               static_cast<double>(c1.stale_events - c0.stale_events) / collisions);
    fmt::print("collisions_per_second: {:.0f}\n", collisions / seconds);
    fmt::print("bytes_per_particle: {:.1f}\n",
               static_cast<double>(engine->memory_bytes()) / static_cast<double>(o.n));
}

} // namespace

void add_bench_event(CLI::App& bench) {
    auto o = std::make_shared<BenchEventOptions>();
    auto* cmd = bench.add_subcommand("event", "Collisions per second of the event-driven engine");
    cmd->add_option("--dim", o->dim, "Dimension (2 or 3)")->check(CLI::IsMember({2, 3}));
    cmd->add_option("--n", o->n, "Number of particles");
    cmd->add_option("--eta", o->eta, "Packing fraction");
    cmd->add_option("--time", o->time, "Simulated time measured (after the warm-up)");
    cmd->add_option("--warmup", o->warmup,
                    "Simulated time run before measuring (melts the lattice)");
    cmd->add_option("--skin", o->skin,
                    "Neighbour-list skin (default: chosen from the density, as in runs)");
    cmd->add_option("--seed", o->seed, "Random seed");
    cmd->callback([o] {
        if (o->dim == 2)
            run_bench<2>(*o);
        else
            run_bench<3>(*o);
    });
}

} // namespace pedesis::cli
