// `uniform_noise = true` in a [[integrator]] table of brownian or langevin: read from the
// config, it changes the trajectory (the kicks are other numbers) but not the
// temperature; a value that is not a boolean, the flag on an integrator without it, and
// the flag with device = "gpu" are bad input, said once.
#include "cli/cli_support.hpp"

namespace pedesis::test {
namespace {

// An ideal gas of 2000 disks at rest under langevin (T = 1.5, m = 1, gamma = 2: relaxed
// after 0.5 time units), run for 4.
std::string gas(const std::string& integrator_extra, const std::string& run_extra = "") {
    return R"(dimension = 2
dynamics = "langevin"
seed = 3
[box]
length = 200
[[species]]
name = "A"
count = 2000
radius = 0.5
[[integrator]]
name = "langevin"
T = 1.5
gamma = 2.0
)" + integrator_extra +
           R"([run]
steps = 400
dt = 0.01
)" + run_extra +
           R"([output]
log_every = 400
formats = []
progress = false
)";
}

using UniformNoise = ScratchDir;

// The temperature's tolerance: 2000 particles in 2D give 4000 velocity components, each
// m v_a^2 / T ~ chi^2_1 (relative variance 2): standard error sqrt(2 / 4000) = 2.2%;
// 10% is 4.5 standard errors, and a run that started at rest and had not been heated
// would read 0.
TEST_F(UniformNoise, ReadFromTheConfigItHeatsToTheSameTemperature) {
    write("gauss.toml", gas(""));
    write("uniform.toml", gas("uniform_noise = true\n"));
    const CliResult g = run_pedesis("run gauss.toml --out g", dir, 120);
    ASSERT_EQ(g.exit_code, 0) << g.output;
    const CliResult u = run_pedesis("run uniform.toml --out u", dir, 120);
    ASSERT_EQ(u.exit_code, 0) << u.output;
    const double tg = csv_columns(read("g/log.csv")).numbers("temperature").back();
    const double tu = csv_columns(read("u/log.csv")).numbers("temperature").back();
    EXPECT_NEAR(tg / 1.5, 1.0, 0.1);
    EXPECT_NEAR(tu / 1.5, 1.0, 0.1);
    // other kicks, another trajectory
    EXPECT_NE(tg, tu);
}

TEST_F(UniformNoise, BadValuesAndPlacesAreRefused) {
    expect_rejected(gas("uniform_noise = \"yes\"\n"), {"bad.toml", "uniform_noise"});
    // nve has no noise to shape
    std::string nve = gas("");
    nve.replace(nve.find("name = \"langevin\"\nT = 1.5\ngamma = 2.0\n"),
                std::string("name = \"langevin\"\nT = 1.5\ngamma = 2.0\n").size(),
                "name = \"nve\"\nuniform_noise = true\n");
    nve.replace(nve.find("dynamics = \"langevin\""), std::string("dynamics = \"langevin\"").size(),
                "dynamics = \"nve\"");
    expect_rejected(nve, {"bad.toml", "uniform_noise"});
    // the GPU's kernels draw Gaussian noise: refused whether or not a GPU is here
    expect_rejected(gas("uniform_noise = true\n", "device = \"gpu\"\n"),
                    {"uniform_noise", "device = \"cpu\""});
}

} // namespace
} // namespace pedesis::test
