#include "bench_event.hpp"

#include "pedesis/core/error.hpp"
#include "pedesis/core/simd_level.hpp"
#include "pedesis/event/event_engine.hpp"
#include "pedesis/setup/lattice.hpp"
#include "pedesis/setup/velocities.hpp"

#include <fmt/core.h>

#include <chrono>
#include <cmath>
#include <fstream>
#include <memory>
#include <numbers>
#include <random>
#include <string>
#include <utility>

#include <sys/resource.h>

namespace pedesis::cli {

namespace {

// Bytes of this process backed by 2 MiB pages (AnonHugePages of /proc/self/smaps_rollup;
// 0 where the system does not say): whether huge_pages.cpp's request was granted.
std::size_t huge_page_bytes() {
    std::ifstream in("/proc/self/smaps_rollup");
    std::string key;
    std::size_t kib = 0;
    while (in >> key) {
        if (key == "AnonHugePages:") {
            in >> kib;
            return kib * 1024;
        }
        in.ignore(1 << 12, '\n');
    }
    return 0;
}

struct BenchEventOptions {
    int dim = 3;
    std::size_t n = 32000;
    double eta = 0.45;
    double time = 20.0;
    double warmup = 2.0;
    double skin = -1.0;
    std::uint64_t seed = 1;
    double size_ratio = 1.0; // < 1: equimolar binary mixture of diameters 1 and size_ratio
    bool shuffle = false;    // the start in random storage order
};

// An equimolar binary mixture in the rock-salt arrangement: the large spheres
// (diameter 1) on an FCC lattice of n_c^3 cubic cells, the small ones (diameter
// size_ratio) in its octahedral holes, which sit half a cell edge along x from every
// lattice site. The holes leave room for a small sphere while the cell edge a
// satisfies a / 2 >= (1 + size_ratio) / 2, i.e. at low enough packing fraction.
ParticleStore<3> rock_salt_mixture(const BenchEventOptions& o, double L) {
    const auto cells = static_cast<std::size_t>(std::llround(std::cbrt(o.n / 8.0)));
    if (8 * cells * cells * cells != o.n)
        throw InputError(fmt::format("bench event: --size-ratio needs --n = 8 k^3 (e.g. 32768 "
                                     "or 1000000), not {}",
                                     o.n));
    const double a = L / static_cast<double>(cells);
    if (a < 1.0 + o.size_ratio)
        throw InputError(fmt::format("bench event: at eta {} the rock-salt start has no room "
                                     "for --size-ratio {} (cell edge {:.4f} < 1 + ratio); lower "
                                     "--eta",
                                     o.eta, o.size_ratio, a));
    ParticleStore<3> p;
    p.species_table = {Species{"L", 0.5, 1.0}, Species{"S", 0.5 * o.size_ratio, 1.0}};
    p.resize(o.n);
    const std::array<Vec<3>, 4> basis{Vec<3>{{0.0, 0.0, 0.0}}, Vec<3>{{0.5, 0.5, 0.0}},
                                      Vec<3>{{0.5, 0.0, 0.5}}, Vec<3>{{0.0, 0.5, 0.5}}};
    std::size_t k = 0;
    for (std::size_t x = 0; x < cells; ++x)
        for (std::size_t y = 0; y < cells; ++y)
            for (std::size_t z = 0; z < cells; ++z)
                for (const auto& b : basis)
                    for (std::uint16_t s = 0; s < 2; ++s) {
                        const Vec<3> cell{{static_cast<double>(x), static_cast<double>(y),
                                           static_cast<double>(z)}};
                        const Vec<3> hole{{0.5 * s, 0.0, 0.0}};
                        p.position[k] = (cell + b + hole) * a - Vec<3>::filled(0.5 * L) +
                                        Vec<3>::filled(0.25 * a);
                        p.species[k] = s;
                        ++k;
                    }
    return p;
}

template <int D> void run_bench(const BenchEventOptions& o) {
    if (o.n == 0) throw InputError("bench event: --n must be positive");
    const double max_eta = D == 2 ? 0.85 : 0.70;
    if (!(o.eta > 0.0 && o.eta < max_eta))
        throw InputError(fmt::format("bench event: --eta must lie in (0, {})", max_eta));
    const bool mixture = o.size_ratio != 1.0;
    if (mixture && (D != 3 || !(o.size_ratio > 0.0 && o.size_ratio < 1.0)))
        throw InputError("bench event: --size-ratio must lie in (0, 1), in 3D");
    const double sigma = 1.0;
    const double ball = D == 2 ? std::numbers::pi / 4.0 : std::numbers::pi / 6.0;
    // mean particle volume: equal numbers of diameters 1 and size_ratio in a mixture
    const double particle_volume =
        mixture ? 0.5 * ball * (1.0 + std::pow(o.size_ratio, D)) : ball * std::pow(sigma, D);
    const double L = std::pow(static_cast<double>(o.n) * particle_volume / o.eta, 1.0 / D);
    Box<D> box(Vec<D>::filled(L), [] {
        std::array<bool, D> p;
        p.fill(true);
        return p;
    }());

    ParticleStore<D> p;
    if constexpr (D == 3) {
        if (mixture) p = rock_salt_mixture(o, L);
    }
    if (!mixture) {
        p.species_table = {Species{"A", 0.5 * sigma, 1.0}};
        const auto kind = D == 2 ? LatticeKind::hexagonal : LatticeKind::fcc;
        std::array<bool, D> open{};
        p.resize(o.n);
        p.position =
            lattice_sites<D>(kind, Vec<D>::filled(-0.5 * L), Vec<D>::filled(0.5 * L), open, o.n);
    }
    if (o.shuffle) { // as a file from another program may come: no order in space
        std::mt19937_64 rng(o.seed);
        for (std::size_t i = p.size(); i > 1; --i) {
            const std::size_t k = rng() % i;
            std::swap(p.position[i - 1], p.position[k]);
            std::swap(p.species[i - 1], p.species[k]);
        }
    }
    VelocitySpec vs;
    vs.kind = VelocityKind::maxwell_boltzmann;
    vs.temperature = 1.0;
    {
        // (scoped: an index of every particle would otherwise live through the timed run
        // and count in the peak memory printed below)
        std::vector<std::size_t> all(o.n);
        for (std::size_t i = 0; i < o.n; ++i) {
            p.tag[i] = static_cast<std::uint32_t>(i);
            p.velocity[i] = draw_velocity<D>(vs, 1.0, o.seed, p.tag[i]);
            all[i] = i;
        }
        remove_drift(p, all);
        // periodic and momentum-free: d degrees of freedom go with the fixed momentum
        rescale_temperature(p, all, 1.0, D);
    }

    EventParams params;
    params.skin = o.skin;
    auto engine = std::make_unique<EventEngine<D>>(std::move(p), box, params);
    fmt::print(
        "bench event: dim {} N {} eta {} L {:.4f} skin {:.3f} time {} (after {} warm-up){}\n", D,
        o.n, o.eta, L, engine->skin(), o.time, o.warmup,
        mixture ? fmt::format(", equimolar mixture, size ratio {}", o.size_ratio) : "");
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
    fmt::print("cpu_kernels: {}\n", simd_name(simd_level()));
    fmt::print("collisions_per_second: {:.0f}\n", collisions / seconds);
    fmt::print("bytes_per_particle: {:.1f}\n",
               static_cast<double>(engine->memory_bytes()) / static_cast<double>(o.n));
    // how much of the process the kernel backs with 2 MiB pages (huge_pages.cpp)
    fmt::print("huge_page_bytes_per_particle: {:.1f}\n",
               static_cast<double>(huge_page_bytes()) / static_cast<double>(o.n));
    // the whole process's peak, setup included (ru_maxrss is in KiB on Linux)
    rusage usage{};
    getrusage(RUSAGE_SELF, &usage);
    fmt::print("max_rss_bytes_per_particle: {:.1f}\n",
               1024.0 * static_cast<double>(usage.ru_maxrss) / static_cast<double>(o.n));
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
    cmd->add_option("--size-ratio", o->size_ratio,
                    "3D: equimolar binary mixture of diameters 1 and this ratio (< 1), started "
                    "in the rock-salt arrangement; --n must be 8 k^3");
    cmd->add_flag("--shuffle", o->shuffle,
                  "Start with the particles stored in random order (the positions are the "
                  "lattice's, the velocities drawn by tag as without it)");
    cmd->callback([o] {
        if (o->dim == 2)
            run_bench<2>(*o);
        else
            run_bench<3>(*o);
    });
}

} // namespace pedesis::cli
