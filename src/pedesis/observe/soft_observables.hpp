#pragma once
// Observables of a soft / active system, each a plain function of the state so that the
// run driver, the tests and the Python module compute them the same way.
#include "pedesis/soft/soft_state.hpp"

#include <cmath>
#include <vector>

namespace pedesis {

// |sum_i n_i| / N: 1 when every director points the same way, O(N^-1/2) when random.
template <int D> double polar_order(const SoftState<D>& s) {
    Vec<D> sum{};
    for (const auto& n : s.director) sum += n;
    return s.size() ? norm(sum) / static_cast<double>(s.size()) : 0.0;
}

// Mean squared displacement of the unwrapped positions from `start`, indexed by tag.
template <int D>
double mean_squared_displacement(const SoftState<D>& s, const std::vector<Vec<D>>& start) {
    double sum = 0.0;
    for (std::size_t i = 0; i < s.size(); ++i) sum += norm2(s.unwrapped(i) - start[s.p.tag[i]]);
    return s.size() ? sum / static_cast<double>(s.size()) : 0.0;
}

template <int D> double kinetic_energy(const SoftState<D>& s) {
    double sum = 0.0;
    for (std::size_t i = 0; i < s.size(); ++i) {
        const double m = s.p.mass(i);
        if (std::isfinite(m)) sum += 0.5 * m * norm2(s.p.velocity[i]);
    }
    return sum;
}

} // namespace pedesis
