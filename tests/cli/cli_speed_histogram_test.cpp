// speed_histogram.csv against the equilibrium speed distribution, through the command
// line: an elastic event-driven gas started with all speeds equal is sampled at many log
// rows after it has relaxed ([output] histogram_start), and the histogram's counts are
// compared by a chi-square test with the Rayleigh (2D) / Maxwell (3D) distribution
//   2D: p(v) = (m v / T) exp(-m v^2 / 2T)
//   3D: p(v) = 4 pi v^2 (m / 2 pi T)^(3/2) exp(-m v^2 / 2T)
// computed here (bin probabilities by Simpson's rule on p, not the code's CDF), at the
// width T = <m v^2> / d of the sampled speeds taken from log.csv's kinetic_energy
// columns (docs/formats.md: the width is T (1 - m / M) at fixed total momentum, which is
// what one particle's speed follows).
//
// Counts. docs/formats.md: density = count / (samples_total w), samples_total = N_s x
// (log rows with t >= histogram_start). The test rebuilds the counts from the density
// column (they must come out as integers) and puts the speeds beyond the last bin,
// samples_total - sum of counts, in an overflow cell, so the densities' normalisation is
// tested too.
//
// Tolerance. The cells are the bins (the last ones with fewer than 20 expected counts
// merged with the overflow), so chi-square has at most cells - 1 degrees of freedom (one
// fewer still for T, taken from the same speeds; using cells - 1 is conservative). The
// samples are log_interval apart, about 5 mean free times (the runs print 0.65 in 2D,
// 0.49 in 3D), so a particle has collided ~5 times between samples and its speeds are
// close to independent; energy conservation only anticorrelates the speeds of one
// sample, which lowers chi-square. Checked while writing the test: over 20 seeds of the
// 2D run the mean of chi2 / dof was 1.04 +- 0.06, over 15 seeds x 2 species of the 3D
// run 1.03 +- 0.04, so the samples count as independent. The bound is the chi-square
// quantile at p = 1e-5 (Wilson-Hilferty). The O(1/N) difference between the
// fixed-energy one-particle distribution and the Maxwellian changes chi-square by < 1
// here. The test has power: it asserts that the same bound rejects the theory at a
// temperature 3% off (chi2 ~ 360 in 2D; 1.5% off already fails both runs).
#include "cli/cli_support.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <functional>
#include <numbers>
#include <string>
#include <vector>

namespace pedesis::test {
namespace {

// the equilibrium speed density of one particle of mass m at width T, in d dimensions
double speed_pdf(int d, double v, double T, double m) {
    const double a = m / T;
    if (d == 2) return a * v * std::exp(-0.5 * a * v * v);
    return 4.0 * std::numbers::pi * v * v * std::pow(a / (2.0 * std::numbers::pi), 1.5) *
           std::exp(-0.5 * a * v * v);
}

// integral of f over [lo, hi], Simpson's rule on 64 intervals (error ~1e-12 for these
// bins, far below one count in 1e5)
double simpson(const std::function<double(double)>& f, double lo, double hi) {
    const int n = 64;
    const double h = (hi - lo) / n;
    double s = f(lo) + f(hi);
    for (int k = 1; k < n; ++k) s += (k % 2 ? 4.0 : 2.0) * f(lo + k * h);
    return s * h / 3.0;
}

// Upper quantile of chi-square with k degrees of freedom at standard-normal z
// (Wilson-Hilferty; within 1% of the exact quantile for k >= 20).
double chi2_quantile(double k, double z) {
    const double c = 2.0 / (9.0 * k);
    return k * std::pow(1.0 - c + z * std::sqrt(c), 3.0);
}
constexpr double z_1e5 = 4.265; // P(Z > z) = 1e-5

struct SpeciesRun {
    std::string name;
    double mass = 1.0;
    std::size_t count = 0;
};

class SpeedHistogramTheory : public ScratchDir {
  protected:
    // Runs `config`, then checks each species' histogram against theory.
    void run_and_check(const std::string& config, int d, double histogram_start, std::size_t bins,
                       const std::vector<SpeciesRun>& species) {
        write("gas.toml", config);
        const CliResult r = run_pedesis("run gas.toml --out out", dir, 120);
        ASSERT_EQ(r.exit_code, 0) << r.output;
        const CsvColumns log = csv_columns(read("out/log.csv"));
        const CsvColumns hist = csv_columns(read("out/speed_histogram.csv"));
        ASSERT_EQ(hist.names, (std::vector<std::string>{"species", "v_lo", "v_hi", "density",
                                                        "theory", "temperature"}));
        const std::vector<double> time = log.numbers("time");
        std::vector<std::size_t> sampled; // the log rows the histogram samples
        for (std::size_t k = 0; k < time.size(); ++k)
            if (time[k] >= histogram_start) sampled.push_back(k);
        ASSERT_GE(sampled.size(), 100u);
        for (const auto& s : species)
            check_species(log, hist, sampled, d, bins, s, species.size() > 1);
    }

