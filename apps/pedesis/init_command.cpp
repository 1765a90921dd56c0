#include "init_command.hpp"

#include "pedesis/io/atomic_file.hpp"
#include "pedesis/io/tutorial_json.hpp"
#include "pedesis/setup/init_random.hpp"

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

struct InitCommandOptions {
    InitRandomOptions random;
    int dim = 2;
    std::string output;
};

template <int D> void write_random_init(const InitCommandOptions& o) {
    const SoftState<D> s = init_random<D>(o.random);
    const std::string text = to_tutorial_json(s.frame()).dump() + "\n";
    write_file_atomically(o.output, [&](std::ostream& out) { out << text; });
    fmt::print("init random: wrote {} particles ({}D, box {}, phi {}, rcut {}, seed {}) to {}\n",
               s.size(), D, box_lengths_text(s.box), o.random.phi, o.random.rcut, o.random.seed,
               o.output);
}

} // namespace

void add_init_command(CLI::App& app) {
    auto* init = app.add_subcommand("init", "Write an initial configuration");
    init->require_subcommand(1);

    auto o = std::make_shared<InitCommandOptions>();
    auto* cmd = init->add_subcommand(
        "random", "Random positions and directors in a periodic box centred at the origin, in "
                  "the JSON layout of the ABP tutorial (what its random_init writes)");
    cmd->add_option("--phi", o->random.phi, "Number density N / V (N = round(phi V))")->required();
    cmd->add_option("--L", o->random.L, "Box length (all axes unless --Ly, --Lz)")->required();
    cmd->add_option("--Ly", o->random.Ly, "Box length along y (default: --L)");
    cmd->add_option("--Lz", o->random.Lz, "Box length along z, 3D only (default: --L)");
    cmd->add_option("--rcut", o->random.rcut,
                    "Least distance between centres, minimum image (default 0: no check)");
    cmd->add_option("--radius", o->random.radius,
                    "Particle radius written to the file (default 1)");
    cmd->add_option("--dim", o->dim, "Dimension (2 or 3)")->check(CLI::IsMember({2, 3}));
    cmd->add_option("--seed", o->random.seed, "Random seed (same seed, same file)");
    cmd->add_option("-o,--output", o->output, "JSON file to write")->required();
    cmd->callback([o] {
        if (o->dim == 2)
            write_random_init<2>(*o);
        else
            write_random_init<3>(*o);
    });
}

} // namespace pedesis::cli
