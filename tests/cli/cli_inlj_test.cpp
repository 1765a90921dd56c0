// LAMMPS' in.lj at 4000 atoms (fcc, 10^3 unit cells at density 0.8442, LJ cut at 2.5 not
// shifted, NVE, dt 0.005) through the real binary: the perfect-lattice start whose first
// neighbour-list build once repeated its pass for ever (spatial/neighbor_list.cpp), from
// pedesis' own `positions = "fcc"` and from the start LAMMPS wrote
// (tests/data/inlj/start.json, made by make_reference.py there). The statistics against
// LAMMPS' own run are a validation test (tests/validation/inlj_lammps_test.cpp).
#include "cli/cli_support.hpp"
#include "support/inlj_config.hpp"

#include <cmath>

namespace pedesis::test {
namespace {

using InLj = ScratchDir;

// Both starts, both skins of the report: each run ends (a kill timer turns a hang into a
// failure) with its last log row at step 200 and the crystal melted into the liquid of
// in.lj's state (LAMMPS: T = 0.70 there; a temperature between 0.5 and 1.0 here). (The
// energy is not conserved closely: the potential is cut unshifted at 2.5, and as the
// crystal melts thousands of pairs cross the cutoff, each with a jump of U(2.5) = -0.016.)
TEST_F(InLj, PerfectLatticeStartsRunToTheEnd) {
    const std::string fcc = "[initial]\npositions = \"fcc\"\nvelocities = \"maxwell_boltzmann\"\n"
                            "temperature = 1.44\n";
    const std::string lammps = "[initial]\nfile = \"" + inlj_data_dir + "/start.json\"\n";
    int k = 0;
    for (const auto* start : {&fcc, &lammps})
        for (double skin : {0.3, 0.5}) {
            const std::string name = "case" + std::to_string(k++);
            write(name + ".toml", inlj(*start, skin, 200, 100));
            const CliResult r = run_pedesis("run " + name + ".toml --out " + name, dir, 120);
            ASSERT_EQ(r.exit_code, 0) << name << " (skin " << skin << "):\n" << r.output;
            const auto log = csv_columns(read(name + "/log.csv"));
            ASSERT_EQ(log.numbers("step").back(), 200.0) << name;
            const double T = log.numbers("temperature").back();
            EXPECT_GT(T, 0.5) << name;
            EXPECT_LT(T, 1.0) << name;
        }
}

} // namespace
} // namespace pedesis::test
