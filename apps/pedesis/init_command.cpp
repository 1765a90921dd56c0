#include "init_command.hpp"

#include "pedesis/core/error.hpp"
#include "pedesis/core/rng.hpp"
#include "pedesis/io/atomic_file.hpp"
#include "pedesis/io/tutorial_json.hpp"
#include "pedesis/setup/random_placement.hpp"
#include "pedesis/soft/soft_state.hpp"

#include <fmt/core.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <limits>
#include <memory>
#include <numbers>
#include <optional>
#include <ostream>
#include <string>
#include <vector>

namespace pedesis::cli {

namespace {

struct InitRandomOptions {
    double phi = 0.0;
    double L = 0.0;
    std::optional<double> Ly, Lz;
    double rcut = 0.0;
    double radius = 1.0;
    int dim = 2;
    std::uint64_t seed = 1;
    std::string output;
};

void require_positive(double x, const char* option, const char* what) {
    if (!(std::isfinite(x) && x > 0.0))
        throw InputError(
            fmt::format("init random: {} must be a positive {}, got {}", option, what, x));
}

// The densest arrangement of points at least rcut apart (hexagonal in 2D, fcc in 3D)
// holds this many per rcut^D; above it no placement can succeed, so say so at once
// instead of letting random placement grind to its give-up.
constexpr double close_packing_density(int dim) {
    return dim == 2 ? 2.0 / std::numbers::sqrt3 : std::numbers::sqrt2;
}

// Random sequential placement stalls well below close packing, near this density
// (jamming coverage 0.547 of disks, 0.384 of spheres, of diameter rcut).
constexpr double jamming_density(int dim) {
    return dim == 2 ? 0.547 * 4.0 / std::numbers::pi : 0.384 * 6.0 / std::numbers::pi;
}

template <int D> std::string box_text(const Box<D>& box) {
    std::string s = fmt::format("{}", box.length(0));
    for (int a = 1; a < D; ++a) s += fmt::format(" x {}", box.length(a));
    return s;
}

template <int D>
std::vector<Vec<D>> random_positions(const Box<D>& box, std::size_t n, const InitRandomOptions& o) {
    std::vector<Vec<D>> pos;
    pos.reserve(n);
    if (o.rcut == 0.0) {
        // Nothing to avoid, and a zero distance would ask the cell list for zero-width
        // cells; these are the draws place_randomly would accept first.
        for (std::size_t k = 0; k < n; ++k) {
            CounterRng rng(o.seed, RngStream::placement, static_cast<std::uint32_t>(k));
            Vec<D> r;
            for (int a = 0; a < D; ++a) r[a] = rng.uniform(box.lo(a), box.hi(a));
            pos.push_back(r);
        }
    } else {
        // Centres are points here: the soft particles' radius may overlap, only rcut counts.
        std::vector<double> radii;
        PlacementRequest<D> req;
        req.count = n;
        req.radius = 0.0;
        for (int a = 0; a < D; ++a) {
            req.lo[a] = box.lo(a);
            req.hi[a] = box.hi(a);
        }
        req.min_distance = o.rcut;
        req.what = "init random";
        try {
            place_randomly(pos, radii, box, req, o.seed);
        } catch (const InputError&) {
            throw InputError(fmt::format(
                "init random: --phi {} is too dense to place centres --rcut {} apart at random: "
                "gave up after {} of {} particles (random placement stalls near phi * rcut^{} = "
                "{:.2f}); lower --phi or --rcut",
                o.phi, o.rcut, pos.size(), n, D, jamming_density(D)));
        }
    }
    // The uniform draws include the upper edge; the box is half-open, and moving a
    // centre across a periodic edge changes no minimum-image distance.
    for (Vec<D>& r : pos) box.wrap(r);
    return pos;
}

// Uniform on the circle or the sphere. The placement stream with its second counter
// word at 1 never meets the counters place_randomly uses (word 1 = 0), so positions
// and directors are independent without a stream of their own.
template <int D> Vec<D> random_director(std::uint64_t seed, std::uint32_t tag) {
    CounterRng rng(seed, RngStream::placement, tag, 1);
    const double angle = 2.0 * std::numbers::pi * rng.uniform();
    Vec<D> n;
    if constexpr (D == 2) {
        n[0] = std::cos(angle);
        n[1] = std::sin(angle);
    } else {
        const double z = rng.uniform(-1.0, 1.0);
        const double s = std::sqrt(std::max(0.0, 1.0 - z * z));
        n[0] = s * std::cos(angle);
        n[1] = s * std::sin(angle);
        n[2] = z;
    }
    return n;
}

template <int D> void init_random(const InitRandomOptions& o) {
    require_positive(o.phi, "--phi", "number density (particles per unit area or volume)");
    require_positive(o.L, "--L", "box length");
    if (o.Ly) require_positive(*o.Ly, "--Ly", "box length");
    if (o.Lz) require_positive(*o.Lz, "--Lz", "box length");
    if (D == 2 && o.Lz) throw InputError("init random: --Lz needs --dim 3");
    if (!(std::isfinite(o.rcut) && o.rcut >= 0.0))
        throw InputError(fmt::format(
            "init random: --rcut must be a distance >= 0 (0: centres may coincide), got {}",
            o.rcut));
    require_positive(o.radius, "--radius", "particle radius");

    Vec<D> L;
    L[0] = o.L;
    L[1] = o.Ly.value_or(o.L);
    if constexpr (D == 3) L[2] = o.Lz.value_or(o.L);
    std::array<bool, D> periodic;
    periodic.fill(true);
    const Box<D> box(L, periodic);

    const double wanted = std::round(o.phi * box.volume());
    if (!(wanted <= static_cast<double>(std::numeric_limits<std::uint32_t>::max())))
        throw InputError(fmt::format(
            "init random: --phi {} in a box {} gives {} particles, more than particle ids "
            "can number ({})",
            o.phi, box_text(box), wanted, std::numeric_limits<std::uint32_t>::max()));
    const auto n = static_cast<std::size_t>(wanted);
    if (n == 0)
        throw InputError(fmt::format("init random: --phi {} in a box {} gives no particle "
                                     "(N = round(phi * volume) = 0)",
                                     o.phi, box_text(box)));
    if (o.phi * std::pow(o.rcut, D) > close_packing_density(D))
        throw InputError(fmt::format(
            "init random: --phi {} is impossible with --rcut {}: no arrangement puts centres "
            "that densely at least rcut apart (close packing allows phi * rcut^{} <= {:.4f}); "
            "lower --phi or --rcut",
            o.phi, o.rcut, D, close_packing_density(D)));
    // The cell list behind the placement sizes its grid from L / rcut in an int.
    double longest = 0.0;
    for (int a = 0; a < D; ++a) longest = std::max(longest, box.length(a));
    if (o.rcut > 0.0 && longest > 1e9 * o.rcut)
        throw InputError(fmt::format(
            "init random: --rcut {} is below 1e-9 of the box length; use --rcut 0 for no "
            "minimum distance",
            o.rcut));

    const std::vector<Vec<D>> pos = random_positions(box, n, o);

    SoftState<D> s;
    s.box = box;
    s.p.species_table = {Species{"A", o.radius, 1.0}};
    s.resize(n);
    for (std::size_t i = 0; i < n; ++i) {
        const auto tag = static_cast<std::uint32_t>(i);
        s.p.tag[i] = tag;
        s.p.species[i] = 0;
        s.p.position[i] = pos[i];
        s.director[i] = random_director<D>(o.seed, tag);
    }

    const std::string text = to_tutorial_json(s).dump() + "\n";
    write_file_atomically(o.output, [&](std::ostream& out) { out << text; });
    fmt::print("init random: wrote {} particles ({}D, box {}, phi {}, rcut {}, seed {}) to {}\n", n,
               D, box_text(box), o.phi, o.rcut, o.seed, o.output);
}

} // namespace

void add_init_command(CLI::App& app) {
    auto* init = app.add_subcommand("init", "Write an initial configuration");
    init->require_subcommand(1);

    auto o = std::make_shared<InitRandomOptions>();
    auto* cmd = init->add_subcommand(
        "random", "Random positions and directors in a periodic box centred at the origin, in "
                  "the JSON layout of the ABP tutorial (what its random_init writes)");
    cmd->add_option("--phi", o->phi, "Number density N / V (N = round(phi V))")->required();
    cmd->add_option("--L", o->L, "Box length (all axes unless --Ly, --Lz)")->required();
    cmd->add_option("--Ly", o->Ly, "Box length along y (default: --L)");
    cmd->add_option("--Lz", o->Lz, "Box length along z, 3D only (default: --L)");
    cmd->add_option("--rcut", o->rcut,
                    "Least distance between centres, minimum image (default 0: no check)");
    cmd->add_option("--radius", o->radius, "Particle radius written to the file (default 1)");
    cmd->add_option("--dim", o->dim, "Dimension (2 or 3)")->check(CLI::IsMember({2, 3}));
    cmd->add_option("--seed", o->seed, "Random seed (same seed, same file)");
    cmd->add_option("-o,--output", o->output, "JSON file to write")->required();
    cmd->callback([o] {
        if (o->dim == 2)
            init_random<2>(*o);
        else
            init_random<3>(*o);
    });
}

} // namespace pedesis::cli
