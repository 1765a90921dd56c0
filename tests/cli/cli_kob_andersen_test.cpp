// The Kob-Andersen examples from the command line, shortened: examples/kob_andersen.toml
// (Langevin NVT at T = 1 with per-pair Lennard-Jones parameters) for 2000 steps, then
// examples/kob_andersen_nve.toml continued from its checkpoint for 1000 NVE steps.
// - The thermostat holds the kinetic temperature: the mean of the log's temperature
//   column over the last 1000 steps (5 rows of N = 1000, each with a relative spread of
//   sqrt(2 / 3N) = 2.6%, correlated over ~1 time unit) lies within 5% of 1.
// - NVE conserves the total energy (potential_energy + kinetic_energy columns): velocity
//   Verlet at dt = 0.005 keeps it to ~1e-4 here, shifted potentials leave no jumps at
//   the cutoffs; 1e-3 would catch a wrong pair force, a missing shift or a broken restart.
#include "cli_support.hpp"

#include <fstream>
#include <regex>

using namespace pedesis::test;

namespace {

class KobAndersen : public ScratchDir {};

std::string example(const std::string& name) {
    std::ifstream in(std::string(PEDESIS_SOURCE_DIR) + "/examples/" + name);
    return std::string(std::istreambuf_iterator<char>(in), {});
}

} // namespace

TEST_F(KobAndersen, NvtHoldsTheTemperatureAndNveConservesEnergy) {
    std::string nvt = example("kob_andersen.toml");
    std::string nve = example("kob_andersen_nve.toml");
    ASSERT_NE(nvt.find("[[force.pairs]]"), std::string::npos);
    nvt = std::regex_replace(nvt, std::regex("steps = 20000"), "steps = 2000");
    nve = std::regex_replace(nve, std::regex("steps = 30000"), "steps = 3000");
    for (std::string* c : {&nvt, &nve}) {
        *c = std::regex_replace(*c, std::regex("checkpoint_every = 5000"), "checkpoint_every = 0");
        *c += "progress = false\n";
    }
    write("nvt.toml", nvt);
    write("nve.toml", nve);
    const CliResult a = run_pedesis("run nvt.toml --out nvt", dir);
    ASSERT_EQ(a.exit_code, 0) << a.output;
    const CliResult b = run_pedesis("run nve.toml --out nve --restart nvt/checkpoint.bin", dir);
    ASSERT_EQ(b.exit_code, 0) << b.output;

    const CsvColumns t = csv_columns(read("nvt/log.csv"));
    const auto steps = t.numbers("step"), temperature = t.numbers("temperature");
    double mean_T = 0.0;
    int rows = 0;
    for (std::size_t k = 0; k < steps.size(); ++k)
        if (steps[k] > 1000) {
            mean_T += temperature[k];
            ++rows;
        }
    ASSERT_EQ(rows, 5);
    EXPECT_NEAR(mean_T / rows, 1.0, 0.05);

    const CsvColumns e = csv_columns(read("nve/log.csv"));
    const auto u = e.numbers("potential_energy"), kin = e.numbers("kinetic_energy");
    ASSERT_EQ(u.size(), 5u); // steps 2200 .. 3000
    double lo = 1e300, hi = -1e300;
    for (std::size_t k = 0; k < u.size(); ++k) {
        const double total = u[k] + kin[k];
        lo = std::min(lo, total);
        hi = std::max(hi, total);
    }
    EXPECT_LT(hi - lo, 1e-3 * std::abs(lo)) << lo << " .. " << hi;
}
