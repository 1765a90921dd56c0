// Transport coefficients from sampled running sums, against exact results: the fit and the
// block statistics on numbers worked by hand; a Gaussian random walk (D = step variance /
// (2 interval)); an Ornstein-Uhlenbeck flux x with <x(0) x(t)> = sigma^2 e^(-t/tau) sampled
// exactly (an AR(1) series), whose running integral has the Einstein coefficient
// (h sigma^2 / 2) coth(h / (2 tau)) -> sigma^2 tau, the same as the trapezoid Green-Kubo
// integral of its sampled correlation; a drift that drift removal must not see; the block
// error against the scatter of independent repeats; exact continuation through save/load.
// Statistical tolerances are stated where they are used, at about four standard errors of
// these seeds' runs, so that each check is deterministic and still fails on a factor or a
// missing term.
#include "pedesis/core/error.hpp"
#include "pedesis/observe/transport_fit.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <cstring>
#include <random>
#include <sstream>
#include <string>
#include <vector>

using namespace pedesis;

namespace {

MomentCorrelator::Lag lag(double tau, double mean_square, double mean = 0.0) {
    return {tau, mean_square, mean, 1};
}

// Independent Gaussian random walks, one per channel, plus a drift v t common to all.
class RandomWalk {
  public:
    RandomWalk(std::size_t channels, double step_variance, double drift, double interval,
               std::uint64_t seed)
        : rng_(seed), step_(std::sqrt(step_variance)), drift_(drift * interval),
          walk_(channels, 0.0), out_(channels, 0.0) {}

    const double* next() {
        for (std::size_t c = 0; c < walk_.size(); ++c) {
            out_[c] = walk_[c] + drift_ * static_cast<double>(n_);
            walk_[c] += step_ * normal_(rng_);
        }
        ++n_;
        return out_.data();
    }

  private:
    std::mt19937_64 rng_;
    std::normal_distribution<double> normal_;
    double step_, drift_;
    std::vector<double> walk_, out_;
    std::uint64_t n_ = 0;
};

bool same_bits(double a, double b) {
    return std::memcmp(&a, &b, sizeof a) == 0;
}

} // namespace

TEST(TransportFit, WindowIsATenthOfTheBlockDownToAFortieth) {
    const FitWindow w = fit_window(400.0);
    EXPECT_EQ(w.from, 10.0);
    EXPECT_EQ(w.to, 40.0);
    EXPECT_THROW(fit_window(0.0), InputError);
    EXPECT_THROW(fit_window(std::nan("")), InputError);
}

TEST(TransportFit, SlopeIsTheLeastSquaresSlopeOverTheLagsInTheWindow) {
    // inside [2, 8]: y = 3 + 2.5 tau + (-1, +1, -1, +1) at tau = 2, 4, 6, 8 (the boundaries
    // count); least squares: 2.5 + sum (t - 5) e / sum (t - 5)^2 = 2.5 + 4 / 20
    std::vector<MomentCorrelator::Lag> lags = {lag(1.0, 100.0), lag(2.0, 7.0),  lag(4.0, 14.0),
                                               lag(6.0, 17.0),  lag(8.0, 24.0), lag(9.0, -50.0)};
    EXPECT_NEAR(einstein_slope(lags, {2.0, 8.0}, false), 2.7, 1e-12);
    // drift removal fits mean_square - mean^2: a mean of tau adds tau^2 that it takes away
    for (auto& l : lags) {
        l.mean = l.tau;
        l.mean_square += l.tau * l.tau;
    }
    EXPECT_NEAR(einstein_slope(lags, {2.0, 8.0}, true), 2.7, 1e-12);
    EXPECT_GT(einstein_slope(lags, {2.0, 8.0}, false), 12.0);
    // fewer than two lags inside
    EXPECT_TRUE(std::isnan(einstein_slope(lags, {2.5, 3.5}, false)));
    EXPECT_TRUE(std::isnan(einstein_slope(lags, {3.0, 5.0}, false)));
}

TEST(TransportFit, BlockEstimateIsTheMeanAndItsStandardError) {
    const Estimate e = block_estimate({1.0, 2.0, 3.0, 4.0});
    EXPECT_EQ(e.value, 2.5);
    // sample variance 5/3, over 4 blocks
    EXPECT_NEAR(e.error, std::sqrt(5.0 / 3.0 / 4.0), 1e-15);
    EXPECT_EQ(e.blocks, 4u);
    const Estimate one = block_estimate({7.0});
    EXPECT_EQ(one.value, 7.0);
    EXPECT_TRUE(std::isnan(one.error));
    EXPECT_TRUE(std::isnan(block_estimate({}).value));
}

