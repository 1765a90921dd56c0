#include "pedesis/observe/transport_fit.hpp"

#include "pedesis/core/error.hpp"
#include "pedesis/io/binary_stream.hpp"

#include <cmath>
#include <istream>
#include <limits>
#include <ostream>

namespace pedesis {

namespace {

constexpr double nan = std::numeric_limits<double>::quiet_NaN();
constexpr std::uint64_t estimator_magic = 0x4e494554534e4945ULL; // "EINSTEIN"
constexpr std::uint32_t estimator_version = 1;
constexpr std::uint64_t min_block_steps = 20;
constexpr std::uint64_t max_block_steps = std::uint64_t{1} << 52; // exact in a double

std::uint64_t block_steps(double block_time, double interval) {
    const double steps = block_time / interval;
    if (!(steps >= static_cast<double>(min_block_steps) - 0.5) ||
        !(steps <= static_cast<double>(max_block_steps)))
        throw InputError(
            "transport: a block must hold at least " + std::to_string(min_block_steps) +
            " sample intervals (block_time / interval = " + std::to_string(steps) + ")");
    return static_cast<std::uint64_t>(std::llround(steps));
}

} // namespace

FitWindow fit_window(double block_time) {
    if (!(block_time > 0.0) || !std::isfinite(block_time))
        throw InputError("transport: the block time must be positive and finite");
    const double to = block_time / 10.0;
    return {to / 4.0, to};
}

double einstein_slope(const std::vector<MomentCorrelator::Lag>& lags, FitWindow window,
                      bool remove_drift) {
    const double lo = window.from * (1.0 - 1e-9), hi = window.to * (1.0 + 1e-9);
    std::vector<double> t, y;
    for (const auto& lag : lags) {
        if (lag.tau < lo || lag.tau > hi) continue;
        t.push_back(lag.tau);
        y.push_back(remove_drift ? lag.mean_square - lag.mean * lag.mean : lag.mean_square);
    }
    if (t.size() < 2) return nan;
    const auto n = static_cast<double>(t.size());
    double tm = 0.0, ym = 0.0;
    for (std::size_t i = 0; i < t.size(); ++i) {
        tm += t[i];
        ym += y[i];
    }
    tm /= n;
    ym /= n;
    double sty = 0.0, stt = 0.0;
    for (std::size_t i = 0; i < t.size(); ++i) {
        sty += (t[i] - tm) * (y[i] - ym);
        stt += (t[i] - tm) * (t[i] - tm);
    }
    return sty / stt;
}

Estimate block_estimate(const std::vector<double>& per_block) {
    const std::size_t B = per_block.size();
    if (B == 0) return {nan, nan, 0};
    double mean = 0.0;
    for (double v : per_block) mean += v;
    mean /= static_cast<double>(B);
    if (B < 2) return {mean, nan, B};
    double ss = 0.0;
    for (double v : per_block) ss += (v - mean) * (v - mean);
    const double variance = ss / static_cast<double>(B - 1);
    return {mean, std::sqrt(variance / static_cast<double>(B)), B};
}

std::vector<double> running_integral(const std::vector<AutoCorrelator::Lag>& lags) {
    std::vector<double> out;
    out.reserve(lags.size());
    double sum = 0.0, t = 0.0, c = lags.empty() ? 0.0 : lags.front().correlation;
    for (const auto& lag : lags) {
        sum += 0.5 * (lag.tau - t) * (lag.correlation + c);
        t = lag.tau;
        c = lag.correlation;
        out.push_back(sum);
    }
    return out;
}

EinsteinEstimator::EinsteinEstimator(std::size_t channels, double interval, double block_time,
                                     double scale, bool remove_drift)
    : interval_(interval), scale_(scale), remove_drift_(remove_drift), whole_(channels, interval),
      block_(channels, interval) {
    if (!std::isfinite(scale)) throw InputError("transport: the scale must be finite");
    block_steps_ = block_steps(block_time, interval);
}

void EinsteinEstimator::add(const double* values) {
    whole_.add(values);
    block_.add(values);
    if (block_.samples() <= block_steps_) return;
    block_values_.push_back(coefficient(block_.lags()));
    block_.clear();
    block_.add(values); // the end of this block starts the next
}

double EinsteinEstimator::fitted(const MomentCorrelator::Lag& lag) const {
    return remove_drift_ ? lag.mean_square - lag.mean * lag.mean : lag.mean_square;
}

double EinsteinEstimator::coefficient(const std::vector<MomentCorrelator::Lag>& lags) const {
    return scale_ * einstein_slope(lags, window(), remove_drift_) / 2.0;
}

Estimate EinsteinEstimator::estimate() const {
    if (block_values_.size() >= 2) return block_estimate(block_values_);
    return {coefficient(whole_.lags()), nan, block_values_.size()};
}

std::vector<EinsteinEstimator::Row> EinsteinEstimator::rows() const {
    const auto lags = whole_.lags();
    const std::size_t n = lags.size();
    std::vector<Row> out;
    out.reserve(n);
    for (std::size_t i = 0; i < n; ++i) {
        double running = nan;
        if (n >= 2) {
            const std::size_t a = i == 0 ? 0 : i - 1, b = i + 1 == n ? i : i + 1;
            running =
                scale_ * (fitted(lags[b]) - fitted(lags[a])) / (lags[b].tau - lags[a].tau) / 2.0;
        }
        out.push_back({lags[i].tau, fitted(lags[i]), running});
    }
    return out;
}

std::size_t EinsteinEstimator::memory_bytes() const {
    return sizeof(*this) + whole_.memory_bytes() + block_.memory_bytes() +
           block_values_.capacity() * sizeof(double);
}

void EinsteinEstimator::save(std::ostream& out) const {
    binary::put(out, estimator_magic);
    binary::put(out, estimator_version);
    binary::put<std::uint64_t>(out, whole_.channels());
    binary::put(out, interval_);
    binary::put(out, block_steps_);
    binary::put(out, scale_);
    binary::put<std::uint8_t>(out, remove_drift_);
    whole_.save(out);
    block_.save(out);
    binary::put(out, block_values_);
}

EinsteinEstimator EinsteinEstimator::load(std::istream& in) {
    std::uint64_t magic = 0, channels = 0, steps = 0;
    std::uint32_t version = 0;
    double interval = 0.0, scale = 0.0;
    std::uint8_t drift = 0;
    binary::get(in, magic);
    if (magic != estimator_magic) throw InputError("transport: not a pedesis transport estimator");
    binary::get(in, version);
    if (version != estimator_version)
        throw InputError("transport: unsupported estimator version " + std::to_string(version));
    binary::get(in, channels);
    binary::get(in, interval);
    binary::get(in, steps);
    binary::get(in, scale);
    binary::get(in, drift);
    if (steps < min_block_steps || steps > max_block_steps || drift > 1)
        throw InputError("transport: corrupt estimator header");
    EinsteinEstimator e(channels, interval, static_cast<double>(steps) * interval, scale,
                        drift != 0);
    e.whole_ = MomentCorrelator::load(in);
    e.block_ = MomentCorrelator::load(in);
    binary::get(in, e.block_values_);
    const auto same = [&](const MomentCorrelator& c) {
        return c.channels() == channels && c.interval() == interval;
    };
    const std::uint64_t whole = e.whole_.samples(), part = e.block_.samples();
    const bool counts_agree = whole == 0 ? part == 0 && e.block_values_.empty()
                                         : part >= 1 && part <= steps && part <= whole &&
                                               (whole - part) / steps == e.block_values_.size() &&
                                               (whole - part) % steps == 0;
    if (e.block_steps_ != steps || !same(e.whole_) || !same(e.block_) || !counts_agree)
        throw InputError("transport: corrupt estimator (its correlators disagree)");
    return e;
}

} // namespace pedesis
