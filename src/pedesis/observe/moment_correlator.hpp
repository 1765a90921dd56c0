#pragma once
// Mean square increments of running sums G_c (Einstein/Helfand moments, unwrapped
// positions for an MSD) at lags spread geometrically up to the whole run, in bounded
// memory: a multiple-tau scheme whose coarser levels keep every ratio^l-th sample
// (decimation, not block averages). The increment of a running sum between two point
// values is exact, so each lag's mean is the exact mean over its pairs: unbiased at every
// lag, and equal to the brute-force mean over the same pairs.
//
// Lags: level 0 pairs each sample with the points - 1 before it (lags 1 .. points - 1
// intervals); level l holds the samples at times that are multiples of ratio^l intervals
// and adds the lags j ratio^l, j = ceil(points / ratio) .. points - 1, each over the pairs
// of its samples (no lag is repeated across levels). Cost per sample: about
// channels x points x ratio / (ratio - 1) subtractions; memory: channels x points doubles
// per level, at most max_levels levels (created as the run reaches them).
#include "pedesis/observe/multiple_tau.hpp"

#include <cstddef>
#include <cstdint>
#include <iosfwd>
#include <utility>
#include <vector>

namespace pedesis {

class MomentCorrelator : public detail::CorrelatorBase {
  public:
    struct Lag {
        double tau;
        double mean_square;  // over pairs and channels of (G_c(t + tau) - G_c(t))^2
        double mean;         // the same of G_c(t + tau) - G_c(t): variance = mean_square - mean^2
        std::uint64_t count; // pairs (time origins), each over every channel
    };

    // `interval`: the time between samples. Throws InputError on sizes out of range.
    MomentCorrelator(std::size_t channels, double interval, std::size_t points = 16,
                     std::size_t ratio = 2, std::size_t max_levels = 48)
        : MomentCorrelator(detail::MultipleTau(detail::MultipleTau::Kind::increments, channels,
                                               interval, points, ratio, max_levels)) {}

    // Ascending in tau; only lags with pairs.
    std::vector<Lag> lags() const;

    // Throws InputError on a truncated, foreign or inconsistent stream.
    static MomentCorrelator load(std::istream& in);

  private:
    explicit MomentCorrelator(detail::MultipleTau tau) : CorrelatorBase(std::move(tau)) {}
};

} // namespace pedesis
