#pragma once
// The swim (active) pressure of any active force: (1 / (d V)) sum_i F_i . (dr_i - dR),
// where dr_i is the unwrapped displacement since `start` and dR its mean. It is the
// virial of the active forces, which stays well defined in a periodic box. The mean is
// subtracted because a polar flock drifts as a whole; without it the sum would grow
// without bound in the ordered state.
#include "pedesis/soft/soft_state.hpp"

#include <vector>

namespace pedesis {

// work(i, d) is particle i's F_i . d for its displacement d less the drift (storage
// index i; `start` by tag).
template <int D, class Work>
double active_virial(const SoftState<D>& s, const std::vector<Vec<D>>& start, Work&& work) {
    const std::size_t n = s.size();
    if (n == 0) return 0.0;
    Vec<D> drift{};
    for (std::size_t i = 0; i < n; ++i) drift += s.unwrapped(i) - start[s.p.tag[i]];
    drift *= 1.0 / static_cast<double>(n);
    double sum = 0.0;
    for (std::size_t i = 0; i < n; ++i) sum += work(i, s.unwrapped(i) - start[s.p.tag[i]] - drift);
    return sum / (D * s.box.volume());
}

} // namespace pedesis
