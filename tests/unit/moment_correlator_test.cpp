// The multiple-tau correlators against brute force: every lag they report is recomputed
// here from its definition (the pairs of the decimated or block-averaged series, O(T^2)),
// not with the correlators' code; the two must agree to rounding. Then the exact
// continuation through save/load, the refusal of bad streams, and bounded memory.
#include "pedesis/core/error.hpp"
#include "pedesis/observe/auto_correlator.hpp"
#include "pedesis/observe/moment_correlator.hpp"

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

using Series = std::vector<std::vector<double>>; // [sample][channel]

struct Expected {
    double tau, quadratic, linear;
    std::uint64_t count;
};

// Running sums of random steps of random size, plus some noise, so that neither the
// increments nor the values are trivial.
Series random_sums(std::size_t samples, std::size_t channels, std::uint32_t seed) {
    std::mt19937_64 rng(seed);
    std::normal_distribution<double> normal;
    Series s(samples, std::vector<double>(channels));
    std::vector<double> sum(channels, 0.0);
    for (std::size_t t = 0; t < samples; ++t)
        for (std::size_t c = 0; c < channels; ++c) {
            sum[c] += normal(rng) * (1.0 + 0.5 * static_cast<double>(c % 3));
            s[t][c] = sum[c] + 0.3 * normal(rng);
        }
    return s;
}

std::size_t first_coarse(std::size_t points, std::size_t ratio) {
    return (points + ratio - 1) / ratio;
}

// Level l: the samples at multiples of ratio^l; lags j ratio^l for j from 1 (level 0) or
// ceil(points / ratio); every origin whose partner is in the series.
std::vector<Expected> brute_force_moments(const Series& s, double interval, std::size_t points,
                                          std::size_t ratio, std::size_t max_levels) {
    std::vector<Expected> out;
    const std::size_t T = s.size(), C = s[0].size();
    std::size_t step = 1;
    for (std::size_t l = 0; l < max_levels && step < T; ++l, step *= ratio) {
        for (std::size_t j = l == 0 ? 1 : first_coarse(points, ratio); j < points; ++j) {
            const std::size_t lag = j * step;
            Expected e{static_cast<double>(lag) * interval, 0.0, 0.0, 0};
            for (std::size_t t = 0; t + lag < T; t += step) {
                for (std::size_t c = 0; c < C; ++c) {
                    const double d = s[t + lag][c] - s[t][c];
                    e.quadratic += d * d;
                    e.linear += d;
                }
                ++e.count;
            }
            if (e.count == 0) continue;
            const double n = static_cast<double>(e.count * C);
            e.quadratic /= n;
            e.linear /= n;
            out.push_back(e);
        }
    }
    return out;
}

// Level l: averages of ratio consecutive values of level l - 1; lags j ratio^l for j from 0
// (level 0) or ceil(points / ratio).
std::vector<Expected> brute_force_products(const Series& s, double interval, std::size_t points,
                                           std::size_t ratio, std::size_t max_levels) {
    std::vector<Expected> out;
    const std::size_t C = s[0].size();
    Series level = s;
    double step = interval;
    for (std::size_t l = 0; l < max_levels && !level.empty(); ++l) {
        for (std::size_t j = l == 0 ? 0 : first_coarse(points, ratio); j < points; ++j) {
            Expected e{static_cast<double>(j) * step, 0.0, 0.0, 0};
            for (std::size_t k = j; k < level.size(); ++k) {
                for (std::size_t c = 0; c < C; ++c) e.quadratic += level[k][c] * level[k - j][c];
                ++e.count;
            }
            if (e.count == 0) continue;
            e.quadratic /= static_cast<double>(e.count * C);
            out.push_back(e);
        }
        Series coarser;
        for (std::size_t k = 0; k + ratio <= level.size(); k += ratio) {
            std::vector<double> mean(C, 0.0);
            for (std::size_t i = 0; i < ratio; ++i)
                for (std::size_t c = 0; c < C; ++c) mean[c] += level[k + i][c];
            for (double& m : mean) m /= static_cast<double>(ratio);
            coarser.push_back(mean);
        }
        level = coarser;
        step *= static_cast<double>(ratio);
    }
    return out;
}

