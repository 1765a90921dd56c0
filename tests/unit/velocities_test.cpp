// Initial velocities: equal_speed gives exactly equal speeds, Maxwell-Boltzmann plus
// rescale gives exactly T, remove_drift gives zero momentum (obstacles left at rest),
// draws are keyed by (seed, tag) only; plus a loose check of the MB moments.
#include "pedesis/core/error.hpp"
#include "pedesis/setup/velocities.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <numeric>

using namespace pedesis;

namespace {

template <int D>
ParticleStore<D> store(std::size_t n, const VelocitySpec& spec, std::uint64_t seed,
                       bool with_obstacle = false) {
    ParticleStore<D> p;
    p.species_table = {Species{"light", 0.5, 1.0}, Species{"heavy", 0.5, 7.5},
                       Species{"wall", 0.5, INFINITY}};
    p.resize(n);
    for (std::size_t i = 0; i < n; ++i) {
        p.tag[i] = static_cast<std::uint32_t>(i);
        p.species[i] = static_cast<std::uint16_t>(i % 2);
        if (with_obstacle && i % 10 == 9) p.species[i] = 2;
        p.velocity[i] = draw_velocity<D>(spec, p.mass(i), seed, p.tag[i]);
    }
    return p;
}

std::vector<std::size_t> all(std::size_t n) {
    std::vector<std::size_t> v(n);
    std::iota(v.begin(), v.end(), std::size_t{0});
    return v;
}

template <int D> double temperature(const ParticleStore<D>& p) {
    double s = 0.0;
    std::size_t k = 0;
    for (std::size_t i = 0; i < p.size(); ++i) {
        if (std::isinf(p.mass(i))) continue;
        s += p.mass(i) * norm2(p.velocity[i]);
        ++k;
    }
    return s / (D * static_cast<double>(k));
}

template <int D> Vec<D> momentum(const ParticleStore<D>& p, double& scale) {
    Vec<D> m{};
    scale = 0.0;
    for (std::size_t i = 0; i < p.size(); ++i) {
        if (std::isinf(p.mass(i))) continue;
        m += p.mass(i) * p.velocity[i];
        scale += p.mass(i) * norm(p.velocity[i]);
    }
    return m;
}

template <int D> void equal_speed_case() {
    VelocitySpec spec;
    spec.kind = VelocityKind::equal_speed;
    spec.speed = 1.7;
    auto p = store<D>(2000, spec, 42);
    for (std::size_t i = 0; i < p.size(); ++i) EXPECT_NEAR(norm(p.velocity[i]), 1.7, 1.7 * 1e-15);
    // directions are isotropic: mean of each component ~ 0 (5 standard errors)
    for (int a = 0; a < D; ++a) {
        double s = 0.0;
        for (const auto& v : p.velocity) s += v[a];
        const double se = 1.7 / std::sqrt(D * 2000.0);
        EXPECT_LT(std::abs(s / 2000.0), 5.0 * se);
    }
}

template <int D> void maxwell_case() {
    VelocitySpec spec;
    spec.kind = VelocityKind::maxwell_boltzmann;
    spec.temperature = 2.5;
    const std::size_t n = 4000;
    auto p = store<D>(n, spec, 7, true);
    // raw draws: <m v_a^2> = T per component for each species, within 5 standard errors
    // (m v_a^2 / T is chi-squared with one degree of freedom: variance 2)
    for (int s = 0; s < 2; ++s) {
        double sum = 0.0;
        std::size_t k = 0;
        for (std::size_t i = 0; i < n; ++i)
            if (p.species[i] == s)
                for (int a = 0; a < D; ++a, ++k)
                    sum += p.mass(i) * p.velocity[i][a] * p.velocity[i][a];
        EXPECT_NEAR(sum / k / 2.5, 1.0, 5.0 * std::sqrt(2.0 / k)) << "species " << s;
    }
    // obstacles are drawn at rest
    for (std::size_t i = 0; i < n; ++i)
        if (p.species[i] == 2) {
            EXPECT_EQ(norm2(p.velocity[i]), 0.0);
        }

    remove_drift(p, all(n));
    double scale = 0.0;
    const Vec<D> P = momentum(p, scale);
    for (int a = 0; a < D; ++a) EXPECT_LT(std::abs(P[a]), 1e-13 * scale);
    for (std::size_t i = 0; i < n; ++i)
        if (p.species[i] == 2) {
            EXPECT_EQ(norm2(p.velocity[i]), 0.0);
        }

    rescale_temperature(p, all(n), 2.5);
    EXPECT_NEAR(temperature(p), 2.5, 2.5 * 1e-14);
    // rescaling keeps the momentum zero
    const Vec<D> P2 = momentum(p, scale);
    for (int a = 0; a < D; ++a) EXPECT_LT(std::abs(P2[a]), 1e-13 * scale);

    // a subset only: the others are untouched
    auto q = p;
    std::vector<std::size_t> evens;
    for (std::size_t i = 0; i < n; i += 2) evens.push_back(i);
    rescale_temperature(q, evens, 0.5);
    for (std::size_t i = 1; i < n; i += 2) EXPECT_EQ(q.velocity[i], p.velocity[i]);
    double s = 0.0;
    for (std::size_t i : evens) s += q.mass(i) * norm2(q.velocity[i]);
    EXPECT_NEAR(s / (D * evens.size()), 0.5, 0.5 * 1e-14);
}

} // namespace

