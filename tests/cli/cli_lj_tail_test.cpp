// [[force]] lj with tail = true: the homogeneous fluid's energy and pressure beyond the
// cutoff are added to the log's potential_energy and pressure (pressure_virial), as
// LAMMPS' pair_modify tail yes. Checked against the textbook closed forms, written here
// independently of the code's general-dimension formula: in 3D (Allen & Tildesley)
//   U_tail = (8/3) pi N rho eps sigma^3 [(1/3) c^-9 - c^-3],
//   P_tail = (16/3) pi rho^2 eps sigma^3 [(2/3) c^-9 - c^-3],
// in 2D (the same integrals over 2 pi r dr)
//   U_tail = pi N rho eps sigma^2 [(2/5) c^-10 - c^-4],
//   P_tail = pi rho^2 eps sigma^2 [(12/5) c^-10 - 3 c^-4],
// c the cutoff in units of sigma, and for a mixture the sum over species pairs with
// N rho -> N_a N_b / V. The trajectory is the same with and without (forces unchanged),
// and shift with tail is refused.
#include "cli_support.hpp"

#include <cmath>
#include <numbers>

using namespace pedesis::test;

namespace {

constexpr double pi = std::numbers::pi;

std::string lj_config(int dim, double length, const std::string& species,
                      const std::string& force_extra) {
    return "dimension = " + std::to_string(dim) + R"(
dynamics = "nve"
seed = 4
[box]
length = )" +
           std::to_string(length) + "\n" + species + R"(
[initial]
positions = "random"
min_distance = 0.9
velocities = "maxwell_boltzmann"
temperature = 1.0
[[force]]
name = "lj"
epsilon = 1.0
sigma = 1.0
cutoff = 2.5
)" + force_extra +
           R"(
[[integrator]]
name = "nve"
[run]
steps = 100
dt = 0.002
[output]
log_every = 50
formats = []
progress = false
)";
}

const std::string one_species = "[[species]]\nname = \"A\"\ncount = 200\nradius = 0.5\n";

// The columns of a run with tail = false and of the same run with tail = true.
struct Both {
    CsvColumns plain, tailed;
};

void expect_shifts(const Both& p, double energy, double pressure) {
    const auto u0 = p.plain.numbers("potential_energy"), u1 = p.tailed.numbers("potential_energy");
    const auto p0 = p.plain.numbers("pressure"), p1 = p.tailed.numbers("pressure");
    const auto w0 = p.plain.numbers("pressure_virial"), w1 = p.tailed.numbers("pressure_virial");
    ASSERT_EQ(u0.size(), 3u);
    ASSERT_EQ(u1.size(), 3u);
    for (std::size_t k = 0; k < u0.size(); ++k) {
        // (the log's 10 significant digits of U and P bound the agreement)
        EXPECT_NEAR(u1[k] - u0[k], energy, 1e-8 * (std::abs(u0[k]) + std::abs(energy))) << k;
        EXPECT_NEAR(p1[k] - p0[k], pressure, 1e-8 * (std::abs(p0[k]) + std::abs(pressure))) << k;
        EXPECT_NEAR(w1[k] - w0[k], pressure, 1e-8 * (std::abs(w0[k]) + std::abs(pressure))) << k;
    }
    // forces are untouched: the same trajectory, bit for bit
    EXPECT_EQ(p.plain.cells.at("kinetic_energy"), p.tailed.cells.at("kinetic_energy"));
}

class LjTail : public ScratchDir {
  protected:
    Both run_both(int dim, double length, const std::string& species,
                  const std::string& extra = "") {
        write("plain.toml", lj_config(dim, length, species, extra));
        // (the force's own key before its [[force.pairs]] tables, which would take it)
        write("tailed.toml", lj_config(dim, length, species, "tail = true\n" + extra));
        const CliResult a = run_pedesis("run plain.toml --out plain", dir);
        EXPECT_EQ(a.exit_code, 0) << a.output;
        const CliResult b = run_pedesis("run tailed.toml --out tailed", dir);
        EXPECT_EQ(b.exit_code, 0) << b.output;
        return {csv_columns(read("plain/log.csv")), csv_columns(read("tailed/log.csv"))};
    }
};

} // namespace

TEST_F(LjTail, ThreeDimensionsOneSpeciesMatchesTheTextbookForm) {
    const double L = 7.0, N = 200.0, rho = N / (L * L * L), c = 2.5;
    const double energy = 8.0 / 3.0 * pi * N * rho * (std::pow(c, -9) / 3.0 - std::pow(c, -3));
    const double pressure =
        16.0 / 3.0 * pi * rho * rho * (2.0 / 3.0 * std::pow(c, -9) - std::pow(c, -3));
    expect_shifts(run_both(3, L, one_species), energy, pressure);
}

TEST_F(LjTail, TwoDimensionsOneSpeciesMatchesTheDiskForm) {
    const double L = 20.0, N = 200.0, rho = N / (L * L), c = 2.5;
    const double energy = pi * N * rho * (0.4 * std::pow(c, -10) - std::pow(c, -4));
    const double pressure = pi * rho * rho * (2.4 * std::pow(c, -10) - 3.0 * std::pow(c, -4));
    expect_shifts(run_both(2, L, one_species), energy, pressure);
}

TEST_F(LjTail, AMixtureSumsOverSpeciesPairsWithTheirOwnParameters) {
    // Kob-Andersen's pair parameters, 160 A and 40 B
    const std::string species = "[[species]]\nname = \"A\"\ncount = 160\nradius = 0.5\n"
                                "[[species]]\nname = \"B\"\ncount = 40\nradius = 0.44\n";
    const std::string pairs = "[[force.pairs]]\nspecies = [\"A\", \"B\"]\nepsilon = 1.5\n"
                              "sigma = 0.8\n[[force.pairs]]\nspecies = [\"B\", \"B\"]\n"
                              "epsilon = 0.5\nsigma = 0.88\n";
    const double L = 7.0, V = L * L * L, c = 2.5;
    const double count[2] = {160.0, 40.0};
    const double eps[2][2] = {{1.0, 1.5}, {1.5, 0.5}}, sig[2][2] = {{1.0, 0.8}, {0.8, 0.88}};
    double energy = 0.0, pressure = 0.0;
    for (int a = 0; a < 2; ++a)
        for (int b = 0; b < 2; ++b) {
            const double s3 = std::pow(sig[a][b], 3), nn = count[a] * count[b];
            // (over ordered pairs: one species gives back N rho = N^2 / V)
            energy += 8.0 / 3.0 * pi * nn / V * eps[a][b] * s3 *
                      (std::pow(c, -9) / 3.0 - std::pow(c, -3));
            pressure += 16.0 / 3.0 * pi * nn / (V * V) * eps[a][b] * s3 *
                        (2.0 / 3.0 * std::pow(c, -9) - std::pow(c, -3));
        }
    expect_shifts(run_both(3, L, species, pairs), energy, pressure);
}

TEST_F(LjTail, ShiftWithTailIsRefused) {
    expect_rejected(lj_config(3, 7.0, one_species, "shift = true\ntail = true\n"),
                    {"shift and tail together", "lj"});
}
