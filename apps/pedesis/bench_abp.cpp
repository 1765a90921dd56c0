#include "bench_abp.hpp"

#include "pedesis/core/error.hpp"
#include "pedesis/core/rng.hpp"
#include "pedesis/core/simd_level.hpp"
#include "pedesis/gpu/gpu_stepper.hpp"
#include "pedesis/setup/lattice.hpp"
#include "pedesis/soft/brownian.hpp"
#include "pedesis/soft/evolver.hpp"
#include "pedesis/soft/pair_force.hpp"
#include "pedesis/soft/pair_potentials.hpp"
#include "pedesis/soft/polar_align.hpp"
#include "pedesis/soft/self_propulsion.hpp"
#include "pedesis/soft/velocity_verlet.hpp"

#include <fmt/core.h>
#include <omp.h>
#include <sys/resource.h>

#include <chrono>
#include <cmath>
#include <cstring>
#include <ctime>
#include <limits>
#include <map>
#include <memory>
#include <numbers>

namespace pedesis::cli {

namespace {

struct BenchAbpOptions {
    int dim = 2;
    std::size_t n = 36000;
    int threads = 1;
    bool align = false;
    std::uint64_t steps = 1000;
    std::uint64_t warmup = 100;
    std::uint64_t seed = 1;
    // Measured (docs/performance.md): Brownian noise moves the fastest of 36000
    // particles about 0.2 per step, so a skin of 0.4 rebuilds the list every step; from
    // 1.0 to 1.5 the rate is flat, and 1.0 keeps the list smallest.
    double skin = 1.0;
    std::uint64_t sort_interval = 200;
    std::string device = "cpu";
    std::string model = "abp"; // or "lj": in.lj's Lennard-Jones liquid
    Precision precision = Precision::full;
};

// The ABP tutorial's model (Session 2), scaled to N particles at its number density.
constexpr double density = 0.4;
constexpr double radius = 1.0;
constexpr double k_harmonic = 10.0, a_harmonic = 2.0;
constexpr double alpha = 1.0, temperature = 0.1, gamma_friction = 1.0, dt = 0.01;
constexpr double j_align = 1.0;

template <int D> std::size_t state_bytes(const SoftState<D>& s) {
    return s.p.position.capacity() * sizeof(Vec<D>) + s.p.velocity.capacity() * sizeof(Vec<D>) +
           s.p.tag.capacity() * sizeof(std::uint32_t) +
           s.p.species.capacity() * sizeof(std::uint16_t) + s.director.capacity() * sizeof(Vec<D>) +
           s.force.capacity() * sizeof(Vec<D>) + s.torque.capacity() * sizeof(TorqueVec<D>) +
           s.image.capacity() * sizeof(s.image[0]);
}

// CPU time of the whole process: on a shared machine, wall time also counts the time
// other jobs held the core.
double cpu_seconds() {
    timespec t{};
    clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &t);
    return static_cast<double>(t.tv_sec) + 1e-9 * static_cast<double>(t.tv_nsec);
}

// FNV-1a over positions and directors in tag order: equal runs (other thread counts,
// other builds meant to give the same numbers) print the same value.
template <int D> std::uint64_t state_checksum(const SoftState<D>& s) {
    std::uint64_t h = 0xcbf29ce484222325ull;
    auto add = [&h](const Vec<D>& v) {
        unsigned char bytes[sizeof(double) * D];
        std::memcpy(bytes, v.c.data(), sizeof bytes);
        for (unsigned char b : bytes) h = (h ^ b) * 0x100000001b3ull;
    };
    for (std::uint32_t i : s.p.index_of_tags()) {
        add(s.p.position[i]);
        add(s.director[i]);
    }
    return h;
}

double max_rss_bytes() {
    rusage u{};
    getrusage(RUSAGE_SELF, &u);
    return static_cast<double>(u.ru_maxrss) * 1024.0; // Linux reports kilobytes
}

// Random sequential placement with centres at least 1 apart, as the tutorial's builder
// (make_random with rcut = 1): fully random centres can sit on top of each other, and
// the first steps would then move some particles further than a small skin allows. A grid of cells
// narrower than 1/sqrt(D) holds at most one centre each, so each trial looks at a fixed
// block of cells and placement is O(N). Serial and drawn per tag, so the system does not
// depend on the thread count. Directors are uniform.
template <int D> void place_particles(SoftState<D>& s, const BenchAbpOptions& o, double L) {
    constexpr double min_dist = 1.0;
    const auto cells = static_cast<std::int64_t>(std::ceil(L * std::sqrt(double(D)) / min_dist));
    const double w = L / static_cast<double>(cells);
    const int reach = static_cast<int>(std::ceil(min_dist / w));
    std::size_t total = 1;
    for (int a = 0; a < D; ++a) total *= static_cast<std::size_t>(cells);
    std::vector<std::int32_t> grid(total, -1);
    auto cell_of = [&](double x) {
        return std::min(cells - 1, static_cast<std::int64_t>((x + 0.5 * L) / w));
    };
    for (std::size_t i = 0; i < o.n; ++i) {
        const auto tag = static_cast<std::uint32_t>(i);
        CounterRng rng(o.seed, RngStream::placement, tag);
        s.p.tag[i] = tag;
        s.p.species[i] = 0;
        while (true) {
            Vec<D> r;
            std::array<std::int64_t, D> c;
            for (int a = 0; a < D; ++a) {
                r[a] = rng.uniform(-0.5 * L, 0.5 * L);
                if (r[a] >= 0.5 * L) r[a] = -0.5 * L; // uniform() may return exactly 1
                c[a] = cell_of(r[a]);
            }
            bool free = true;
            std::array<int, D> k;
            k.fill(-reach);
            while (free) { // the (2 reach + 1)^D block around c
                std::size_t idx = 0, stride = 1;
                for (int a = 0; a < D; ++a) {
                    idx +=
                        static_cast<std::size_t>(((c[a] + k[a]) % cells + cells) % cells) * stride;
                    stride *= static_cast<std::size_t>(cells);
                }
                const std::int32_t j = grid[idx];
                if (j >= 0 && norm2(s.box.minimum_image(r - s.p.position[j])) < min_dist * min_dist)
                    free = false;
                int a = 0;
                while (a < D && ++k[a] > reach) k[a++] = -reach;
                if (a == D) break;
            }
            if (!free) continue;
            s.p.position[i] = r;
            std::size_t idx = 0, stride = 1;
            for (int a = 0; a < D; ++a) {
                idx += static_cast<std::size_t>(c[a]) * stride;
                stride *= static_cast<std::size_t>(cells);
            }
            grid[idx] = static_cast<std::int32_t>(i);
            break;
        }
        if constexpr (D == 2) {
            const double theta = rng.uniform(0.0, 2.0 * std::numbers::pi);
            s.director[i] = Vec<D>{{std::cos(theta), std::sin(theta)}};
        } else {
            Vec<D> d;
            for (int a = 0; a < D; ++a) d[a] = rng.normal();
            s.director[i] = d * (1.0 / norm(d));
        }
    }
}

template <int D> void build_system(SoftState<D>& s, const BenchAbpOptions& o, double L) {
    std::array<bool, D> periodic;
    periodic.fill(true);
    s.box = Box<D>(Vec<D>::filled(L), periodic);
    s.resize(o.n);
    s.p.species_table = {Species{"A", radius, 1.0}};
    place_particles(s, o, L);
}

// LAMMPS' bench/in.lj: fcc at reduced density 0.8442, LJ cut at 2.5 (not shifted), skin
// 0.3, NVE with dt 0.005, velocities at T = 1.44 with zero total momentum; N is rounded to
// 4 m^3.
constexpr double lj_density = 0.8442, lj_temperature = 1.44, lj_dt = 0.005, lj_skin = 0.3;

std::size_t lj_cells(std::size_t n) {
    return static_cast<std::size_t>(std::llround(std::cbrt(static_cast<double>(n) / 4.0)));
}

void build_lj(SoftState<3>& s, std::size_t n, std::uint64_t seed) {
    const std::size_t m = std::max<std::size_t>(lj_cells(n), 1);
    const double L = static_cast<double>(m) * std::cbrt(4.0 / lj_density);
    s.box = Box<3>(Vec<3>::filled(L), {true, true, true});
    const std::size_t count = 4 * m * m * m;
    s.resize(count);
    s.p.species_table = {Species{"A", 0.5, 1.0}};
    const auto sites = lattice_sites<3>(LatticeKind::fcc, Vec<3>::filled(-0.5 * L),
                                        Vec<3>::filled(0.5 * L), {false, false, false}, count);
    Vec<3> mean{};
    for (std::size_t i = 0; i < count; ++i) {
        s.p.position[i] = sites[i];
        s.p.tag[i] = static_cast<std::uint32_t>(i);
        s.director[i] = Vec<3>{{1.0, 0.0, 0.0}};
        CounterRng rng(seed, RngStream::velocity, static_cast<std::uint32_t>(i));
        for (int a = 0; a < 3; ++a) s.p.velocity[i][a] = std::sqrt(lj_temperature) * rng.normal();
        mean += s.p.velocity[i];
    }
    mean *= 1.0 / static_cast<double>(count);
    for (auto& v : s.p.velocity) v -= mean;
}

// What both models print: rate, list, memory and a checksum of the final state.
template <int D>
void time_and_report(SoftState<D>& s, Evolver<D>& e, const BenchAbpOptions& o, double step_dt) {
    e.run(o.warmup, step_dt);
    const std::uint64_t builds0 = e.list_builds();
    const double cpu0 = cpu_seconds();
    const auto t0 = std::chrono::steady_clock::now();
    e.run(o.steps, step_dt);
    const auto t1 = std::chrono::steady_clock::now();
    const double cpu = cpu_seconds() - cpu0;
    const double seconds = std::chrono::duration<double>(t1 - t0).count();
    const std::uint64_t builds = e.list_builds() - builds0;
    e.sync_host();

    const std::size_t n = s.size();
    const double nd = static_cast<double>(n);
    const double particle_steps = nd * static_cast<double>(o.steps);
    fmt::print("wall_seconds: {:.3f}  seconds_per_step: {:.4g}  cpu_seconds: {:.3f} "
               "(cpu_particle_steps_per_second: {:.0f})\n",
               seconds, seconds / static_cast<double>(o.steps), cpu, particle_steps / cpu);
    const double every = builds ? static_cast<double>(o.steps) / static_cast<double>(builds)
                                : std::numeric_limits<double>::infinity();
    const double state = static_cast<double>(state_bytes(s));
    double list = 0.0;
    if (const auto* device = e.device()) {
        fmt::print("list_builds: {} (one every {:.1f} steps, each a sort along the curve)\n",
                   builds, every);
        fmt::print("device: {}\n", device->description());
        fmt::print("device_bytes_per_particle: {:.1f}  max_rss_bytes_per_particle: {:.1f}\n",
                   static_cast<double>(device->device_bytes()) / nd, max_rss_bytes() / nd);
    } else {
        const auto& nl = e.neighbor_list();
        list = static_cast<double>(nl.memory_bytes());
        fmt::print("list_builds: {} (one every {:.1f} steps; space-filling-curve sorts included)  "
                   "list_entries_per_particle: {:.2f} (each pair once)\n",
                   builds, every, static_cast<double>(nl.entries()) / nd);
        fmt::print("state_bytes_per_particle: {:.1f}  neighbour_list_bytes_per_particle: {:.1f}  "
                   "max_rss_bytes_per_particle: {:.1f}\n",
                   state / nd, list / nd, max_rss_bytes() / nd);
    }
    if (!e.device()) {
        fmt::print("cpu_kernels: {}\n", simd_name(simd_level()));
        bool mixed = true;
        for (const auto& f : e.forces())
            if (const auto p = f->rows_precision(s)) mixed = mixed && *p == Precision::mixed;
        fmt::print("precision: {}\n", precision_name(mixed ? o.precision : Precision::full));
    }
    fmt::print("state_checksum: {:016x}\n", state_checksum(s));
    fmt::print("particle_steps_per_second: {:.0f}\n", particle_steps / seconds);
    if (!e.device()) fmt::print("bytes_per_particle: {:.1f}\n", (state + list) / nd);
}

void run_lj(const BenchAbpOptions& o) {
    if (o.steps < 1) throw InputError("bench abp: --steps must be at least 1");
    if (lj_cells(o.n) < 3) throw InputError("bench abp --model lj: --n must be at least 108");
    omp_set_num_threads(o.threads);
    SoftState<3> s;
    build_lj(s, o.n, o.seed);
    s.pair_precision = o.precision;
    Evolver<3> e(s, lj_skin);
    e.add_force(std::make_unique<PairForce<3, LjPair>>("lj", LjPair{1.0, 1.0, 2.5, false}));
    e.add_integrator(std::make_unique<VelocityVerletIntegrator<3>>());
    e.set_sort_interval(o.sort_interval);
    // as a fresh `pedesis run` does: the first sort interval would otherwise run with
    // the neighbour rows pointing at memory in placement order
    e.sort_storage_at_start();
    if (o.device == "gpu" && o.precision == Precision::mixed)
        throw InputError("bench abp: --precision mixed runs on the CPU (the GPU path computes in "
                         "double only)");
    if (o.device == "gpu") e.set_device(make_gpu_stepper<3>(s, e, {}));
    fmt::print("bench abp --model lj: dim 3 N {} density {} L {:.4f} threads {} device {}\n",
               s.size(), lj_density, s.box.length(0), o.threads, o.device);
    fmt::print("model: in.lj (LJ epsilon 1 sigma 1 cut 2.5, fcc start, T0 {}), nve, dt {}, skin "
               "{}, steps {} (after {} warm-up) seed {}\n",
               lj_temperature, lj_dt, lj_skin, o.steps, o.warmup, o.seed);
    time_and_report(s, e, o, lj_dt);
}

template <int D> void run_bench(const BenchAbpOptions& o) {
    if (o.n < 2) throw InputError("bench abp: --n must be at least 2");
    if (o.n > static_cast<std::size_t>(std::numeric_limits<std::int32_t>::max()))
        throw InputError("bench abp: --n must be below 2^31");
    if (o.threads < 1) throw InputError("bench abp: --threads must be at least 1");
    if (o.steps < 1) throw InputError("bench abp: --steps must be at least 1");
    if (!(o.skin >= 0.0 && std::isfinite(o.skin)))
        throw InputError("bench abp: --skin must be a finite number >= 0");
    const double L = std::pow(static_cast<double>(o.n) / density, 1.0 / D);
    const double r_list = a_harmonic + o.skin;
    if (L < 2.0 * r_list)
        throw InputError(fmt::format(
            "bench abp: box side {:.4g} (N = {} at density {}) is too small for the list "
            "cutoff {} + skin {}: the minimum image needs a side of at least {}; use a larger "
            "--n (at least {:.0f}) or a smaller --skin",
            L, o.n, density, a_harmonic, o.skin, 2.0 * r_list,
            std::ceil(density * std::pow(2.0 * r_list, D))));
    omp_set_num_threads(o.threads);

    SoftState<D> s;
    build_system(s, o, L);
    s.pair_precision = o.precision;
    Evolver<D> e(s, o.skin);
    e.add_force(std::make_unique<PairForce<D, HarmonicPair>>("harmonic",
                                                             HarmonicPair{k_harmonic, a_harmonic}));
    e.add_force(std::make_unique<SelfPropulsion<D>>(alpha));
    if (o.align) e.add_torque(std::make_unique<PolarAlign<D>>(j_align, a_harmonic));
    e.add_integrator(std::make_unique<BrownianIntegrator<D>>(temperature, gamma_friction, o.seed));
    e.add_integrator(
        std::make_unique<BrownianRotationIntegrator<D>>(temperature, gamma_friction, o.seed));
    e.set_sort_interval(o.sort_interval);
    // as a fresh `pedesis run` does: the first sort interval would otherwise run with
    // the neighbour rows pointing at memory in placement order
    e.sort_storage_at_start();
    if (o.device == "gpu" && o.precision == Precision::mixed)
        throw InputError("bench abp: --precision mixed runs on the CPU (the GPU path computes in "
                         "double only)");
    if (o.device == "gpu") e.set_device(make_gpu_stepper<D>(s, e, {}));

    fmt::print("bench abp: dim {} N {} density {} L {:.4f} threads {} device {}\n", D, o.n, density,
               L, o.threads, o.device);
    fmt::print("model: harmonic k {} a {}, self-propulsion alpha {}, T {} (positions and "
               "rotations), gamma {}, dt {}, alignment {}\n",
               k_harmonic, a_harmonic, alpha, temperature, gamma_friction, dt,
               o.align ? fmt::format("J {}", j_align) : std::string("off"));
    fmt::print("skin {} sort_interval {} steps {} (after {} warm-up) seed {}\n", o.skin,
               o.sort_interval, o.steps, o.warmup, o.seed);

    time_and_report(s, e, o, dt);
}

} // namespace

