#include "pedesis/observe/multiple_tau.hpp"

#include "pedesis/core/error.hpp"
#include "pedesis/io/binary_stream.hpp"

#include <algorithm>
#include <cmath>
#include <istream>
#include <ostream>
#include <string>

namespace pedesis::detail {

namespace {

constexpr std::uint64_t magic = 0x524f4c4552524f43ULL; // "CORRELOR"
constexpr std::uint32_t version = 1;

// Channels are summed in fixed chunks, each chunk's sum kept apart and the chunks added
// in order: the result is the same bits whatever the number of threads, so that a
// checkpoint continues exactly on another machine. A chunk of x and of a ring row stays
// in L1 while the lags are swept.
constexpr std::size_t chunk = 1024;

// Far beyond any run, small enough that channels x points x 8 bytes cannot overflow.
constexpr std::uint64_t max_channels = std::uint64_t{1} << 40;
constexpr std::uint64_t max_points = 1u << 16;
constexpr std::uint64_t max_ratio = 1u << 16;
constexpr std::uint64_t max_max_levels = 64;

void check_range(const char* what, std::uint64_t v, std::uint64_t lo, std::uint64_t hi) {
    if (v < lo || v > hi)
        throw InputError(std::string("correlator: ") + what + " " + std::to_string(v) +
                         " is out of range (" + std::to_string(lo) + " to " + std::to_string(hi) +
                         ")");
}

} // namespace

MultipleTau::MultipleTau(Kind kind, std::size_t channels, double interval, std::size_t points,
                         std::size_t ratio, std::size_t max_levels)
    : kind_(kind), channels_(channels), interval_(interval), points_(points), ratio_(ratio),
      max_levels_(max_levels) {
    if (kind != Kind::increments && kind != Kind::products)
        throw InputError("correlator: unknown kind");
    if (!(interval > 0.0) || !std::isfinite(interval))
        throw InputError("correlator: the sample interval must be positive and finite");
    check_range("channels", channels, 1, max_channels);
    check_range("points", points, 2, max_points);
    check_range("ratio", ratio, 2, max_ratio);
    check_range("max_levels", max_levels, 1, max_max_levels);
}

std::size_t MultipleTau::first_lag(std::size_t level) const {
    if (level == 0) return kind_ == Kind::increments ? 1 : 0; // a zero increment says nothing
    return (points_ + ratio_ - 1) / ratio_;
}

void MultipleTau::open_level() {
    if (partial_.empty()) partial_.assign(2 * ((channels_ + chunk - 1) / chunk) * points_, 0.0);
    if (active_ == levels_.size()) {
        Level L;
        L.ring.assign(points_ * channels_, 0.0);
        L.linear.assign(points_, 0.0);
        L.quadratic.assign(points_, 0.0);
        L.count.assign(points_, 0);
        if (kind_ == Kind::products && levels_.size() + 1 < max_levels_)
            L.block.assign(channels_, 0.0);
        levels_.push_back(std::move(L));
    }
    ++active_;
}

void MultipleTau::clear() {
    for (Level& L : levels_) {
        std::fill(L.linear.begin(), L.linear.end(), 0.0);
        std::fill(L.quadratic.begin(), L.quadratic.end(), 0.0);
        std::fill(L.count.begin(), L.count.end(), 0);
        std::fill(L.block.begin(), L.block.end(), 0.0);
        L.received = L.head = L.in_block = 0;
    }
    active_ = 0;
    samples_ = 0;
}

void MultipleTau::add(const double* values) {
    if (samples_ == 0) {
        if (kind_ == Kind::increments) origin_.assign(values, values + channels_);
        open_level();
    }
    ++samples_;
    push(0, values);
}

void MultipleTau::push(std::size_t l, const double* value) {
    Level& L = levels_[l];
    L.head = L.received == 0 ? 0 : (L.head + 1) % points_;
    double* row = L.ring.data() + L.head * channels_;
    std::copy_n(value, channels_, row);
    const std::uint64_t k = L.received++;
    const std::size_t lo = first_lag(l);
    const auto hi = static_cast<std::size_t>(std::min<std::uint64_t>(points_ - 1, k));
    if (lo <= hi) accumulate(L, lo, hi);
    if (l + 1 == max_levels_) return;

    if (kind_ == Kind::increments) {
        if (k == 0 || k % ratio_ != 0) return;
        // Level l+1 holds the samples at multiples of ratio^(l+1), the first of them the
        // run's first sample, which the levels below have long forgotten.
        if (active_ == l + 1) {
            open_level();
            push(l + 1, origin_.data());
        }
        push(l + 1, row);
        return;
    }
    double* block = L.block.data();
    for (std::size_t c = 0; c < channels_; ++c) block[c] += row[c];
    if (++L.in_block < ratio_) return;
    const auto r = static_cast<double>(ratio_);
    for (std::size_t c = 0; c < channels_; ++c) block[c] /= r;
    if (active_ == l + 1) open_level();
    push(l + 1, block);
    Level& same = levels_[l]; // opening a level may have moved the levels (not their rows)
    std::fill(same.block.begin(), same.block.end(), 0.0);
    same.in_block = 0;
}

void MultipleTau::accumulate(Level& L, std::size_t lo, std::size_t hi) {
    const std::size_t P = points_, C = channels_;
    const std::size_t chunks = (C + chunk - 1) / chunk;
    double* lin = partial_.data();
    double* quad = lin + chunks * P;
    const double* ring = L.ring.data();
    const std::size_t newest = L.head;
    const bool increments = kind_ == Kind::increments;
    const auto chunk_sums = [&](std::size_t k) {
        const std::size_t c0 = k * chunk, n = std::min(chunk, C - c0);
        const double* x = ring + newest * C + c0;
        for (std::size_t j = lo; j <= hi; ++j) {
            const std::size_t row = newest >= j ? newest - j : newest + P - j;
            const double* y = ring + row * C + c0;
            double s1 = 0.0, s2 = 0.0;
            if (increments) {
#pragma omp simd reduction(+ : s1, s2)
                for (std::size_t i = 0; i < n; ++i) {
                    const double d = x[i] - y[i];
                    s1 += d;
                    s2 += d * d;
                }
            } else {
#pragma omp simd reduction(+ : s2)
                for (std::size_t i = 0; i < n; ++i) s2 += x[i] * y[i];
            }
            lin[k * P + j] = s1;
            quad[k * P + j] = s2;
        }
    };
    // On the caller's thread: a parallel region per sample left the other threads
    // spinning between samples, which doubled the CPU time of an event-driven run (a
    // single-threaded engine) with [transport] on 2 cores.
    for (std::size_t k = 0; k < chunks; ++k) chunk_sums(k);
    for (std::size_t j = lo; j <= hi; ++j) {
        double s1 = 0.0, s2 = 0.0;
        for (std::size_t k = 0; k < chunks; ++k) {
            s1 += lin[k * P + j];
            s2 += quad[k * P + j];
        }
        L.linear[j] += s1;
        L.quadratic[j] += s2;
        ++L.count[j];
    }
}

std::vector<MultipleTau::LagSums> MultipleTau::lags() const {
    std::vector<LagSums> out;
    double step = interval_; // ratio^level intervals
    for (std::size_t l = 0; l < active_; ++l) {
        const Level& L = levels_[l];
        for (std::size_t j = first_lag(l); j < points_; ++j)
            if (L.count[j] > 0)
                out.push_back(
                    {static_cast<double>(j) * step, L.linear[j], L.quadratic[j], L.count[j]});
        step *= static_cast<double>(ratio_);
    }
    return out;
}

std::size_t MultipleTau::memory_bytes() const {
    std::size_t bytes = sizeof(*this) + origin_.capacity() * sizeof(double) +
                        partial_.capacity() * sizeof(double) + levels_.capacity() * sizeof(Level);
    for (const Level& L : levels_)
        bytes += (L.ring.capacity() + L.linear.capacity() + L.quadratic.capacity() +
                  L.block.capacity()) *
                     sizeof(double) +
                 L.count.capacity() * sizeof(std::uint64_t);
    return bytes;
}

void MultipleTau::save(std::ostream& out) const {
    binary::put(out, magic);
    binary::put(out, version);
    binary::put(out, static_cast<std::uint8_t>(kind_));
    binary::put<std::uint64_t>(out, channels_);
    binary::put(out, interval_);
    for (std::size_t v : {points_, ratio_, max_levels_}) binary::put<std::uint64_t>(out, v);
    binary::put(out, samples_);
    binary::put(out, samples_ > 0 ? origin_ : std::vector<double>{});
    binary::put<std::uint64_t>(out, active_);
    for (std::size_t l = 0; l < active_; ++l)
        level_fields(levels_[l], [&](const auto& field) { binary::put(out, field); });
}

MultipleTau MultipleTau::load(std::istream& in, Kind kind) {
    std::uint64_t m = 0;
    std::uint32_t v = 0;
    std::uint8_t k = 0;
    binary::get(in, m);
    if (m != magic) throw InputError("correlator: not a pedesis correlator");
    binary::get(in, v);
    if (v != version) throw InputError("correlator: unsupported version " + std::to_string(v));
    binary::get(in, k);
    if (k != static_cast<std::uint8_t>(kind))
        throw InputError("correlator: the stream holds a correlator of another kind");
    std::uint64_t channels = 0, points = 0, ratio = 0, max_levels = 0;
    double interval = 0.0;
    binary::get(in, channels);
    binary::get(in, interval);
    for (std::uint64_t* p : {&points, &ratio, &max_levels}) binary::get(in, *p);
    MultipleTau t(kind, channels, interval, points, ratio, max_levels);

    const auto corrupt = [](const std::string& what) {
        return InputError("correlator: corrupt stream (" + what + ")");
    };
    binary::get(in, t.samples_);
    binary::get(in, t.origin_);
    const bool keeps_origin = kind == Kind::increments && t.samples_ > 0;
    if (t.origin_.size() != (keeps_origin ? channels : 0)) throw corrupt("first sample");
    std::uint64_t active = 0;
    binary::get(in, active);
    if (active > max_levels || (active == 0) != (t.samples_ == 0)) throw corrupt("level count");
    for (std::uint64_t l = 0; l < active; ++l) {
        Level L;
        level_fields(L, [&](auto& field) { binary::get(in, field); });
        const bool averages = kind == Kind::products && l + 1 < max_levels;
        if (L.ring.size() != points * channels || L.linear.size() != points ||
            L.quadratic.size() != points || L.count.size() != points ||
            L.block.size() != (averages ? channels : 0))
            throw corrupt("level " + std::to_string(l) + " sizes");
        if (L.received == 0 || L.head != (L.received - 1) % points || L.in_block >= ratio ||
            (l == 0 && L.received != t.samples_))
            throw corrupt("level " + std::to_string(l) + " counters");
        t.levels_.push_back(std::move(L));
        ++t.active_;
    }
    if (active > 0) t.partial_.assign(2 * ((channels + chunk - 1) / chunk) * points, 0.0);
    return t;
}

} // namespace pedesis::detail
