// The soft engine's log.csv against exact results, through the command line: small
// non-interacting systems run by `pedesis run`, their log read back by column name.
//
//  * free overdamped Brownian particles (a 2D mixture with per-species T and gamma, and
//    3D): msd = 2 d D t with D = T / gamma, pressure_ideal = n T, no virial or active
//    pressure, no potential energy;
//  * free active Brownian particles in 2D (self_propulsion alpha, brownian T = 0,
//    brownian_rotation T_r, gamma_r): msd = 2 v0^2 tau^2 (t / tau - 1 + e^(-t / tau)),
//    v0 = alpha / gamma, tau = 1 / D_r = gamma_r / T_r, and the swim pressure
//    pressure_active = n alpha v0 tau (1 - e^(-t / tau)) / d (docs/engines.md);
//  * free Langevin particles in 3D (a mixture of masses and frictions, started at rest):
//    temperature relaxes as T (1 - e^(-2 gamma t / m)) per species and averages to the
//    thermostat's T; msd follows the Ornstein-Uhlenbeck result; the energy and pressure
//    columns agree with the temperature.
//
// Every noise is drawn from the seed, so each run is deterministic; the tolerances are
// 5 standard deviations of the estimator (derived at each check) plus, where the time
// step changes the expectation, the exact difference between the time-discrete and the
// continuous result, computed here. Every row is checked, each at 5 sigma (at most 81
// rows per quantity: a false alarm below 1e-4 even if they were independent).
#include "cli/cli_support.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <initializer_list>
#include <string>
#include <vector>