TEST(TransportFit, RunningIntegralIsTheTrapezoidRuleFromZero) {
    const std::vector<AutoCorrelator::Lag> lags = {{0.0, 1.0, 9}, {1.0, 3.0, 8}, {3.0, 7.0, 6}};
    const auto I = running_integral(lags);
    ASSERT_EQ(I.size(), 3u);
    EXPECT_EQ(I[0], 0.0);
    EXPECT_EQ(I[1], 2.0);        // (1 + 3) / 2
    EXPECT_EQ(I[2], 2.0 + 10.0); // 2 (3 + 7) / 2
    EXPECT_TRUE(running_integral({}).empty());
}

TEST(EinsteinEstimator, RowsAreTheCentredSlopeOfTheMoment) {
    // G = 0.5 n for every channel: every increment over tau = k h is 0.5 k, so mean_square =
    // (tau / 2h)^2 exactly, and the centred slope between neighbours a, b is
    // (t_a + t_b) / (2h)^2, times scale / 2 in `running`
    const double h = 0.25, scale = 3.0;
    EinsteinEstimator e(2, h, 20 * h, scale, false);
    EinsteinEstimator removed(2, h, 20 * h, scale, true);
    for (int n = 0; n < 600; ++n) {
        const double g[2] = {0.5 * n, 0.5 * n};
        e.add(g);
        removed.add(g);
    }
    const auto rows = e.rows();
    ASSERT_GT(rows.size(), 20u);
    const double v2 = (0.5 / h) * (0.5 / h); // (increment per unit time)^2
    for (std::size_t i = 0; i < rows.size(); ++i) {
        EXPECT_NEAR(rows[i].mean_square, v2 * rows[i].tau * rows[i].tau,
                    1e-12 * rows[i].mean_square);
        const std::size_t a = i == 0 ? 0 : i - 1, b = i + 1 == rows.size() ? i : i + 1;
        const double want = scale * v2 * (rows[a].tau + rows[b].tau) / 2.0;
        EXPECT_NEAR(rows[i].running, want, 1e-10 * want) << i;
    }
    // with drift removal nothing is left of a pure drift
    for (const auto& r : removed.rows()) {
        EXPECT_NEAR(r.mean_square, 0.0, 1e-10 * v2 * r.tau * r.tau);
        EXPECT_NEAR(r.running, 0.0, 1e-9 * v2 * r.tau);
    }
}

TEST(EinsteinEstimator, RandomWalkGivesTheStepVarianceOverTwoIntervals) {
    // D = 0.3 / (2 x 0.5) = 0.3; 192 channels (64 particles in 3D), 40 blocks of 400 steps.
    // The block standard error here is about 0.4 %; tolerance 2 %.
    const double h = 0.5, D = 0.3;
    const std::size_t channels = 192;
    RandomWalk walk(channels, 2.0 * D * h, 0.0, h, 101);
    EinsteinEstimator e(channels, h, 400 * h, 1.0, false);
    for (int n = 0; n <= 40 * 400; ++n) e.add(walk.next());
    const Estimate est = e.estimate();
    EXPECT_EQ(est.blocks, 40u);
    EXPECT_EQ(e.block_values().size(), 40u);
    EXPECT_NEAR(est.value, D, 0.02 * D);
    EXPECT_LT(est.error, 0.01 * D);
    EXPECT_GT(est.error, 0.0);
    EXPECT_NEAR(est.value, D, 4.0 * est.error);
    // the window is the documented rule's; the running slope stays at D inside it
    EXPECT_EQ(e.window().from, 5.0);
    EXPECT_EQ(e.window().to, 20.0);
    for (const auto& r : e.rows()) {
        if (r.tau < e.window().from || r.tau > e.window().to) continue;
        EXPECT_NEAR(r.running, D, 0.05 * D) << r.tau;
    }
}

TEST(EinsteinEstimator, FewerThanTwoBlocksFallBackToTheWholeRun) {
    const double h = 0.5, D = 0.3;
    RandomWalk walk(192, 2.0 * D * h, 0.0, h, 102);
    EinsteinEstimator e(192, h, 400 * h, 1.0, false);
    for (int n = 0; n < 600; ++n) e.add(walk.next());
    const Estimate est = e.estimate();
    EXPECT_EQ(est.blocks, 1u);
    EXPECT_TRUE(std::isnan(est.error));
    EXPECT_NEAR(est.value, D, 0.1 * D); // one block and a half: about 3 % standard error
}

