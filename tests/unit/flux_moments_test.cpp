// The running integrals of the Helfand moments (core/flux_moments.hpp) of both hard-particle
// engines against their definitions. While no particle crosses the box, unwrapped and
// stored positions agree and the moments are plain sums over the particles:
//   G_ab(t) − G_ab(0) = [Σ m v_a x_b]_0^t,  H_a(t) − H_a(0) = [Σ x_a m v² / 2]_0^t,
// exactly (to rounding) whatever happened in between: this checks the kinetic integrals
// between collisions and the collisional parts (the contact vector times Δp and ΔE).
// A cluster of spheres in the middle of a box too large for anyone to reach its faces.
#include "pedesis/event/event_engine.hpp"
#include "pedesis/stepped/stepped_engine.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <random>

using namespace pedesis;

namespace {

// 7^3 spheres (radius 0.5, masses 1 and 2.5) on a lattice of spacing 1.2 around the
// origin, Maxwell velocities at T = 1, in a periodic box of side 60.
ParticleStore<3> cluster() {
    ParticleStore<3> p;
    p.species_table = {Species{"A", 0.5, 1.0}, Species{"B", 0.5, 2.5}};
    std::mt19937_64 rng(5);
    std::normal_distribution<double> gauss;
    for (int i = 0; i < 7; ++i)
        for (int j = 0; j < 7; ++j)
            for (int k = 0; k < 7; ++k) {
                p.position.push_back(Vec<3>{{1.2 * (i - 3), 1.2 * (j - 3), 1.2 * (k - 3)}});
                const std::uint16_t s = (i + j + k) % 2;
                const double scale = s ? 1.0 / std::sqrt(2.5) : 1.0;
                p.velocity.push_back(Vec<3>{{gauss(rng), gauss(rng), gauss(rng)}} * scale);
                p.tag.push_back(static_cast<std::uint32_t>(p.tag.size()));
                p.species.push_back(s);
            }
    return p;
}

struct Moments {
    SymTensor g{};
    Vec<3> h{};
};

// Σ m v_a x_b (symmetrised, the slots of SymTensor) and Σ x e of a state.
Moments direct(const ParticleStore<3>& p) {
    Moments m;
    for (std::size_t i = 0; i < p.size(); ++i) {
        const double mass = p.mass(i);
        add_sym_outer<3>(m.g, p.velocity[i], p.position[i], mass);
        m.h += p.position[i] * (0.5 * mass * norm2(p.velocity[i]));
    }
    return m;
}

Moments from_engine(const FluxMoments<3>& f, const EventCounters<3>& c) {
    Moments m;
    for (int s = 0; s < 6; ++s) m.g[s] = f.kinetic_integral[s] + c.virial[s];
    m.h = f.heat_integral + f.heat_collisional;
    return m;
}

void expect_same_change(const Moments& engine0, const Moments& engine1, const Moments& direct0,
                        const Moments& direct1, const char* who) {
    for (int s = 0; s < 6; ++s) {
        const double want = direct1.g[s] - direct0.g[s];
        EXPECT_NEAR(engine1.g[s] - engine0.g[s], want, 1e-9 * (1.0 + std::abs(direct1.g[s])))
            << who << ", G slot " << s;
    }
    for (int a = 0; a < 3; ++a) {
        const double want = direct1.h[a] - direct0.h[a];
        EXPECT_NEAR(engine1.h[a] - engine0.h[a], want, 1e-9 * (1.0 + std::abs(direct1.h[a])))
            << who << ", H axis " << a;
    }
}

const Box<3> big_box(Vec<3>{{60.0, 60.0, 60.0}}, {true, true, true});

TEST(FluxMoments, EventEngineMomentsAreTheSumsOverParticles) {
    const ParticleStore<3> p = cluster();
    EventEngine<3> e(p, big_box, EventParams{});
    StopLimits limits;
    limits.time = 1.0; // moments from t = 1 on: a start that is not zero
    e.run(limits);
    e.track_flux_moments();
    const Moments engine0 = from_engine(e.flux_moments(), e.counters());
    const Moments direct0 = direct(e.snapshot());
    limits.time = 5.0;
    e.run(limits);
    const Moments engine1 = from_engine(e.flux_moments(), e.counters());
    const ParticleStore<3> now = e.snapshot();
    for (const auto& r : now.position)
        for (int a = 0; a < 3; ++a) ASSERT_LT(std::abs(r[a]), 29.0) << "a particle reached a face";
    EXPECT_GT(e.counters().pair_collisions, 500u);
    expect_same_change(engine0, engine1, direct0, direct(now), "event");
    // the kinetic integral's trace is 2 K t, K constant (elastic)
    const FluxMoments<3> f = e.flux_moments();
    EXPECT_NEAR(sym_trace<3>(f.kinetic) * 4.0, 2.0 * e.kinetic_energy() * 4.0,
                1e-9 * e.kinetic_energy());
}

TEST(FluxMoments, SteppedEngineMomentsAreTheSumsOverParticles) {
    const ParticleStore<3> p = cluster();
    SteppedParams sp;
    sp.dt = 0.005;
    SteppedEngine<3> e(p, big_box, sp);
    e.track_flux_moments();
    const Moments engine0 = from_engine(e.flux_moments(), e.counters());
    const Moments direct0 = direct(e.particles());
    while (e.steps() < 800) e.step();
    const Moments engine1 = from_engine(e.flux_moments(), e.counters());
    EXPECT_GT(e.counters().pair_collisions, 500u);
    expect_same_change(engine0, engine1, direct0, direct(e.particles()), "stepped");
}

TEST(FluxMoments, AFreeParticlesIntegralsAreItsVelocityProductsTimesTime) {
    FluxMoments<3> m;
    const Vec<3> v{{1.0, -2.0, 0.5}};
    m.count(2.0, v, 1.0);
    m.advance(3.0);
    EXPECT_DOUBLE_EQ(m.kinetic_integral[sym_slot(0, 1)], 2.0 * 1.0 * -2.0 * 3.0);
    EXPECT_DOUBLE_EQ(m.heat_integral[2], 0.5 * (0.5 * 2.0 * 5.25) * 3.0); // v_z e t
}

} // namespace