namespace pedesis::test {
namespace {

class SoftLogTheory : public ScratchDir {
  protected:
    // Runs `config` and returns its log.csv by column.
    CsvColumns run_log(const std::string& config) {
        write("soft.toml", config);
        const CliResult r = run_pedesis("run soft.toml --out out", dir, 120);
        EXPECT_EQ(r.exit_code, 0) << r.output;
        return csv_columns(read("out/log.csv"));
    }
};

bool has_column(const CsvColumns& log, const std::string& name) {
    return std::find(log.names.begin(), log.names.end(), name) != log.names.end();
}

// Columns that these runs (no pair forces; no self-propulsion or no noise) must log as
// exactly 0 in every row.
void expect_zero_columns(const CsvColumns& log, std::initializer_list<const char*> names) {
    for (const char* name : names) {
        const auto v = log.numbers(name);
        for (std::size_t k = 0; k < v.size(); ++k) EXPECT_EQ(v[k], 0.0) << name << " row " << k;
    }
}

// time = step x dt in every row
void expect_time_is_step_dt(const CsvColumns& log, double dt) {
    const auto step = log.numbers("step"), time = log.numbers("time");
    for (std::size_t k = 0; k < step.size(); ++k)
        EXPECT_NEAR(time[k], step[k] * dt, 1e-9 * (1.0 + time[k])) << "row " << k;
}

struct BrownianSpecies {
    double count, T, gamma;
};

// Free overdamped particles: each displacement component is Gaussian with variance
// 2 D t (Euler-Maruyama is exact without forces), so |dr|^2 = 2 D t chi2_d: mean
// 2 d D t, variance 8 d D^2 t^2. The msd column is the mean over all N particles.
void check_free_brownian(const CsvColumns& log, int d, double volume,
                         const std::vector<BrownianSpecies>& species) {
    double n_total = 0.0, nT = 0.0;
    for (const auto& s : species) {
        n_total += s.count;
        nT += s.count * s.T;
    }
    const auto time = log.numbers("time"), msd = log.numbers("msd");
    const auto p_ideal = log.numbers("pressure_ideal"), p = log.numbers("pressure");
    ASSERT_GE(time.size(), 10u);
    for (std::size_t k = 0; k < time.size(); ++k) {
        const double t = time[k];
        double mean = 0.0, var = 0.0;
        for (const auto& s : species) {
            const double D = s.T / s.gamma;
            mean += s.count * 2.0 * d * D * t;
            var += s.count * 8.0 * d * D * D * t * t;
        }
        mean /= n_total;
        const double sigma = std::sqrt(var) / n_total;
        EXPECT_NEAR(msd[k], mean, 5.0 * sigma + 1e-12) << "row " << k << ", t = " << t;
        // pressure_ideal = sum_i T_i / V (docs/formats.md), exact
        EXPECT_NEAR(p_ideal[k], nT / volume, 1e-9 * nT / volume) << "row " << k;
        EXPECT_NEAR(p[k], p_ideal[k], 1e-9 * p_ideal[k]) << "row " << k;
    }
    std::printf("t = %g: msd %.6g, theory %.6g\n", time.back(), msd.back(), [&] {
        double m = 0.0;
        for (const auto& s : species) m += s.count * 2.0 * d * s.T / s.gamma;
        return m * time.back() / n_total;
    }());
    // overdamped runs have no velocities of their own: no temperature columns
    EXPECT_FALSE(has_column(log, "temperature"));
    EXPECT_FALSE(has_column(log, "kinetic_energy"));
}

TEST_F(SoftLogTheory, FreeBrownianMixtureMsdAndIdealPressure2D) {
    // A: D = 0.5 / 2 = 0.25, B: D = 0.6 / 0.8 = 0.75, so msd = (12000 x 4 x 0.25 +
    // 8000 x 4 x 0.75) t / 20000 = 1.8 t (wrong per-species values, or T instead of
    // T / gamma, are off by > 20%; the tolerance at t = 5 is 4%). The rms displacement
    // of B at t = 5 is 3.9 in a box of 40, so about a third of the particles cross a
    // periodic face: the msd uses the unwrapped positions. skin 1: the largest step,
    // sqrt(2 D dt) = 0.087 per component, stays far below it. ~1.5 s.
    const auto log = run_log(R"(dimension = 2
dynamics = "brownian"
seed = 4
[box]
length = 40.0
[[species]]
name = "A"
count = 12000
radius = 0.5
[[species]]
name = "B"
count = 8000
radius = 0.5
[neighbor_list]
skin = 1.0
[[integrator]]
name = "brownian"
T = { A = 0.5, B = 0.6 }
gamma = { A = 2.0, B = 0.8 }
[run]
steps = 1000
dt = 0.005
[output]
log_every = 100
formats = []
progress = false
)");
    ASSERT_FALSE(HasFailure());
    expect_time_is_step_dt(log, 0.005);
    expect_zero_columns(log, {"potential_energy", "pressure_virial", "pressure_active"});
    check_free_brownian(log, 2, 40.0 * 40.0, {{12000, 0.5, 2.0}, {8000, 0.6, 0.8}});
}

TEST_F(SoftLogTheory, FreeBrownianMsdAndIdealPressure3D) {
    // D = 0.8 / 1.6 = 0.5: msd = 6 D t = 3 t, 15 at t = 5 (rms 3.9 in a box of 20); the
    // relative standard deviation of the msd is sqrt(2 / (3 N)) = 0.8%. ~1 s.
    const auto log = run_log(R"(dimension = 3
dynamics = "brownian"
seed = 12
[box]
length = 20.0
[[species]]
name = "A"
count = 10000
radius = 0.5
[neighbor_list]
skin = 1.0
[[integrator]]
name = "brownian"
T = 0.8
gamma = 1.6
[run]
steps = 1000
dt = 0.005
[output]
log_every = 100
formats = []
progress = false
)");
    ASSERT_FALSE(HasFailure());
    expect_time_is_step_dt(log, 0.005);
    expect_zero_columns(log, {"potential_energy", "pressure_virial", "pressure_active"});
    check_free_brownian(log, 3, 20.0 * 20.0 * 20.0, {{10000, 0.8, 1.6}});
}

TEST_F(SoftLogTheory, FreeActiveBrownianMsdAndSwimPressure2D) {
    // v0 = alpha / gamma = 3 / 1.5 = 2, D_r = 0.5 / 0.25 = 2, tau = 1 / D_r = 0.5 (2D);
    // no translational noise. Run to 5 tau, a row every tau / 4. ~1 s.
    const double N = 50000, L = 100.0, alpha = 3.0, v0 = 2.0, Dr = 2.0, tau = 1.0 / Dr;
    const double dt = 0.005, d = 2.0, volume = L * L;
    const auto log = run_log(R"(dimension = 2
dynamics = "brownian"
seed = 8
[box]
length = 100.0
[[species]]
name = "A"
count = 50000
radius = 0.5
[[force]]
name = "self_propulsion"
alpha = 3.0
[[integrator]]
name = "brownian"
T = 0.0
gamma = 1.5
[[integrator]]
name = "brownian_rotation"
T = 0.5
gamma = 0.25
[run]
steps = 500
dt = 0.005
[output]
log_every = 25
formats = []
progress = false
)");
    ASSERT_FALSE(HasFailure());
    expect_time_is_step_dt(log, dt);
    expect_zero_columns(log, {"potential_energy", "pressure_virial", "pressure_ideal"});
    const auto step = log.numbers("step"), time = log.numbers("time"), msd = log.numbers("msd");
    const auto p_active = log.numbers("pressure_active"), p = log.numbers("pressure");
    const auto order = log.numbers("polar_order");
    ASSERT_EQ(time.size(), 21u);
    // Time-discrete expectations: the step moves r by dt v0 n_k with the director of the
    // step's start, and the 2D rotation is exact, <n_j . n_k> = q^|j-k|, q = e^(-D_r dt).
    // After k steps, msd = v0^2 dt^2 sum_{i,j<k} q^|i-j| and
    // <n_k . dr_k> = v0 dt sum_{j<k} q^(k-j). They differ from the continuous results by
    // O(D_r dt): the difference, checked to be below 1% (it is 0.5% for the swim
    // pressure, 1e-5 for the msd), is added to the tolerance.
    const double q = std::exp(-Dr * dt);
    for (std::size_t r = 0; r < time.size(); ++r) {
        const double t = time[r];
        const auto k = static_cast<long>(std::lround(step[r]));
        double pairs = static_cast<double>(k), ndr = 0.0;
        for (long l = 1; l < k; ++l) pairs += 2.0 * static_cast<double>(k - l) * std::pow(q, l);
        for (long l = 1; l <= k; ++l) ndr += std::pow(q, l);
        const double msd_discrete = v0 * v0 * dt * dt * pairs;
        const double ndr_discrete = v0 * dt * ndr;
        const double msd_theory = 2.0 * v0 * v0 * tau * tau * (t / tau - 1.0 + std::exp(-t / tau));
        const double ndr_theory = v0 * tau * (1.0 - std::exp(-t / tau));
        const double msd_dt_effect = std::abs(msd_discrete - msd_theory);
        const double ndr_dt_effect = std::abs(ndr_discrete - ndr_theory);
        EXPECT_LE(msd_dt_effect, 0.01 * msd_theory + 1e-12) << "row " << r;
        EXPECT_LE(ndr_dt_effect, 0.01 * ndr_theory + 1e-12) << "row " << r;
        // msd: with T = 0 every |dr| <= v0 t, so Var|dr|^2 <= E|dr|^4 - msd^2
        // <= msd (v0^2 t^2 - msd): a bound, whatever the distribution
        const double msd_sigma =
            std::sqrt(std::max(0.0, msd_theory * (v0 * v0 * t * t - msd_theory)) / N);
        EXPECT_NEAR(msd[r], msd_theory, 5.0 * msd_sigma + msd_dt_effect + 1e-12)
            << "row " << r << ", t = " << t;
        // swim pressure sum_i alpha n_i . (dr_i - dR) / (d V): (n . dr)^2 <= |dr|^2, so
        // each term's variance is at most alpha^2 msd; subtracting the mean displacement
        // dR changes the sum by alpha (sum n_i) . dR, O(1 / N) of it
        const double p_theory = N * alpha * ndr_theory / (d * volume);
        const double p_sigma = alpha * std::sqrt(N * msd_theory) / (d * volume);
        EXPECT_NEAR(p_active[r], p_theory,
                    5.0 * p_sigma + N * alpha * ndr_dt_effect / (d * volume) + 1e-12)
            << "row " << r << ", t = " << t;
        // T = 0 and no pair forces: the pressure is the swim pressure alone
        EXPECT_NEAR(p[r], p_active[r], 1e-9 * std::abs(p_active[r]) + 1e-15) << "row " << r;
        // random, independent directors: N P^2 is exponentially distributed with mean 1,
        // so P < 5 / sqrt(N) but for a chance of e^-25
        EXPECT_LT(order[r], 5.0 / std::sqrt(N)) << "row " << r;
    }
    std::printf("t = %g: msd %.6g (theory %.6g), swim pressure %.6g (steady state %.6g)\n",
                time.back(), msd.back(),
                2.0 * v0 * v0 * tau * tau *
                    (time.back() / tau - 1.0 + std::exp(-time.back() / tau)),
                p_active.back(), N * alpha * v0 * tau / (d * volume));
}

// Free Langevin particle of mass m, friction gamma, started at rest: per component
// <v^2>(t) = (T / m)(1 - e^(-2 t / tau_v)), tau_v = m / gamma, and the Ornstein-Uhlenbeck
// displacement variance 2 D [t - 2 tau_v (1 - e^(-t / tau_v)) + tau_v / 2 (1 - e^(-2 t /
// tau_v))], D = T / gamma.
double ou_msd_per_component(double t, double T, double gamma, double m) {
    const double tau = m / gamma, D = T / gamma;
    return 2.0 * D *
           (t - 2.0 * tau * (-std::expm1(-t / tau)) + 0.5 * tau * (-std::expm1(-2.0 * t / tau)));
}

// The same for BAOAB with step dt and no forces, exactly: the O step
// v <- c v + s xi (c = e^(-gamma dt / m), s^2 = (1 - c^2) T / m) once a step, positions
// moved by dt (v_k + v_{k+1}) / 2. With X_n = sum_{k=1..n} v_k, dr_n = dt (X_n - v_n / 2);
// the second moments of (X, v) follow a recursion. Returns the msd per component at
// each step 0..n.
std::vector<double> baoab_msd_per_component(std::size_t n, double dt, double T, double gamma,
                                            double m) {
    const double c = std::exp(-gamma * dt / m), s2 = -std::expm1(-2.0 * gamma * dt / m) * T / m;
    double vv = 0.0, xv = 0.0, xx = 0.0;
    std::vector<double> out(n + 1, 0.0);
    for (std::size_t k = 1; k <= n; ++k) {
        const double xv_prev = xv;
        vv = c * c * vv + s2;             // E v_k^2
        xv = c * xv_prev + vv;            // E X_k v_k = E (X_{k-1} + v_k) v_k
        xx = xx + 2.0 * c * xv_prev + vv; // E X_k^2
        out[k] = dt * dt * (xx - xv + 0.25 * vv);
    }
    return out;
}

TEST_F(SoftLogTheory, FreeLangevinMixtureThermalizes3D) {
    // A: m = 1, gamma = 2 (tau_v = 0.5); B: m = 2, gamma = 1 (tau_v = 2); T = 1.5; 4000
    // of each, started at rest. dt = 0.02: without forces the O step is exact, so the
    // velocities follow T (1 - e^(-2 t / tau_v)) at any dt. A row every 0.5 to t = 40.
    // ~2 s.
    const double T = 1.5, dt = 0.02, d = 3.0, L = 30.0, volume = L * L * L;
    struct Sp {
        double count, m, gamma;
    };
    const std::vector<Sp> species{{4000, 1.0, 2.0}, {4000, 2.0, 1.0}};
    const double N = 8000;
    const auto log = run_log(R"(dimension = 3
dynamics = "langevin"
seed = 6
[box]
length = 30.0
[[species]]
name = "A"
count = 4000
radius = 0.5
mass = 1.0
[[species]]
name = "B"
count = 4000
radius = 0.5
mass = 2.0
[[integrator]]
name = "langevin"
T = 1.5
gamma = { A = 2.0, B = 1.0 }
[run]
steps = 2000
dt = 0.02
[output]
log_every = 25
formats = []
progress = false
)");
    ASSERT_FALSE(HasFailure());
    expect_time_is_step_dt(log, dt);
    expect_zero_columns(log, {"potential_energy", "pressure_virial", "pressure_active"});
    const auto step = log.numbers("step"), time = log.numbers("time");
    const auto temp = log.numbers("temperature"), K = log.numbers("kinetic_energy");
    const auto E = log.numbers("total_energy"), msd = log.numbers("msd");
    const auto p = log.numbers("pressure"), p_ideal = log.numbers("pressure_ideal");
    ASSERT_EQ(time.size(), 81u);
    std::vector<std::vector<double>> discrete;
    for (const auto& s : species)
        discrete.push_back(baoab_msd_per_component(2000, dt, T, s.gamma, s.m));

    double sum_T = 0.0, var_sum = 0.0, max_dt_effect = 0.0;
    std::size_t rows = 0;
    for (std::size_t r = 0; r < time.size(); ++r) {
        const double t = time[r];
        const auto k = static_cast<std::size_t>(std::lround(step[r]));
        // temperature = 2 K / (d N) (langevin: f = d N); per species the mean of m v^2 is
        // d T_s(t), each of the d N_s components m v_a^2 = T_s chi2_1 (variance 2 T_s^2)
        double T_theory = 0.0, T_var = 0.0, msd_theory = 0.0, msd_discrete = 0.0, msd_var = 0.0;
        for (std::size_t i = 0; i < species.size(); ++i) {
            const auto& s = species[i];
            const double Ts = -T * std::expm1(-2.0 * t * s.gamma / s.m);
            T_theory += s.count * Ts / N;
            T_var += s.count * d * 2.0 * Ts * Ts / (d * N * d * N);
            // displacements are Gaussian: |dr|^2 = sigma^2 chi2_d, variance 2 d sigma^4
            const double m1 = ou_msd_per_component(t, T, s.gamma, s.m);
            msd_theory += s.count * d * m1 / N;
            msd_discrete += s.count * d * discrete[i][k] / N;
            msd_var += s.count * 2.0 * d * m1 * m1 / (N * N);
        }
        EXPECT_NEAR(temp[r], T_theory, 5.0 * std::sqrt(T_var) + 1e-12)
            << "row " << r << ", t = " << t;
        // the time step's effect on the msd, exact for BAOAB without forces: O(dt^2),
        // checked to be below 1% and added to the tolerance
        const double dt_effect = std::abs(msd_discrete - msd_theory);
        EXPECT_LE(dt_effect, 0.01 * msd_theory + 1e-12) << "row " << r;
        max_dt_effect = std::max(max_dt_effect, dt_effect / std::max(msd_theory, 1e-300));
        EXPECT_NEAR(msd[r], msd_theory, 5.0 * std::sqrt(msd_var) + dt_effect + 1e-12)
            << "row " << r << ", t = " << t;
        // the columns agree with each other: K = d N T / 2, no potential energy, and the
        // ideal pressure 2 K / (d V) is the whole pressure
        EXPECT_NEAR(K[r], d * N * temp[r] / 2.0, 1e-8 * K[r] + 1e-12) << "row " << r;
        EXPECT_NEAR(E[r], K[r], 1e-9 * K[r] + 1e-12) << "row " << r;
        EXPECT_NEAR(p_ideal[r], 2.0 * K[r] / (d * volume), 1e-8 * p_ideal[r] + 1e-15)
            << "row " << r;
        EXPECT_NEAR(p[r], p_ideal[r], 1e-9 * p_ideal[r] + 1e-15) << "row " << r;
        if (t >= 20.0) { // 10 tau_v of the slower species: equilibrium to e^-20
            sum_T += temp[r];
            var_sum += T_var;
            ++rows;
        }
    }
    // The mean over the equilibrium rows equals T. Rows 0.5 apart are correlated: m v^2
    // of one species decorrelates as rho = e^(-2 dt_row / tau_v) (0.14 for A, 0.61 for
    // B); the variance of the mean of an AR(1) series is at most (1 + rho) / (1 - rho)
    // times that of independent rows (1.31 and 4.08), applied to each species' half of
    // the variance.
    const double n_rows = static_cast<double>(rows);
    const double var_row = var_sum / n_rows; // equal for both species at equilibrium
    const double inflate =
        0.5 * (1.0 + std::exp(-2.0 * 0.5 / 0.5)) / (1.0 - std::exp(-2.0 * 0.5 / 0.5)) +
        0.5 * (1.0 + std::exp(-2.0 * 0.5 / 2.0)) / (1.0 - std::exp(-2.0 * 0.5 / 2.0));
    const double sigma_mean = std::sqrt(var_row * inflate / n_rows);
    const double mean_T = sum_T / n_rows;
    std::printf("mean temperature over %zu rows: %.6g (thermostat %g, 5 sigma = %.3g); "
                "largest time-step effect on the msd %.2g\n",
                rows, mean_T, T, 5.0 * sigma_mean, max_dt_effect);
    EXPECT_NEAR(mean_T, T, 5.0 * sigma_mean);
}

} // namespace
} // namespace pedesis::test