TEST(EinsteinEstimator, BlockErrorMatchesTheScatterOfIndependentRepeats) {
    // 12 repeats; each one's block error estimates the standard deviation of its value.
    // With 12 repeats the scatter is known to about 20 %: the two must agree within a
    // factor of 1.6 (an error missing its 1/sqrt(B), B = 20, would be 4.5 times too big).
    const double h = 0.5, D = 0.3;
    std::vector<double> values;
    double mean_square_error = 0.0;
    for (std::uint64_t seed = 0; seed < 12; ++seed) {
        RandomWalk walk(16, 2.0 * D * h, 0.0, h, 1000 + seed);
        EinsteinEstimator e(16, h, 100 * h, 1.0, false);
        for (int n = 0; n <= 20 * 100; ++n) e.add(walk.next());
        const Estimate est = e.estimate();
        ASSERT_EQ(est.blocks, 20u);
        values.push_back(est.value);
        mean_square_error += est.error * est.error / 12.0;
    }
    const Estimate across = block_estimate(values);
    const double scatter = across.error * std::sqrt(12.0); // sample standard deviation
    const double typical = std::sqrt(mean_square_error);
    EXPECT_GT(scatter / typical, 1.0 / 1.6) << scatter << " " << typical;
    EXPECT_LT(scatter / typical, 1.6) << scatter << " " << typical;
    EXPECT_NEAR(across.value, D, 4.0 * across.error);
}

TEST(EinsteinEstimator, DriftRemovalIgnoresAConstantDrift) {
    const double h = 0.5, D = 0.3;
    RandomWalk plain(3, 2.0 * D * h, 0.0, h, 7), drifting(3, 2.0 * D * h, 5.0, h, 7);
    EinsteinEstimator a(3, h, 100 * h, 1.0, true), b(3, h, 100 * h, 1.0, true),
        raw(3, h, 100 * h, 1.0, false);
    for (int n = 0; n <= 30 * 100; ++n) {
        a.add(plain.next());
        const double* g = drifting.next();
        b.add(g);
        raw.add(g);
    }
    ASSERT_EQ(a.block_values().size(), 30u);
    // the same walks: the drift cancels up to rounding of (5 x 10)^2 against 2 D 10
    for (std::size_t k = 0; k < 30; ++k)
        EXPECT_NEAR(b.block_values()[k], a.block_values()[k], 1e-8) << k;
    EXPECT_NEAR(b.estimate().value, a.estimate().value, 1e-8);
    EXPECT_NEAR(a.estimate().value, D, 4.0 * a.estimate().error);
    // without removal the drift dominates
    EXPECT_GT(raw.estimate().value, 10.0 * D);
}

namespace {

// The Ornstein-Uhlenbeck flux sampled exactly every h: x' = a x + sqrt(1 - a^2) sigma xi,
// a = e^(-h / tau), so <x_0 x_k> = sigma^2 a^k exactly; G = h sum_{i<n} x_i.
class OrnsteinUhlenbeck {
  public:
    OrnsteinUhlenbeck(std::size_t channels, double sigma2, double tau, double h, std::uint64_t seed)
        : rng_(seed), a_(std::exp(-h / tau)), kick_(std::sqrt((1.0 - a_ * a_) * sigma2)), h_(h),
          x_(channels), g_(channels, 0.0) {
        for (double& v : x_) v = std::sqrt(sigma2) * normal_(rng_);
    }
    // Called once per sample: x_n and G_n, then the step to n + 1.
    const double* x() const { return x_.data(); }
    const double* g() const { return g_.data(); }
    void step() {
        for (std::size_t c = 0; c < x_.size(); ++c) {
            g_[c] += h_ * x_[c];
            x_[c] = a_ * x_[c] + kick_ * normal_(rng_);
        }
    }

  private:
    std::mt19937_64 rng_;
    std::normal_distribution<double> normal_;
    double a_, kick_, h_;
    std::vector<double> x_, g_;
};

} // namespace

