// gravity, harmonic_trap and active_ou through the command line: the log's
// gravity_energy and trap_energy columns against their definitions from the snapshots'
// positions (and potential_energy their sum, with no pair force), a restart of active
// Ornstein-Uhlenbeck particles that continues bit for bit (their active velocities are
// in the checkpoint), and the set-up's refusals.
#include "cli/cli_support.hpp"

#include <nlohmann/json.hpp>

#include <cmath>
#include <regex>

namespace pedesis::test {
namespace {

class FieldsAndAoup : public ScratchDir {};

// Two species in a periodic 3D box: gravity along x (weights 1.5 and -0.5), a trap with
// one stiffness per axis centred off the origin (so that the nearest image of the centre
// matters for the particles far from it).
const std::string fields_config = R"(dimension = 3
dynamics = "brownian"
seed = 5

[box]
length = 12.0

[neighbor_list]
skin = 3.0

[[species]]
name = "A"
count = 60
radius = 0.5

[[species]]
name = "B"
count = 40
radius = 0.5

[[force]]
name = "gravity"
axis = "x"
force = { A = 1.5, B = -0.5 }

[[force]]
name = "harmonic_trap"
k = [0.5, 1.0, 2.0]
centre = [3.0, -1.0, 0.5]

[[integrator]]
name = "brownian"
T = 1.0
gamma = 1.0

[run]
steps = 20
dt = 0.01

[output]
log_every = 10
snapshot_every = 10
formats = ["json"]
progress = false
)";

TEST_F(FieldsAndAoup, FieldEnergiesAreTheirDefinitionsInTheLog) {
    write("fields.toml", fields_config);
    const CliResult r = run_pedesis("run fields.toml --out out", dir, 60);
    ASSERT_EQ(r.exit_code, 0) << r.output;
    const CsvColumns log = csv_columns(read("out/log.csv"));
    const auto gravity = log.numbers("gravity_energy"), trap = log.numbers("trap_energy"),
               potential = log.numbers("potential_energy");
    ASSERT_EQ(gravity.size(), 3u);
    const double weight[2] = {1.5, -0.5}, k[3] = {0.5, 1.0, 2.0}, c[3] = {3.0, -1.0, 0.5};
    const double L = 12.0;
    for (std::size_t row = 0; row < 3; ++row) {
        char name[64];
        std::snprintf(name, sizeof name, "out/snapshots/frame_%06zu.json", row);
        const auto frame = nlohmann::json::parse(read(name));
        double u_gravity = 0.0, u_trap = 0.0;
        for (const auto& p : frame["system"]["particles"]) {
            const auto r_i = p["r"].get<std::vector<double>>();
            u_gravity += weight[p["type"].get<int>()] * r_i[0];
            for (int a = 0; a < 3; ++a) {
                double d = r_i[static_cast<std::size_t>(a)] - c[a];
                d -= L * std::round(d / L);
                u_trap += 0.5 * k[a] * d * d;
            }
        }
        // the log prints 10 significant digits
        EXPECT_NEAR(gravity[row], u_gravity, 1e-8 * (1.0 + std::abs(u_gravity))) << "row " << row;
        EXPECT_NEAR(trap[row], u_trap, 1e-8 * u_trap) << "row " << row;
        EXPECT_NEAR(potential[row], u_gravity + u_trap, 1e-8 * (u_gravity + u_trap))
            << "row " << row;
    }
}

// AOUPs (with thermal noise and storage sorts on both sides of the checkpoint): 100
// steps, then a restart to 200, equal 200 steps in one go.
std::string aoup_config(int steps) {
    return R"(dimension = 2
dynamics = "brownian"
seed = 9

[box]
length = 30.0

[neighbor_list]
skin = 0.5
sort_every = 30

[[species]]
name = "A"
count = 400
radius = 0.5

[[force]]
name = "harmonic"
k = 10.0

[[force]]
name = "active_ou"
tau = 0.5
D_a = 0.3

[[integrator]]
name = "brownian"
T = 0.1
gamma = 1.0

[run]
steps = )" +
           std::to_string(steps) +
           R"(
dt = 0.002

[output]
log_every = 25
snapshot_every = 100
formats = ["json"]
progress = false
)";
}

TEST_F(FieldsAndAoup, ActiveOuRestartEqualsContinuousRun) {
    write("full.toml", aoup_config(200));
    write("half.toml", aoup_config(100));
    const auto full = run_pedesis("run full.toml --out full", dir, 60);
    ASSERT_EQ(full.exit_code, 0) << full.output;
    ASSERT_EQ(run_pedesis("run half.toml --out half", dir, 60).exit_code, 0);
    const auto cont =
        run_pedesis("run full.toml --out cont --restart half/checkpoint.bin", dir, 60);
    ASSERT_EQ(cont.exit_code, 0) << cont.output;
    const std::string a = read("full/snapshots/frame_000002.json");
    ASSERT_FALSE(a.empty());
    EXPECT_TRUE(a == read("cont/snapshots/frame_000002.json"))
        << "the restarted run differs from the continuous one";
    // the log rows after the checkpoint (pressure_active among them) agree too
    const std::string la = read("full/log.csv"), lb = read("cont/log.csv");
    EXPECT_NE(la.find(lb.substr(lb.find('\n') + 1)), std::string::npos) << lb;
    // and the swim pressure is there
    const auto active = csv_columns(lb).numbers("pressure_active");
    ASSERT_FALSE(active.empty());
    EXPECT_GT(active.back(), 0.0);
}

TEST_F(FieldsAndAoup, SetUpRefusals) {
    expect_rejected(std::regex_replace(fields_config, std::regex("axis = \"x\""), "axis = \"w\""),
                    {"bad.toml", "'w' is not one of x, y, z"});
    expect_rejected(
        std::regex_replace(fields_config, std::regex("k = \\[0.5, 1.0, 2.0\\]"), "k = [0.5, 1.0]"),
        {"gives 2 numbers for a 3D box"});
    std::string nve = std::regex_replace(aoup_config(10), std::regex("brownian"), "nve");
    nve = std::regex_replace(nve, std::regex("T = 0.1\ngamma = 1.0\n"), "");
    expect_rejected(nve, {"bad.toml", "active_ou", "brownian or langevin"});
}

} // namespace
} // namespace pedesis::test