TEST(Velocities, EqualSpeed2D) {
    equal_speed_case<2>();
}
TEST(Velocities, EqualSpeed3D) {
    equal_speed_case<3>();
}
TEST(Velocities, MaxwellRescaleAndDrift2D) {
    maxwell_case<2>();
}
TEST(Velocities, MaxwellRescaleAndDrift3D) {
    maxwell_case<3>();
}

TEST(Velocities, KeyedBySeedAndTagOnly) {
    VelocitySpec spec;
    spec.kind = VelocityKind::maxwell_boltzmann;
    const auto a = draw_velocity<3>(spec, 1.0, 5, 17);
    const auto b = draw_velocity<3>(spec, 1.0, 5, 17);
    EXPECT_EQ(a, b);
    EXPECT_NE(a, draw_velocity<3>(spec, 1.0, 5, 18));
    EXPECT_NE(a, draw_velocity<3>(spec, 1.0, 6, 17));
    // mass only scales the draw
    const auto c = draw_velocity<3>(spec, 4.0, 5, 17);
    for (int k = 0; k < 3; ++k) EXPECT_NEAR(c[k], 0.5 * a[k], 1e-15);
}

TEST(Velocities, ZeroAndUniformAndNormal) {
    VelocitySpec spec;
    spec.kind = VelocityKind::zero;
    EXPECT_EQ(norm2(draw_velocity<2>(spec, 1.0, 1, 1)), 0.0);
    spec.kind = VelocityKind::uniform;
    spec.speed = 0.3;
    for (std::uint32_t t = 0; t < 1000; ++t) {
        const auto v = draw_velocity<3>(spec, 1.0, 1, t);
        for (int k = 0; k < 3; ++k) EXPECT_LE(std::abs(v[k]), 0.3);
    }
    EXPECT_EQ(parse_velocity_kind("equal_speed"), VelocityKind::equal_speed);
    EXPECT_THROW(parse_velocity_kind("maxwell"), InputError);
}

TEST(Velocities, RescaleAndDriftLeaveAllObstaclesAlone) {
    ParticleStore<2> p;
    p.species_table = {Species{"wall", 0.5, INFINITY}};
    p.resize(3);
    remove_drift(p, all(3));
    rescale_temperature(p, all(3), 1.0);
    for (const auto& v : p.velocity) {
        EXPECT_TRUE(all_finite(v));
        EXPECT_EQ(norm2(v), 0.0);
    }
}