TEST(EinsteinEstimator, OrnsteinUhlenbeckFluxGivesSigmaSquaredTau) {
    // sigma^2 = 2, tau = 1, h = 0.2: the exact coefficient of the sampled flux is
    // (h sigma^2 / 2) coth(h / 2 tau) = 2.00667 (sigma^2 tau = 2 as h -> 0). 64 channels,
    // 100 blocks of 200 tau: the window [5, 20] starts 5 decay times in (bias below 0.2 %);
    // the block standard error is about 0.8 %; tolerance 3 %, and 4 standard errors of the
    // exact expectation of the estimator (computed below from the exact mean squares).
    const double sigma2 = 2.0, tau = 1.0, h = 0.2;
    const std::size_t channels = 64;
    OrnsteinUhlenbeck ou(channels, sigma2, tau, h, 2024);
    EinsteinEstimator e(channels, h, 200.0, 1.0, false);
    AutoCorrelator ac(channels, h);
    for (int n = 0; n <= 100 * 1000; ++n) {
        e.add(ou.g());
        ac.add(ou.x());
        ou.step();
    }
    const double exact = h * sigma2 / 2.0 / std::tanh(h / (2.0 * tau));
    const Estimate est = e.estimate();
    ASSERT_EQ(est.blocks, 100u);
    EXPECT_NEAR(est.value, exact, 0.03 * exact);
    EXPECT_LT(est.error, 0.015 * exact);

    // The estimator's exact expectation: each lag's mean square is unbiased, so it is the
    // least-squares slope of the exact mean squares
    // <(G_k - G_0)^2> = h^2 sigma^2 (k + 2 sum_{m<k} (k - m) a^m) over the window's lags.
    const double a = std::exp(-h / tau);
    std::vector<MomentCorrelator::Lag> expected;
    for (const auto& l : e.correlator().lags()) {
        if (l.tau > 2.0 * e.window().to) break;
        const auto k = static_cast<long>(std::lround(l.tau / h));
        double s = static_cast<double>(k);
        for (long m = 1; m < k; ++m) s += 2.0 * static_cast<double>(k - m) * std::pow(a, m);
        expected.push_back({l.tau, h * h * sigma2 * s, 0.0, 1});
    }
    const double expectation = einstein_slope(expected, e.window(), false) / 2.0;
    EXPECT_NEAR(expectation, exact, 0.002 * exact);
    EXPECT_NEAR(est.value, expectation, 4.0 * est.error);

    // The autocorrelation: sigma^2 e^(-t / tau) at every lag, short and coarse (block
    // averaging adds at most 7e-4 sigma^2 here; the statistical error is about 1e-3 sigma^2);
    // tolerance 5e-3 sigma^2.
    const auto lags = ac.lags();
    ASSERT_EQ(lags.front().tau, 0.0);
    int coarse = 0;
    for (const auto& l : lags) {
        if (l.tau > 12.0 * tau) break;
        EXPECT_NEAR(l.correlation, sigma2 * std::exp(-l.tau / tau), 5e-3 * sigma2) << l.tau;
        if (l.tau > 16 * h) ++coarse;
    }
    EXPECT_GE(coarse, 15); // 16 .. 30 and 32 .. 60 intervals
    // ... and its running integral levels off at the same coefficient: 2 % between 8 and
    // 12 decay times (statistical error about 0.4 %, the coarse trapezoid's under 0.5 %).
    const auto I = running_integral(lags);
    int plateau = 0;
    for (std::size_t i = 0; i < lags.size(); ++i)
        if (lags[i].tau >= 8.0 * tau && lags[i].tau <= 12.0 * tau) {
            EXPECT_NEAR(I[i], sigma2 * tau, 0.02 * sigma2 * tau) << lags[i].tau;
            ++plateau;
        }
    EXPECT_GT(plateau, 5);
}

TEST(EinsteinEstimator, DriftRemovalOfAFluxWithAMeanIsUnbiased) {
    // The bulk viscosity's case: a flux (the pressure) with a mean of 3 on top of an
    // Ornstein-Uhlenbeck fluctuation, sigma^2 = 1, tau = 1, h = 0.2: the drift-removed
    // coefficient is that of the fluctuation, (h sigma^2 / 2) coth(h / 2 tau) = 1.00333.
    // One channel, 40 blocks of 200 tau; 40 independent repeats (seeds) pool to a standard
    // error near 1 %: tolerance 4 of them. Removing each block's own mean of the
    // increments instead came out near 0.86 (a Brownian bridge over the block).
    const double sigma2 = 1.0, tau = 1.0, h = 0.2, mean = 3.0;
    const double exact = h * sigma2 / 2.0 / std::tanh(h / (2.0 * tau));
    std::vector<double> values;
    for (std::uint64_t seed = 1; seed <= 40; ++seed) {
        OrnsteinUhlenbeck ou(1, sigma2, tau, h, seed);
        EinsteinEstimator e(1, h, 200.0, 1.0, true);
        for (int n = 0; n <= 40 * 1000; ++n) {
            const double g = ou.g()[0] + mean * h * n;
            e.add(&g);
            ou.step();
        }
        EXPECT_NEAR(e.drift(), mean, 0.08); // 5 standard deviations, sqrt(2 sigma^2 tau / T)
        values.push_back(e.estimate().value);
    }
    const Estimate pooled = block_estimate(values);
    EXPECT_NEAR(pooled.value, exact, 4.0 * pooled.error) << pooled.error;
    EXPECT_LT(pooled.error, 0.02 * exact);
}