void expect_moments(const MomentCorrelator& mc, const std::vector<Expected>& want) {
    const auto got = mc.lags();
    ASSERT_EQ(got.size(), want.size());
    for (std::size_t i = 0; i < got.size(); ++i) {
        SCOPED_TRACE("lag " + std::to_string(i) + " tau " + std::to_string(want[i].tau));
        EXPECT_NEAR(got[i].tau, want[i].tau, 1e-12 * want[i].tau);
        EXPECT_EQ(got[i].count, want[i].count);
        EXPECT_NEAR(got[i].mean_square, want[i].quadratic, 1e-12 * want[i].quadratic);
        EXPECT_NEAR(got[i].mean, want[i].linear, 1e-12 * std::sqrt(want[i].quadratic));
    }
}

void expect_products(const AutoCorrelator& ac, const std::vector<Expected>& want,
                     double magnitude) {
    const auto got = ac.lags();
    ASSERT_EQ(got.size(), want.size());
    for (std::size_t i = 0; i < got.size(); ++i) {
        SCOPED_TRACE("lag " + std::to_string(i) + " tau " + std::to_string(want[i].tau));
        EXPECT_NEAR(got[i].tau, want[i].tau, 1e-12 * want[i].tau);
        EXPECT_EQ(got[i].count, want[i].count);
        EXPECT_NEAR(got[i].correlation, want[i].quadratic, 1e-12 * magnitude);
    }
}

template <class Correlator> void feed(Correlator& c, const Series& s, std::size_t from = 0) {
    for (std::size_t t = from; t < s.size(); ++t) c.add(s[t].data());
}

// Series of a stationary signal (for the autocorrelator): unit-variance noise.
Series random_values(std::size_t samples, std::size_t channels, std::uint32_t seed) {
    std::mt19937_64 rng(seed);
    std::normal_distribution<double> normal;
    Series s(samples, std::vector<double>(channels));
    for (auto& row : s)
        for (double& v : row) v = normal(rng);
    return s;
}

struct Shape {
    std::size_t points, ratio, max_levels;
};

// The defaults; an odd ratio with points not a multiple of it; a capped level count.
constexpr Shape shapes[] = {{16, 2, 48}, {10, 3, 48}, {8, 2, 4}};

std::string describe(const Shape& sh) {
    return "points " + std::to_string(sh.points) + " ratio " + std::to_string(sh.ratio) +
           " max_levels " + std::to_string(sh.max_levels);
}

template <class Correlator> Correlator fed(const Series& s, double interval, const Shape& sh) {
    Correlator c(s[0].size(), interval, sh.points, sh.ratio, sh.max_levels);
    feed(c, s);
    return c;
}

} // namespace

TEST(MomentCorrelator, EqualsTheBruteForceMeanOverTheSamePairsAtEveryLag) {
    const Series s = random_sums(2500, 3, 11);
    for (const Shape& sh : shapes) {
        SCOPED_TRACE(describe(sh));
        const auto want = brute_force_moments(s, 0.1, sh.points, sh.ratio, sh.max_levels);
        expect_moments(fed<MomentCorrelator>(s, 0.1, sh), want);
        // coarse levels are there: the longest lag reaches far past the level-0 ring
        ASSERT_FALSE(want.empty());
        EXPECT_GT(want.back().tau, 0.1 * static_cast<double>(4 * sh.points));
    }
}

TEST(MomentCorrelator, ManyChannelsTakeTheChunkedParallelPathAndStayExact) {
    // 5000 channels: five chunks, the last one partial
    const Series s = random_sums(300, 5000, 12);
    MomentCorrelator mc(5000, 0.5);
    feed(mc, s);
    expect_moments(mc, brute_force_moments(s, 0.5, 16, 2, 48));
}