    void check_species(const CsvColumns& log, const CsvColumns& hist,
                       const std::vector<std::size_t>& sampled, int d, std::size_t bins,
                       const SpeciesRun& s, bool species_fluctuates) {
        SCOPED_TRACE("species " + s.name);
        // the width <m v^2> / d of the sampled speeds: at every sampled row the species'
        // sum of m v^2 is 2 K_s (log.csv's kinetic_energy_<name>, lab frame)
        const std::vector<double> K = log.numbers("kinetic_energy_" + s.name);
        double T = 0.0;
        for (std::size_t k : sampled) T += 2.0 * K[k] / (d * static_cast<double>(s.count));
        T /= static_cast<double>(sampled.size());
        const double total = static_cast<double>(s.count * sampled.size());

        std::vector<double> lo, hi, density, theory, temperature;
        const auto& names = hist.cells.at("species");
        const auto col = [&](const char* c) { return hist.numbers(c); };
        const auto all_lo = col("v_lo"), all_hi = col("v_hi"), all_density = col("density"),
                   all_theory = col("theory"), all_temperature = col("temperature");
        for (std::size_t k = 0; k < names.size(); ++k) {
            if (names[k] != s.name) continue;
            lo.push_back(all_lo[k]);
            hi.push_back(all_hi[k]);
            density.push_back(all_density[k]);
            theory.push_back(all_theory[k]);
            temperature.push_back(all_temperature[k]);
        }
        ASSERT_EQ(lo.size(), bins);
        const double w = hi[0] - lo[0];
        const double v_max = hi.back();
        EXPECT_NEAR(v_max, static_cast<double>(bins) * w, 1e-8 * v_max);
        // docs: v_max >= 4.5 sqrt(<v^2> / d) of the first sample, which is T / m up to the
        // relative fluctuation sqrt(2 / (d N_s)) of K_s between samples (0 for one
        // species in a periodic box); allow 5 of those
        const double spread =
            species_fluctuates ? 5.0 * std::sqrt(2.0 / (d * static_cast<double>(s.count))) : 0.0;
        EXPECT_GE(v_max, 4.5 * std::sqrt(T / s.mass) * (1.0 - spread - 1e-9));

        std::vector<double> observed, expected;
        double counted = 0.0, p_inside = 0.0;
        for (std::size_t k = 0; k < bins; ++k) {
            EXPECT_NEAR(lo[k], static_cast<double>(k) * w, 1e-8 * v_max) << "bin " << k;
            EXPECT_NEAR(hi[k] - lo[k], w, 1e-8 * v_max) << "bin " << k;
            const double c = density[k] * total * w;
            ASSERT_NEAR(c, std::round(c), 1e-3) << "bin " << k << ": not a whole count";
            counted += std::round(c);
            const double p =
                simpson([&](double v) { return speed_pdf(d, v, T, s.mass); }, lo[k], hi[k]);
            p_inside += p;
            observed.push_back(std::round(c));
            expected.push_back(total * p);
            // the code's theory column is the same bin average (10 significant digits)
            EXPECT_NEAR(theory[k], p / w, 1e-8 * std::max(1.0, p / w)) << "bin " << k;
            EXPECT_NEAR(temperature[k], T, 1e-8 * T) << "bin " << k;
        }
        ASSERT_LE(counted, total);

        // chi-square against the theory at width t: the bins, the last ones merged with
        // the overflow until the merged cell expects >= 20
        const auto chi2_at = [&](double t, std::size_t& cells) {
            std::vector<double> e(bins);
            double inside = 0.0;
            for (std::size_t k = 0; k < bins; ++k) {
                e[k] = total *
                       simpson([&](double v) { return speed_pdf(d, v, t, s.mass); }, lo[k], hi[k]);
                inside += e[k];
            }
            std::size_t keep = bins;
            double tail_o = total - counted, tail_e = total - inside;
            while (keep > 0 && (e[keep - 1] < 20.0 || tail_e < 20.0)) {
                --keep;
                tail_o += observed[keep];
                tail_e += e[keep];
            }
            double chi2 = (tail_o - tail_e) * (tail_o - tail_e) / tail_e;
            for (std::size_t k = 0; k < keep; ++k)
                chi2 += (observed[k] - e[k]) * (observed[k] - e[k]) / e[k];
            cells = keep + 1;
            return chi2;
        };
        std::size_t cells = 0;
        const double chi2 = chi2_at(T, cells);
        ASSERT_GE(cells, 20u);
        const double bound = chi2_quantile(static_cast<double>(cells - 1), z_1e5);
        std::printf("%s: %.0f speeds in %zu samples, T = %.6g, %zu cells, chi2 = %.1f "
                    "(bound %.1f at p = 1e-5), %.0f beyond v_max = %.4g (expected %.1f)\n",
                    s.name.c_str(), total, sampled.size(), T, cells, chi2, bound, total - counted,
                    v_max, total * (1.0 - p_inside));
        EXPECT_LT(chi2, bound) << "the speed histogram does not follow the "
                               << (d == 2 ? "Rayleigh" : "Maxwell") << " distribution";
        // power: a temperature 3% off must be rejected by the same bound
        std::size_t cells_off = 0;
        EXPECT_GT(chi2_at(1.03 * T, cells_off), bound);
    }
};

TEST_F(SpeedHistogramTheory, ElasticDisksFollowRayleigh2D) {
    // 1000 disks of mass 2 (not 1, so that a lost mass would show), packing fraction 0.22,
    // all with speed 1.5 at t = 0: width T = m v^2 / 2 = 2.25. Sampled from t = 20 (~30
    // collisions per particle, well relaxed) every 3 time units (4.6 mean free times):
    // 401 samples, 401000 speeds. ~1.5 s.
    run_and_check(R"(dimension = 2
seed = 11
[box]
length = 60.0
[[species]]
name = "disk"
count = 1000
radius = 0.5
mass = 2.0
[initial]
positions = "random"
velocities = "equal_speed"
speed = 1.5
[run]
time = 1220.0
[output]
log_interval = 3.0
histogram_start = 20.0
histogram_bins = 40
formats = []
progress = false
)",
                  2, 20.0, 40, {{"disk", 2.0, 1000}});
}

TEST_F(SpeedHistogramTheory, ElasticMixtureFollowsMaxwell3D) {
    // 400 + 400 spheres of mass 1 and 3, packing fraction 0.15, all with speed 1 at t = 0
    // (so the heavy species starts 3x hotter and must share its energy). Each species'
    // histogram follows the Maxwellian of its own mass at its own width. Sampled from
    // t = 10 (~20 collisions per particle) every 2.5 time units (5 mean free times): 401
    // samples, 160400 speeds per species. ~2.5 s.
    run_and_check(R"(dimension = 3
seed = 5
[box]
length = 14.0
[[species]]
name = "light"
count = 400
radius = 0.5
mass = 1.0
[[species]]
name = "heavy"
count = 400
radius = 0.5
mass = 3.0
[initial]
positions = "random"
velocities = "equal_speed"
speed = 1.0
[run]
time = 1010.0
[output]
log_interval = 2.5
histogram_start = 10.0
histogram_bins = 40
formats = []
progress = false
)",
                  3, 10.0, 40, {{"light", 1.0, 400}, {"heavy", 3.0, 400}});
}

} // namespace
} // namespace pedesis::test