namespace {

std::string saved(const EinsteinEstimator& e) {
    std::ostringstream out;
    e.save(out);
    return out.str();
}

EinsteinEstimator reloaded(const std::string& bytes) {
    std::istringstream in(bytes);
    return EinsteinEstimator::load(in);
}

} // namespace

TEST(EinsteinEstimator, ContinuesBitForBitAfterSaveAndLoad) {
    const double h = 0.5;
    RandomWalk walk(6, 0.3, 0.2, h, 55);
    std::vector<std::vector<double>> samples;
    for (int n = 0; n < 3000; ++n) {
        const double* g = walk.next();
        samples.emplace_back(g, g + 6);
    }
    // saved empty, on a block boundary and inside a block
    for (std::size_t cut : {std::size_t{0}, std::size_t{401}, std::size_t{1234}}) {
        SCOPED_TRACE("cut at " + std::to_string(cut));
        EinsteinEstimator a(6, h, 200 * h, 0.7, true);
        for (std::size_t n = 0; n < cut; ++n) a.add(samples[n].data());
        EinsteinEstimator b = reloaded(saved(a));
        for (std::size_t n = cut; n < samples.size(); ++n) {
            a.add(samples[n].data());
            b.add(samples[n].data());
        }
        ASSERT_EQ(a.block_values().size(), 14u);
        ASSERT_EQ(b.block_values().size(), 14u);
        for (std::size_t k = 0; k < 14; ++k)
            EXPECT_TRUE(same_bits(a.block_values()[k], b.block_values()[k])) << k;
        EXPECT_TRUE(same_bits(a.estimate().value, b.estimate().value));
        EXPECT_TRUE(same_bits(a.estimate().error, b.estimate().error));
        const auto ra = a.rows(), rb = b.rows();
        ASSERT_EQ(ra.size(), rb.size());
        for (std::size_t i = 0; i < ra.size(); ++i)
            EXPECT_TRUE(same_bits(ra[i].running, rb[i].running)) << i;
        EXPECT_EQ(saved(a), saved(b));
    }
}

TEST(EinsteinEstimator, LoadRefusesTruncatedAndInconsistentStreams) {
    RandomWalk walk(2, 0.3, 0.0, 0.5, 56);
    EinsteinEstimator e(2, 0.5, 20.0, 1.0, false);
    for (int n = 0; n < 250; ++n) e.add(walk.next());
    const std::string bytes = saved(e);
    for (std::size_t n = 0; n < bytes.size(); n += 5)
        EXPECT_THROW(reloaded(bytes.substr(0, n)), InputError) << n;
    EXPECT_NO_THROW(reloaded(bytes));
    // magic(8) version(4) channels(8) interval(8) block_steps(8): a block of 19 steps, and
    // one that disagrees with the correlators' sample counts
    const auto with_steps = [&](std::uint64_t steps) {
        std::string b = bytes;
        std::memcpy(b.data() + 28, &steps, sizeof steps);
        return b;
    };
    EXPECT_THROW(reloaded(with_steps(19)), InputError);
    EXPECT_THROW(reloaded(with_steps(41)), InputError);
    EXPECT_NO_THROW(reloaded(with_steps(40)));
    // another estimator's channels
    std::string b = bytes;
    const std::uint64_t three = 3;
    std::memcpy(b.data() + 12, &three, sizeof three);
    EXPECT_THROW(reloaded(b), InputError);
}

TEST(EinsteinEstimator, RefusesABlockOfFewerThanTwentyIntervals) {
    EXPECT_THROW(EinsteinEstimator(3, 0.5, 9.0, 1.0, false), InputError);
    EXPECT_NO_THROW(EinsteinEstimator(3, 0.5, 10.0, 1.0, false));
    EXPECT_THROW(EinsteinEstimator(3, 0.5, 10.0, std::nan(""), false), InputError);
    EXPECT_THROW(EinsteinEstimator(3, 0.0, 10.0, 1.0, false), InputError);
}
