#include "pedesis/stepped/time_step.hpp"

#include "pedesis/core/error.hpp"
#include "pedesis/observe/theory.hpp"
#include "pedesis/observe/thermo.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <limits>

namespace pedesis {

namespace {

// Rounds down to two significant digits, so that a suggested dt is easy to type and
// never above the bound it comes from.
double round_down_two_digits(double x) {
    if (!(x > 0.0) || !std::isfinite(x)) return x;
    const double scale = std::pow(10.0, std::floor(std::log10(x)) - 1.0);
    double r = std::floor(x / scale) * scale;
    if (r > x) r -= scale; // rounding of the product can land a hair above x
    return r;
}

} // namespace

template <int D> FastestParticle fastest_particle(const ParticleStore<D>& p, double dt) {
    FastestParticle f;
    for (std::size_t i = 0; i < p.size(); ++i) {
        if (std::isinf(p.mass(i))) continue;
        const double v = norm(p.velocity[i]);
        const double moves = v * dt / p.radius(i);
        if (moves > f.radii_per_step) f = FastestParticle{i, v, moves};
    }
    return f;
}

template <int D>
double expected_collisions_per_particle(const ParticleStore<D>& p, const Box<D>& box,
                                        double duration) {
    double diameter = 0.0, mass = 0.0;
    std::size_t mobile = 0;
    for (std::size_t i = 0; i < p.size(); ++i) {
        if (std::isinf(p.mass(i))) continue;
        diameter += 2.0 * p.radius(i);
        mass += p.mass(i);
        ++mobile;
    }
    // lab-frame speeds set the collision rate and the step: no centre-of-mass correction
    const double T = measure_kinetics<D>(p, std::array<bool, D>{}).temperature();
    if (mobile == 0 || !(T > 0.0) || !(duration > 0.0)) return 0.0;
    const double n = static_cast<double>(p.size()) / box.volume();
    const double m = static_cast<double>(mobile);
    return duration * theory::enskog_collision_frequency(D, n, diameter / m, T, mass / m);
}

template <int D>
double suggested_time_step(const ParticleStore<D>& p, double max_move, double samples) {
    const double T = measure_kinetics<D>(p, std::array<bool, D>{}).temperature();
    const double tail = 2.0 * (std::log(std::max(samples, 1.0)) + 6.0);
    double best = std::numeric_limits<double>::infinity();
    for (std::size_t i = 0; i < p.size(); ++i) {
        const double m = p.mass(i);
        if (std::isinf(m)) continue;
        const double v = std::max(norm(p.velocity[i]), std::sqrt(tail * T / m));
        if (v > 0.0) best = std::min(best, p.radius(i) / v);
    }
    return round_down_two_digits(max_move * best);
}

template <int D>
void check_time_step(const ParticleStore<D>& p, double dt, double max_move,
                     const std::string& where, double samples) {
    const FastestParticle f = fastest_particle(p, dt);
    if (f.radii_per_step <= max_move) return;
    throw InputError(fmt::format(
        "{}: {:g} is too large: particle {} (species '{}') starts at speed {:.4g} and would move "
        "{:.3g} radii in one step, more than stepped.max_move = {:g}, so particles could pass "
        "through each other or a wall; use dt = {:.2g} or less",
        where, dt, p.tag[f.index], p.species_table[p.species[f.index]].name, f.speed,
        f.radii_per_step, max_move, suggested_time_step(p, max_move, samples)));
}

template FastestParticle fastest_particle(const ParticleStore<2>&, double);
template FastestParticle fastest_particle(const ParticleStore<3>&, double);
template double expected_collisions_per_particle(const ParticleStore<2>&, const Box<2>&, double);
template double expected_collisions_per_particle(const ParticleStore<3>&, const Box<3>&, double);
template double suggested_time_step(const ParticleStore<2>&, double, double);
template double suggested_time_step(const ParticleStore<3>&, double, double);
template void check_time_step(const ParticleStore<2>&, double, double, const std::string&, double);
template void check_time_step(const ParticleStore<3>&, double, double, const std::string&, double);

} // namespace pedesis