TEST(AutoCorrelator, EqualsTheBruteForceCorrelationOfTheBlockAveragedSeries) {
    const Series s = random_values(2500, 3, 13);
    for (const Shape& sh : shapes) {
        SCOPED_TRACE(describe(sh));
        const auto want = brute_force_products(s, 0.1, sh.points, sh.ratio, sh.max_levels);
        ASSERT_FALSE(want.empty());
        EXPECT_EQ(want.front().tau, 0.0);
        expect_products(fed<AutoCorrelator>(s, 0.1, sh), want, 1.0);
    }
    const Series wide = random_values(300, 5000, 14);
    AutoCorrelator ac(5000, 0.5);
    feed(ac, wide);
    expect_products(ac, brute_force_products(wide, 0.5, 16, 2, 48), 1.0);
}

namespace {

template <class Correlator> std::string saved(const Correlator& c) {
    std::ostringstream out;
    c.save(out);
    return out.str();
}

template <class Correlator> Correlator reloaded(const std::string& bytes) {
    std::istringstream in(bytes);
    return Correlator::load(in);
}

// Saved after `cut` samples and loaded, then both fed the rest: every lag the same bits
// (the Lag structs have no padding, so their bytes are their values).
template <class Correlator> void expect_exact_continuation(const Series& s, std::size_t cut) {
    SCOPED_TRACE("cut at " + std::to_string(cut));
    Correlator a(4, 0.2, 8, 3, 6);
    for (std::size_t t = 0; t < cut; ++t) a.add(s[t].data());
    Correlator b = reloaded<Correlator>(saved(a));
    EXPECT_EQ(saved(b), saved(a));
    feed(a, s, cut);
    feed(b, s, cut);
    const auto la = a.lags(), lb = b.lags();
    ASSERT_EQ(la.size(), lb.size());
    ASSERT_FALSE(la.empty());
    for (std::size_t i = 0; i < la.size(); ++i)
        EXPECT_EQ(std::memcmp(&la[i], &lb[i], sizeof la[i]), 0) << "lag " << i;
    EXPECT_EQ(b.samples(), s.size());
    EXPECT_EQ(b.levels(), a.levels());
}

} // namespace

TEST(MomentCorrelator, ContinuesBitForBitAfterSaveAndLoad) {
    const Series s = random_sums(3000, 4, 21);
    // saved empty, after one sample, in the middle of the levels' cycles, and late
    for (std::size_t cut : {0, 1, 777, 2049}) expect_exact_continuation<MomentCorrelator>(s, cut);
}

TEST(AutoCorrelator, ContinuesBitForBitAfterSaveAndLoad) {
    const Series s = random_values(3000, 4, 22);
    for (std::size_t cut : {0, 5, 777, 2049}) expect_exact_continuation<AutoCorrelator>(s, cut);
}

TEST(MomentCorrelator, LoadRefusesTruncatedForeignAndCraftedStreams) {
    const Series s = random_sums(700, 3, 23);
    MomentCorrelator mc(3, 0.1);
    feed(mc, s);
    const std::string bytes = saved(mc);
    // every shorter prefix is refused (stride 3 keeps this fast; it still cuts every field)
    for (std::size_t n = 0; n < bytes.size(); n += 3)
        EXPECT_THROW(reloaded<MomentCorrelator>(bytes.substr(0, n)), InputError) << n;
    EXPECT_NO_THROW(reloaded<MomentCorrelator>(bytes));

    // garbage, and an autocorrelator's stream
    std::mt19937 rng(5);
    std::string garbage(bytes.size(), '\0');
    for (char& ch : garbage) ch = static_cast<char>(rng());
    EXPECT_THROW(reloaded<MomentCorrelator>(garbage), InputError);
    AutoCorrelator ac(3, 0.1);
    feed(ac, s);
    EXPECT_THROW(reloaded<MomentCorrelator>(saved(ac)), InputError);
    EXPECT_THROW(reloaded<AutoCorrelator>(bytes), InputError);

    // the header's sizes overwritten: magic(8) version(4) kind(1) channels(8) interval(8)
    // points(8) ratio(8) max_levels(8)
    const auto with = [&](std::size_t offset, std::uint64_t value) {
        std::string b = bytes;
        std::memcpy(b.data() + offset, &value, sizeof value);
        return b;
    };
    const std::size_t channels_at = 13, points_at = 29, ratio_at = 37, levels_at = 45;
    // 2^39 channels would be 64 TiB of ring: refused from the lengths, nothing allocated
    EXPECT_THROW(reloaded<MomentCorrelator>(with(channels_at, std::uint64_t{1} << 39)), InputError);
    EXPECT_THROW(reloaded<MomentCorrelator>(with(channels_at, std::uint64_t{1} << 62)), InputError);
    EXPECT_THROW(reloaded<MomentCorrelator>(with(channels_at, 4)), InputError);
    EXPECT_THROW(reloaded<MomentCorrelator>(with(points_at, 0)), InputError);
    EXPECT_THROW(reloaded<MomentCorrelator>(with(points_at, 17)), InputError);
    EXPECT_THROW(reloaded<MomentCorrelator>(with(ratio_at, 1)), InputError);
    EXPECT_THROW(reloaded<MomentCorrelator>(with(levels_at, 3)), InputError);
    // level 0's ring one value short, the stream otherwise whole: after the header (53),
    // samples (8), the first sample (8 + 3 x 8), the level count (8) and level 0's three
    // counters (24), the ring's length at 125 and its values from 133
    std::string short_ring = with(125, 16 * 3 - 1);
    short_ring.erase(133, 8);
    EXPECT_THROW(reloaded<MomentCorrelator>(short_ring), InputError);
    // the interval: NaN
    std::string bad_interval = bytes;
    const double not_a_number = std::nan("");
    std::memcpy(bad_interval.data() + 21, &not_a_number, sizeof not_a_number);
    EXPECT_THROW(reloaded<MomentCorrelator>(bad_interval), InputError);
}

