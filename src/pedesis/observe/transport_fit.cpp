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
constexpr std::uint32_t estimator_version = 2;
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
    double mean = 0.0;
    for (std::size_t c = 0; c < whole_.channels(); ++c) mean += values[c];
    mean /= static_cast<double>(whole_.channels());
    if (whole_.samples() == 0) first_mean_ = mean;
    last_mean_ = mean;
    whole_.add(values);
    block_.add(values);
    if (block_.samples() <= block_steps_) return;
    block_lags_.push_back(block_.lags());
    block_.clear();
    block_.add(values); // the end of this block starts the next
}

double EinsteinEstimator::drift() const {
    const std::uint64_t n = whole_.samples();
    if (n < 2) return 0.0;
    return (last_mean_ - first_mean_) / (static_cast<double>(n - 1) * interval_);
}

double EinsteinEstimator::fitted(const MomentCorrelator::Lag& lag) const {
    if (!remove_drift_) return lag.mean_square;
    const double c = drift(), t = lag.tau;
    const double run = static_cast<double>(whole_.samples() - 1) * interval_;
    if (!(t < run)) return nan;
    return (lag.mean_square - 2.0 * c * t * lag.mean + c * c * t * t) / (1.0 - t / run);
}

double EinsteinEstimator::coefficient(const std::vector<MomentCorrelator::Lag>& lags) const {
    std::vector<MomentCorrelator::Lag> y = lags;
    for (auto& lag : y) lag.mean_square = fitted(lag);
    return scale_ * einstein_slope(y, window(), false) / 2.0;
}

std::vector<double> EinsteinEstimator::block_values() const {
    std::vector<double> v;
    v.reserve(block_lags_.size());
    for (const auto& lags : block_lags_) v.push_back(coefficient(lags));
    return v;
}

Estimate EinsteinEstimator::estimate() const {
    if (block_lags_.size() >= 2) return block_estimate(block_values());
    return {coefficient(whole_.lags()), nan, block_lags_.size()};
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
    std::size_t blocks = 0;
    for (const auto& lags : block_lags_) blocks += lags.capacity() * sizeof(lags[0]);
    return sizeof(*this) + whole_.memory_bytes() + block_.memory_bytes() + blocks;
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
    binary::put<std::uint64_t>(out, block_lags_.size());
    for (const auto& lags : block_lags_) binary::put(out, lags);
    binary::put(out, first_mean_);
    binary::put(out, last_mean_);
    binary::put(out, window_);
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
    std::uint64_t blocks = 0;
    binary::get(in, blocks);
    // each block holds block_steps samples at least: more blocks than samples is corrupt
    // (and each takes 8 bytes of the stream at least)
    if (blocks > e.whole_.samples() || blocks > binary::remaining(in) / 8)
        throw InputError("transport: corrupt estimator blocks");
    e.block_lags_.resize(blocks);
    for (auto& lags : e.block_lags_) binary::get(in, lags);
    binary::get(in, e.first_mean_);
    binary::get(in, e.last_mean_);
    binary::get(in, e.window_);
    if (!(std::isfinite(e.window_.from) && std::isfinite(e.window_.to) && e.window_.from >= 0.0 &&
          e.window_.to >= e.window_.from))
        throw InputError("transport: corrupt fit window");
    const auto same = [&](const MomentCorrelator& c) {
        return c.channels() == channels && c.interval() == interval;
    };
    const std::uint64_t whole = e.whole_.samples(), part = e.block_.samples();
    const bool counts_agree = whole == 0 ? part == 0 && e.block_lags_.empty()
                                         : part >= 1 && part <= steps && part <= whole &&
                                               (whole - part) / steps == e.block_lags_.size() &&
                                               (whole - part) % steps == 0;
    if (e.block_steps_ != steps || !same(e.whole_) || !same(e.block_) || !counts_agree)
        throw InputError("transport: corrupt estimator (its correlators disagree)");
    return e;
}

} // namespace pedesis
