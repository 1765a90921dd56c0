#pragma once
// The standard multiple-tau autocorrelator (Ramirez, Sukumaran, Vorselaars, Likhtman,
// J. Chem. Phys. 133, 154103 (2010)), averaged over channels: for the velocity
// autocorrelation, channels = d N velocity components and correlation = <v_a(0) v_a(t)>
// (times d for <v(0).v(t)>). Level 0 pairs each sample with itself and the points - 1
// before it; level l holds averages of ratio^l consecutive samples and adds the lags
// j ratio^l, j = ceil(points / ratio) .. points - 1. The averaging smooths the function
// over the level's block (relative error about (block / decay time)^2 / 12 for an
// exponential), the price of bounded memory: channels x (points + 1) doubles per level.
#include "pedesis/observe/multiple_tau.hpp"

#include <cstddef>
#include <cstdint>
#include <iosfwd>
#include <utility>
#include <vector>

namespace pedesis {

class AutoCorrelator : public detail::CorrelatorBase {
  public:
    struct Lag {
        double tau;
        double correlation;  // mean over pairs and channels of x_c(t + tau) x_c(t)
        std::uint64_t count; // pairs (time origins), each over every channel
    };

    // `interval`: the time between samples. Throws InputError on sizes out of range.
    AutoCorrelator(std::size_t channels, double interval, std::size_t points = 16,
                   std::size_t ratio = 2, std::size_t max_levels = 48)
        : AutoCorrelator(detail::MultipleTau(detail::MultipleTau::Kind::products, channels,
                                             interval, points, ratio, max_levels)) {}

    // Ascending in tau, starting at tau = 0; only lags with pairs.
    std::vector<Lag> lags() const;

    // Throws InputError on a truncated, foreign or inconsistent stream.
    static AutoCorrelator load(std::istream& in);

  private:
    explicit AutoCorrelator(detail::MultipleTau tau) : CorrelatorBase(std::move(tau)) {}
};

} // namespace pedesis
