#pragma once
// Observables of a soft / active system, each a plain function of the state so that the
// run driver, the tests and the Python module compute them the same way.
#include "pedesis/core/sym_tensor.hpp"
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
// (unwrapped, by tag); alpha[s] is species s's active force along the director, and
// `active` (empty, or one per owned particle) the other active forces
// (ForceTerm::add_active_forces); only finite masses count as kinetic.
template <int D> struct SoftLogSums {
    Vec<D> director{};                 // sum n_i
    double squared_displacement = 0.0; // sum |dr_i|^2
    Vec<D> displacement{};             // sum dr_i
    double swim = 0.0;                 // sum F_active,i . dr_i
    Vec<D> swim_direction{};           // sum F_active,i
    Vec<D> momentum{};                 // sum m_i v_i
    double mass = 0.0;                 // sum m_i
    double kinetic = 0.0;              // sum m_i v_i^2 / 2
    double mobile = 0.0;               // particles of finite mass
    double particles = 0.0;
    SymTensor swim_tensor{};    // sum F_active,i dr_i (symmetrised)
    SymTensor kinetic_tensor{}; // sum m_i v_i v_i

    static constexpr std::size_t size = 4 * D + 6 + 12;
    std::array<double, size> flat() const {
        std::array<double, size> f{};
        std::size_t k = 0;
        for (const Vec<D>* v : {&director, &displacement, &swim_direction, &momentum})
            for (int a = 0; a < D; ++a) f[k++] = (*v)[a];
        for (double x : {squared_displacement, swim, mass, kinetic, mobile, particles}) f[k++] = x;
        for (const SymTensor* t : {&swim_tensor, &kinetic_tensor})
            for (double x : *t) f[k++] = x;
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
        for (SymTensor* t : {&s.swim_tensor, &s.kinetic_tensor})
            for (double& x : *t) x = f[k++];
        return s;
    }
};

// Parts of the pressure tensor times the volume, from the sums. The kinetic part in the
// centre-of-mass frame along the conserved axes: sum m (v - V)_a (v - V)_b, V_a = P_a / M
// on a conserved axis and 0 elsewhere, which is sum m v_a v_b - P_a P_b / M when a or b
// is conserved (its trace is 2 K less the conserved components' P_a^2 / M).
template <int D>
SymTensor thermal_tensor_of(const SoftLogSums<D>& t, const std::array<bool, D>& conserved) {
    SymTensor k = t.kinetic_tensor;
    if (t.mass > 0.0)
        for (int a = 0; a < D; ++a)
            for (int b = a; b < D; ++b)
                if (conserved[a] || conserved[b])
                    k[sym_slot(a, b)] -= t.momentum[a] * t.momentum[b] / t.mass;
    return k;
}

// The swim part: sum F_active,a (dr - drift)_b (symmetrised), the drift the mean
// displacement: the tensor whose trace / d V is the swim pressure (active_virial.hpp).
template <int D> SymTensor swim_tensor_of(const SoftLogSums<D>& t) {
    SymTensor s = t.swim_tensor;
    if (t.particles > 0.0)
        add_sym_outer<D>(s, t.swim_direction, t.displacement, -1.0 / t.particles);
    return s;
}

template <int D>
SoftLogSums<D> soft_log_sums(const SoftState<D>& s, const std::vector<Vec<D>>& start,
                             const std::vector<double>& alpha,
                             const std::vector<Vec<D>>& active = {}) {
    SoftLogSums<D> t;
    for (std::size_t i = 0; i < s.owned(); ++i) {
        const Vec<D> dr = s.unwrapped(i) - start[s.p.tag[i]];
        const double a = alpha[s.p.species[i]];
        t.director += s.director[i];
        t.squared_displacement += norm2(dr);
        t.displacement += dr;
        t.swim += a * dot(s.director[i], dr);
        t.swim_direction += a * s.director[i];
        add_sym_outer<D>(t.swim_tensor, s.director[i], dr, a);
        if (!active.empty()) {
            t.swim += dot(active[i], dr);
            t.swim_direction += active[i];
            add_sym_outer<D>(t.swim_tensor, active[i], dr, 1.0);
        }
        const double m = s.p.mass(i);
        if (std::isfinite(m)) {
            t.momentum += m * s.p.velocity[i];
            t.mass += m;
            t.kinetic += 0.5 * m * norm2(s.p.velocity[i]);
            add_sym_outer<D>(t.kinetic_tensor, s.p.velocity[i], s.p.velocity[i], m);
            t.mobile += 1.0;
        }
        t.particles += 1.0;
    }
    return t;
}

} // namespace pedesis