void add_bench_abp(CLI::App& bench) {
    auto o = std::make_shared<BenchAbpOptions>();
    auto* cmd = bench.add_subcommand(
        "abp", "Particle-steps per second of the soft/active engine (the ABP tutorial's system)");
    cmd->add_option("--n", o->n, "Number of particles (number density 0.4)");
    cmd->add_option("--threads", o->threads, "OpenMP threads");
    cmd->add_flag("--align", o->align, "Add polar alignment (J = 1, range 2)");
    cmd->add_option("--dim", o->dim, "Dimension (2 or 3)")->check(CLI::IsMember({2, 3}));
    cmd->add_option("--steps", o->steps, "Steps measured (after the warm-up)");
    cmd->add_option("--warmup", o->warmup, "Steps run before measuring");
    cmd->add_option("--seed", o->seed, "Random seed");
    cmd->add_option("--skin", o->skin, "Neighbour-list skin");
    cmd->add_option("--sort-interval", o->sort_interval,
                    "Steps between space-filling-curve sorts (0: never)");
    cmd->add_option("--precision", o->precision,
                    "Pair math: double, or mixed (float pair rows, double integration)")
        ->transform(CLI::CheckedTransformer(std::map<std::string, Precision>{
            {"double", Precision::full}, {"mixed", Precision::mixed}}));
    cmd->add_option("--device", o->device, "Where to step: cpu or gpu (docs/gpu.md)")
        ->check(CLI::IsMember({"cpu", "gpu"}));
    cmd->add_option("--model", o->model,
                    "abp: the tutorial's active Brownian particles; lj: LAMMPS' in.lj liquid "
                    "(3D, N rounded to 4 m^3)")
        ->check(CLI::IsMember({"abp", "lj"}));
    cmd->callback([o] {
        if (o->model == "lj")
            run_lj(*o);
        else if (o->dim == 2)
            run_bench<2>(*o);
        else
            run_bench<3>(*o);
    });
}

} // namespace pedesis::cli
