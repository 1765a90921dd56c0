#pragma once
// The storage and the inner loop that the two multiple-tau correlators share
// (moment_correlator.hpp, auto_correlator.hpp). Level l is a ring of `points` rows of
// `channels` values spaced ratio^l samples apart; a new row at level l is paired with the
// rows j = lo..points-1 behind it, where lo is 0 or 1 on level 0 and ceil(points/ratio)
// above (smaller j there would repeat a lag of the level below). What a coarser level is
// fed and what a pair adds is the Kind:
// - increments: every ratio-th row of the level below (decimation, point values: the
//   increments of a running sum between point values are exact, so every lag's mean is
//   the exact mean over its pairs, with no smoothing); a pair adds d and d^2, d = new - old.
// - products: the average of ratio rows of the level below (Ramirez et al., J. Chem. Phys.
//   133, 154103 (2010)); a pair adds new * old.
// Memory: channels x points doubles per level (products: one row more, the average being
// built), levels created as the run reaches them, at most max_levels; no allocation in add()
// once a level exists.
#include <cstddef>
#include <cstdint>
#include <iosfwd>
#include <utility>
#include <vector>

namespace pedesis::detail {

class MultipleTau {
  public:
    enum class Kind : std::uint8_t { increments = 1, products = 2 };

    // One lag: tau = j ratio^level intervals, the sums over its pairs and channels of
    // the increment (increments only) and of the squared increment or the product, and
    // the number of pairs (time origins; each pair covers every channel).
    struct LagSums {
        double tau;
        double linear;
        double quadratic;
        std::uint64_t count;
    };

    // `interval`: the time between samples. Throws InputError on sizes out of range (what a
    // corrupt file could also hold).
    MultipleTau(Kind kind, std::size_t channels, double interval, std::size_t points,
                std::size_t ratio, std::size_t max_levels);

    void add(const double* values);
    // Forgets every sample; keeps the memory (a block restart allocates nothing).
    void clear();

    // Lags with count > 0, ascending.
    std::vector<LagSums> lags() const;

    Kind kind() const { return kind_; }
    std::size_t channels() const { return channels_; }
    double interval() const { return interval_; }
    std::size_t points() const { return points_; }
    std::size_t ratio() const { return ratio_; }
    std::size_t max_levels() const { return max_levels_; }
    std::size_t levels() const { return active_; }
    std::uint64_t samples() const { return samples_; }
    std::size_t memory_bytes() const;

    void save(std::ostream& out) const;
    // Throws InputError on a stream that is truncated, of another kind, or whose sizes
    // disagree; allocates no more than the stream holds.
    static MultipleTau load(std::istream& in, Kind kind);

  private:
    struct Level {
        std::vector<double> ring; // points x channels, row r at r * channels
        std::vector<double> linear, quadratic;
        std::vector<std::uint64_t> count;
        std::vector<double> block; // products below the top level: the sum being averaged
        std::uint64_t received = 0;
        std::uint64_t head = 0; // the row of the newest value
        std::uint64_t in_block = 0;
    };
    // Every field of a level, in the order of the stream (one list for save and load).
    template <class L, class F> static void level_fields(L& level, F&& f) {
        f(level.received);
        f(level.head);
        f(level.in_block);
        f(level.ring);
        f(level.linear);
        f(level.quadratic);
        f(level.count);
        f(level.block);
    }

    void push(std::size_t level, const double* value);
    void accumulate(Level& level, std::size_t lo, std::size_t hi);
    void open_level();
    std::size_t first_lag(std::size_t level) const;

    Kind kind_;
    std::size_t channels_;
    double interval_;
    std::size_t points_, ratio_, max_levels_;
    std::uint64_t samples_ = 0;
    std::vector<double> origin_; // increments: the first sample, the start of every level
    std::vector<Level> levels_;  // allocated; the first active_ are in use
    std::size_t active_ = 0;
    std::vector<double> partial_; // per chunk of channels and lag: the two sums
};

// What the two correlators share around their levels: feeding, sizes, saving.
class CorrelatorBase {
  public:
    // The channels' values at the next sample time.
    void add(const double* values) { tau_.add(values); }
    // Forgets every sample; keeps the memory (a restart allocates nothing).
    void clear() { tau_.clear(); }

    std::size_t channels() const { return tau_.channels(); }
    double interval() const { return tau_.interval(); }
    std::uint64_t samples() const { return tau_.samples(); }
    std::size_t levels() const { return tau_.levels(); }
    std::size_t memory_bytes() const { return tau_.memory_bytes(); }

    // Exact: a loaded correlator fed the same samples gives the same bits (with the same
    // build: the channel sums are vectorised).
    void save(std::ostream& out) const { tau_.save(out); }

  protected:
    explicit CorrelatorBase(MultipleTau tau) : tau_(std::move(tau)) {}
    MultipleTau tau_;
};

} // namespace pedesis::detail
