#pragma once
// Observables of a soft / active system, each a plain function of the state so that the
// run driver, the tests and the Python module compute them the same way.
#include "pedesis/soft/soft_state.hpp"

#include <array>
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

// The sums over particles [0, owned) that every quantity of the soft log is made of, so
// that processes sharing a run (domain decomposition) each sum their own particles and
// add the sums up: reductions, not a gathered state. Displacements are from `start`
// (unwrapped, by tag); alpha[s] is species s's active force; only finite masses count
// as kinetic.
template <int D> struct SoftLogSums {
    Vec<D> director{};                 // sum n_i
    double squared_displacement = 0.0; // sum |dr_i|^2
    Vec<D> displacement{};             // sum dr_i
    double swim = 0.0;                 // sum alpha_i n_i . dr_i
    Vec<D> swim_direction{};           // sum alpha_i n_i
    Vec<D> momentum{};                 // sum m_i v_i
    double mass = 0.0;                 // sum m_i
    double kinetic = 0.0;              // sum m_i v_i^2 / 2
    double mobile = 0.0;               // particles of finite mass
    double particles = 0.0;

    static constexpr std::size_t size = 4 * D + 6;
    std::array<double, size> flat() const {
        std::array<double, size> f{};
        std::size_t k = 0;
        for (const Vec<D>* v : {&director, &displacement, &swim_direction, &momentum})
            for (int a = 0; a < D; ++a) f[k++] = (*v)[a];
        for (double x : {squared_displacement, swim, mass, kinetic, mobile, particles}) f[k++] = x;
        return f;
    }
    static SoftLogSums from_flat(const std::array<double, size>& f) {
        SoftLogSums s;
        std::size_t k = 0;
        for (Vec<D>* v : {&s.director, &s.displacement, &s.swim_direction, &s.momentum})
            for (int a = 0; a < D; ++a) (*v)[a] = f[k++];
        for (double* x :
             {&s.squared_displacement, &s.swim, &s.mass, &s.kinetic, &s.mobile, &s.particles})
            *x = f[k++];
        return s;
    }
};

template <int D>
SoftLogSums<D> soft_log_sums(const SoftState<D>& s, const std::vector<Vec<D>>& start,
                             const std::vector<double>& alpha) {
    SoftLogSums<D> t;
    for (std::size_t i = 0; i < s.owned(); ++i) {
        const Vec<D> dr = s.unwrapped(i) - start[s.p.tag[i]];
        const double a = alpha[s.p.species[i]];
        t.director += s.director[i];
        t.squared_displacement += norm2(dr);
        t.displacement += dr;
        t.swim += a * dot(s.director[i], dr);
        t.swim_direction += a * s.director[i];
        const double m = s.p.mass(i);
        if (std::isfinite(m)) {
            t.momentum += m * s.p.velocity[i];
            t.mass += m;
            t.kinetic += 0.5 * m * norm2(s.p.velocity[i]);
            t.mobile += 1.0;
        }
        t.particles += 1.0;
    }
    return t;
}

} // namespace pedesis
