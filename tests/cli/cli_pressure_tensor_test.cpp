// The pressure tensor in log.csv and summary.json, for every engine: the columns are
// pressure_xx, pressure_yy, pressure_xy in 2D and all six in 3D, and in every row the
// mean of the diagonal is `pressure` to the log's ten printed digits; walled and
// periodic axes, overdamped active, inertial and hard runs alike.
#include "cli/cli_support.hpp"

#include <nlohmann/json.hpp>

#include <cmath>
#include <fstream>

namespace pedesis::test {
namespace {

const std::vector<std::string> columns_2d = {"pressure_xx", "pressure_yy", "pressure_xy"};
const std::vector<std::string> columns_3d = {"pressure_xx", "pressure_yy", "pressure_zz",
                                             "pressure_xy", "pressure_xz", "pressure_yz"};

std::string hard_config(int dim, const std::string& dynamics, const std::string& boundary) {
    return "dimension = " + std::to_string(dim) + "\nseed = 5\n" + dynamics +
           "[box]\nlength = " + std::string(dim == 2 ? "20.0" : "12.0") + "\nboundary = \"" +
           boundary +
           "\"\n[[species]]\nname = \"A\"\ncount = 60\nradius = 0.5\n"
           "[[species]]\nname = \"B\"\ncount = 20\nradius = 0.7\nmass = 2.0\n"
           "[run]\ntime = 3.0\n[output]\nlog_interval = 0.5\nprogress = false\n";
}

class PressureTensorColumns : public ScratchDir {
  protected:
    void check_run(const std::string& name, const std::string& config, int dim, bool hard) {
        write(name + ".toml", config);
        const CliResult r = run_pedesis("run " + name + ".toml --out " + name, dir);
        ASSERT_EQ(r.exit_code, 0) << r.output;
        const CsvColumns log = csv_columns(read(name + "/log.csv"));
        const auto& wanted = dim == 2 ? columns_2d : columns_3d;
        for (const auto& c : wanted) ASSERT_TRUE(log.cells.count(c)) << name << ": no " << c;
        if (dim == 2) {
            for (const char* c : {"pressure_zz", "pressure_xz", "pressure_yz"})
                EXPECT_FALSE(log.cells.count(c)) << name << ": 2D has " << c;
        }
        const std::vector<double> p = log.numbers("pressure");
        ASSERT_GE(p.size(), 3u) << name;
        double largest_off_diagonal = 0.0;
        for (std::size_t row = 0; row < p.size(); ++row) {
            double trace = 0.0;
            for (int a = 0; a < dim; ++a)
                trace += log.numbers(wanted[static_cast<std::size_t>(a)])[row];
            // ten significant digits each: the mean agrees to a few parts in 1e10 of the
            // largest component
            double scale = std::abs(p[row]);
            for (int a = 0; a < dim; ++a)
                scale = std::max(scale,
                                 std::abs(log.numbers(wanted[static_cast<std::size_t>(a)])[row]));
            EXPECT_NEAR(trace / dim, p[row], 1e-9 * scale + 1e-300) << name << ", row " << row;
            for (std::size_t c = static_cast<std::size_t>(dim); c < wanted.size(); ++c)
                largest_off_diagonal =
                    std::max(largest_off_diagonal, std::abs(log.numbers(wanted[c])[row]));
        }
        // off-diagonal components are measured, not left at zero (they fluctuate about it)
        EXPECT_GT(largest_off_diagonal, 0.0) << name;
        if (hard) {
            std::ifstream in(dir / name / "summary.json");
            const auto j = nlohmann::json::parse(in);
            double trace = 0.0;
            for (const char* a : {"xx", "yy", "zz"})
                if (j.at("pressure_tensor").contains(a))
                    trace += j["pressure_tensor"][a].get<double>();
            EXPECT_EQ(j["pressure_tensor"].size(), dim == 2 ? 3u : 6u) << name;
            EXPECT_NEAR(trace / dim, j["pressure"].get<double>(),
                        1e-12 * std::abs(j["pressure"].get<double>()))
                << name;
        }
    }
};

TEST_F(PressureTensorColumns, EventRunsWithWallsAndPeriodicAxes) {
    check_run("event_walls", hard_config(2, "", "wall"), 2, true);
    check_run("event_periodic", hard_config(3, "", "periodic"), 3, true);
}

TEST_F(PressureTensorColumns, SteppedRuns) {
    const std::string stepped = "dynamics = \"stepped\"\n[stepped]\ndt = 0.005\n";
    check_run("stepped_walls", hard_config(3, stepped, "wall"), 3, true);
    check_run("stepped_periodic", hard_config(2, stepped, "periodic"), 2, true);
}

TEST_F(PressureTensorColumns, SoftRunsOverdampedActiveAndInertial) {
    check_run("abp", R"(dimension = 2
dynamics = "brownian"
seed = 4
[box]
length = 20
[[species]]
name = "A"
count = 100
radius = 1.0
positions = "square"
[[force]]
name = "harmonic"
k = 10.0
[[force]]
name = "self_propulsion"
alpha = 1.0
[[integrator]]
name = "brownian"
T = 0.1
gamma = 1.0
[[integrator]]
name = "brownian_rotation"
T = 0.5
gamma = 1.0
[run]
steps = 200
dt = 0.01
[output]
log_every = 50
progress = false
)",
              2, false);
    check_run("lj", R"(dimension = 3
dynamics = "langevin"
seed = 3
[box]
length = 7
[[species]]
name = "A"
count = 256
radius = 0.5
positions = "fcc"
[[force]]
name = "lj"
epsilon = 1.0
sigma = 1.0
tail = true
[[integrator]]
name = "langevin"
T = 1.2
gamma = 1.0
[run]
steps = 200
dt = 0.002
[output]
log_every = 50
progress = false
)",
              3, false);
}

} // namespace
} // namespace pedesis::test