TEST(MomentCorrelator, ConstructorRefusesSizesOutOfRange) {
    EXPECT_THROW(MomentCorrelator(0, 0.1), InputError);
    EXPECT_THROW(MomentCorrelator(1, 0.0), InputError);
    EXPECT_THROW(MomentCorrelator(1, std::nan("")), InputError);
    EXPECT_THROW(MomentCorrelator(1, 0.1, 1), InputError);
    EXPECT_THROW(MomentCorrelator(1, 0.1, 16, 1), InputError);
    EXPECT_THROW(MomentCorrelator(1, 0.1, 16, 2, 0), InputError);
    EXPECT_THROW(AutoCorrelator(1, 0.1, 16, 2, 65), InputError);
}

TEST(MomentCorrelator, MemoryStaysBoundedOverAMillionSamples) {
    const std::size_t channels = 2, points = 16;
    MomentCorrelator free_levels(channels, 1.0);
    MomentCorrelator capped(channels, 1.0, points, 2, 6);
    AutoCorrelator averaged(channels, 1.0, points, 2, 6);
    std::mt19937_64 rng(3);
    std::normal_distribution<double> normal;
    double x[channels] = {0.0, 0.0};
    for (std::size_t t = 0; t < 1000000; ++t) {
        for (double& v : x) v += normal(rng);
        free_levels.add(x);
        capped.add(x);
        averaged.add(x);
    }
    // a level opens when the run reaches 2^l samples: 2^19 <= 10^6 < 2^20
    EXPECT_EQ(free_levels.levels(), 20u);
    EXPECT_EQ(capped.levels(), 6u);
    EXPECT_EQ(averaged.levels(), 6u);
    // the ring of each level plus its sums, and a small fixed part
    const auto bound = [&](std::size_t levels) {
        return levels * (points * channels + 4 * points + channels) * sizeof(double) + 8192;
    };
    EXPECT_LE(free_levels.memory_bytes(), bound(20));
    EXPECT_LE(capped.memory_bytes(), bound(6));
    EXPECT_LE(averaged.memory_bytes(), bound(6));
    EXPECT_GE(capped.memory_bytes(), 6 * points * channels * sizeof(double));
    // the capped correlators' longest lag is the top level's: 15 x 2^5
    EXPECT_EQ(capped.lags().back().tau, 15.0 * 32.0);
    EXPECT_EQ(averaged.lags().back().tau, 15.0 * 32.0);
    // uncapped: 15 x 2^16 is the longest lag with a pair in 10^6 samples (the top three
    // levels, opened at 2^17 .. 2^19, have none yet)
    EXPECT_EQ(free_levels.lags().back().tau, 15.0 * 65536.0);
}
