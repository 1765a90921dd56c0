#include "pedesis/setup/velocities.hpp"

#include "pedesis/core/error.hpp"
#include "pedesis/core/rng.hpp"

#include <cmath>
#include <stdexcept>

namespace pedesis {

VelocityKind parse_velocity_kind(const std::string& name) {
    if (name == "zero") return VelocityKind::zero;
    if (name == "equal_speed") return VelocityKind::equal_speed;
    if (name == "uniform") return VelocityKind::uniform;
    if (name == "normal") return VelocityKind::normal;
    if (name == "maxwell_boltzmann") return VelocityKind::maxwell_boltzmann;
    throw InputError(
        "unknown velocity distribution '" + name +
        "' (use zero, equal_speed, uniform, normal, maxwell_boltzmann, or give velocity = [..])");
}

template <int D>
Vec<D> draw_velocity(const VelocitySpec& spec, double mass, std::uint64_t seed, std::uint32_t tag) {
    CounterRng rng(seed, RngStream::velocity, tag);
    Vec<D> v{};
    switch (spec.kind) {
    case VelocityKind::zero:
    case VelocityKind::given:
        break;
    case VelocityKind::equal_speed: {
        double n2 = 0.0;
        // an exact zero has probability 0; 64 in a row means a broken generator
        for (int draw = 0; draw < 64 && n2 == 0.0; ++draw) {
            for (int a = 0; a < D; ++a) v[a] = rng.normal();
            n2 = norm2(v);
        }
        if (n2 == 0.0) throw std::logic_error("velocities: 64 normal draws in a row of zero");
        v *= spec.speed / std::sqrt(n2);
        break;
    }
    case VelocityKind::uniform:
        for (int a = 0; a < D; ++a) v[a] = rng.uniform(-spec.speed, spec.speed);
        break;
    case VelocityKind::normal:
        for (int a = 0; a < D; ++a) v[a] = spec.sigma * rng.normal();
        break;
    case VelocityKind::maxwell_boltzmann: {
        const double s = std::isinf(mass) ? 0.0 : std::sqrt(spec.temperature / mass);
        for (int a = 0; a < D; ++a) v[a] = s * rng.normal();
        break;
    }
    }
    return v;
}

template <int D> void remove_drift(ParticleStore<D>& p, const std::vector<std::size_t>& which) {
    Vec<D> momentum{};
    double mass = 0.0;
    for (std::size_t i : which) {
        const double m = p.mass(i);
        if (std::isinf(m)) continue;
        momentum += m * p.velocity[i];
        mass += m;
    }
    if (mass == 0.0) return;
    const Vec<D> drift = momentum * (1.0 / mass);
    for (std::size_t i : which)
        if (!std::isinf(p.mass(i))) p.velocity[i] -= drift;
}

template <int D>
void rescale_temperature(ParticleStore<D>& p, const std::vector<std::size_t>& which, double T,
                         double removed_freedom) {
    double twice_kinetic = 0.0;
    std::size_t mobile = 0;
    for (std::size_t i : which) {
        const double m = p.mass(i);
        if (std::isinf(m)) continue;
        twice_kinetic += m * norm2(p.velocity[i]);
        ++mobile;
    }
    const double freedom = D * static_cast<double>(mobile) - removed_freedom;
    if (mobile == 0 || twice_kinetic == 0.0 || !(freedom > 0.0)) return;
    const double current = twice_kinetic / freedom;
    const double s = std::sqrt(T / current);
    for (std::size_t i : which) p.velocity[i] *= s;
}

template Vec<2> draw_velocity<2>(const VelocitySpec&, double, std::uint64_t, std::uint32_t);
template Vec<3> draw_velocity<3>(const VelocitySpec&, double, std::uint64_t, std::uint32_t);
template void remove_drift(ParticleStore<2>&, const std::vector<std::size_t>&);
template void remove_drift(ParticleStore<3>&, const std::vector<std::size_t>&);
template void rescale_temperature(ParticleStore<2>&, const std::vector<std::size_t>&, double,
                                  double);
template void rescale_temperature(ParticleStore<3>&, const std::vector<std::size_t>&, double,
                                  double);

} // namespace pedesis
