// Exact one- and two-body cases through the whole event engine (prediction, calendar,
// collision rule, counters), each compared with its closed-form answer to rounding.
#include "pedesis/core/error.hpp"
#include "pedesis/event/event_engine.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <vector>

using namespace pedesis;

namespace {

constexpr double pi = std::numbers::pi;

struct Body {
    std::uint16_t species;
    std::vector<double> r, v;
};

template <int D>
ParticleStore<D> bodies(const std::vector<Species>& table, const std::vector<Body>& list) {
    ParticleStore<D> p;
    p.species_table = table;
    p.resize(list.size());
    for (std::size_t i = 0; i < list.size(); ++i) {
        for (int a = 0; a < D; ++a) {
            p.position[i][a] = list[i].r[a];
            p.velocity[i][a] = list[i].v[a];
        }
        p.tag[i] = static_cast<std::uint32_t>(i);
        p.species[i] = list[i].species;
    }
    return p;
}

template <int D> Box<D> walled(double L) {
    std::array<bool, D> per{};
    return Box<D>(Vec<D>::filled(L), per);
}

template <int D> Box<D> periodic(double L) {
    std::array<bool, D> per;
    per.fill(true);
    return Box<D>(Vec<D>::filled(L), per);
}

template <int D>
EventEngine<D> run_to(ParticleStore<D> p, const Box<D>& box, double t, EventParams params = {}) {
    EventEngine<D> e(std::move(p), box, params);
    StopLimits lim;
    lim.time = t;
    e.run(lim);
    return e;
}

// Particle with storage index i in a snapshot (the engine may not reorder, but do not assume)
template <int D> std::size_t by_tag(const ParticleStore<D>& s, std::uint32_t tag) {
    for (std::size_t i = 0; i < s.size(); ++i)
        if (s.tag[i] == tag) return i;
    ADD_FAILURE() << "tag " << tag << " missing";
    return 0;
}

// angle between two vectors, accurate near 0 and pi
template <int D> double angle(const Vec<D>& a, const Vec<D>& b) {
    double cross2;
    if constexpr (D == 2) {
        const double c = a[0] * b[1] - a[1] * b[0];
        cross2 = c * c;
    } else {
        const double cx = a[1] * b[2] - a[2] * b[1], cy = a[2] * b[0] - a[0] * b[2],
                     cz = a[0] * b[1] - a[1] * b[0];
        cross2 = cx * cx + cy * cy + cz * cz;
    }
    return std::atan2(std::sqrt(cross2), dot(a, b));
}

// Scattering of a point of unit speed off a fixed (or very heavy) hard particle with
// contact distance R = r1 + r2 at impact parameter b along direction `perp`.
template <int D>
Vec<D> scatter(double b, double obstacle_mass, const Vec<D>& perp,
               Vec<D>* obstacle_velocity = nullptr) {
    const double r1 = 0.3, r2 = 0.7;
    std::vector<double> start(D, 0.0), zero(D, 0.0), v(D, 0.0);
    start[0] = -5.0;
    for (int a = 0; a < D; ++a) start[a] += b * perp[a];
    v[0] = 1.0;
    auto p = bodies<D>({Species{"probe", r1, 1.0}, Species{"target", r2, obstacle_mass}},
                       {Body{0, start, v}, Body{1, zero, zero}});
    auto e = run_to<D>(p, walled<D>(30.0), 12.0);
    EXPECT_EQ(e.counters().pair_collisions, 1u) << "b = " << b;
    EXPECT_EQ(e.counters().wall_collisions, 0u);
    const auto s = e.snapshot();
    if (obstacle_velocity) *obstacle_velocity = s.velocity[by_tag(s, 1)];
    return s.velocity[by_tag(s, 0)];
}

} // namespace

// ---- walls --------------------------------------------------------------------------

template <int D> void wall_period_case() {
    const double L = 10.0, r = 0.5, v0 = 0.7;
    std::vector<double> start = {1.3, -2.1, 3.4};
    start.resize(D);
    std::vector<double> v(D, v0);
    auto p = bodies<D>({Species{"A", r, 2.0}}, {Body{0, start, v}});
    // one period: the particle crosses the free length L - 2r twice along every axis
    const double period = 2.0 * (L - 2.0 * r) / v0;
    auto e = run_to<D>(p, walled<D>(L), period);
    const auto& c = e.counters();
    EXPECT_EQ(c.wall_collisions, static_cast<std::uint64_t>(2 * D)); // every wall once
    EXPECT_EQ(c.pair_collisions, 0u);
    const auto s = e.snapshot();
    for (int a = 0; a < D; ++a) {
        EXPECT_NEAR(s.position[0][a], start[a], 1e-12) << "axis " << a;
        EXPECT_NEAR(s.velocity[0][a], v0, 1e-12) << "axis " << a;
        // each wall received 2 m v0
        EXPECT_NEAR(c.wall_impulse[a][0], 2.0 * 2.0 * v0, 1e-12);
        EXPECT_NEAR(c.wall_impulse[a][1], 2.0 * 2.0 * v0, 1e-12);
    }
    EXPECT_EQ(c.energy_lost, 0.0);
    EXPECT_NEAR(e.kinetic_energy(), 0.5 * 2.0 * D * v0 * v0, 1e-14);
    EXPECT_DOUBLE_EQ(e.time(), period);

    // half a period later the particle is at the mirror image through the contact planes
    StopLimits lim;
    lim.time = 1.5 * period;
    e.run(lim);
    EXPECT_EQ(e.counters().wall_collisions, static_cast<std::uint64_t>(3 * D));
}

TEST(ExactWalls, SquareBoxPeriod2D) {
    wall_period_case<2>();
}
TEST(ExactWalls, CubeBoxPeriod3D) {
    wall_period_case<3>();
}

TEST(ExactWalls, InelasticWall) {
    // normal velocity -> -xi v, tangential unchanged, wall receives m (1 + xi) |v|
    auto p = bodies<2>({Species{"A", 0.5, 3.0}}, {Body{0, {0.0, 0.0}, {2.0, 0.5}}});
    EventParams params;
    params.wall_restitution = 0.25;
    auto e = run_to<2>(p, Box<2>(Vec<2>{{10.0, 100.0}}, {false, true}), 3.0, params);
    // hits x = 4.5 at t = 2.25, then moves back at 0.5
    const auto s = e.snapshot();
    EXPECT_EQ(e.counters().wall_collisions, 1u);
    EXPECT_NEAR(s.velocity[0][0], -0.5, 1e-15);
    EXPECT_NEAR(s.velocity[0][1], 0.5, 1e-15);
    EXPECT_NEAR(s.position[0][0], 4.5 - 0.5 * 0.75, 1e-12);
    EXPECT_NEAR(e.counters().wall_impulse[0][1], 3.0 * 1.25 * 2.0, 1e-12);
    EXPECT_EQ(e.counters().wall_impulse[0][0], 0.0);
    const double lost = 0.5 * 3.0 * (1.0 - 0.25 * 0.25) * 4.0;
    EXPECT_NEAR(e.counters().energy_lost, lost, 1e-12);
    EXPECT_NEAR(e.kinetic_energy(), 0.5 * 3.0 * (0.25 + 0.25), 1e-12);
}

// ---- head-on collisions --------------------------------------------------------------

template <int D> void head_on_case(double xi, const Vec<D>& dir) {
    SCOPED_TRACE("xi = " + std::to_string(xi));
    const Vec<D> u = dir * (1.0 / norm(dir));
    const double v1 = 1.3, v2 = -0.4;
    std::vector<double> r1(D), r2(D), w1(D), w2(D);
    for (int a = 0; a < D; ++a) {
        r1[a] = -2.0 * u[a];
        r2[a] = 2.0 * u[a];
        w1[a] = v1 * u[a];
        w2[a] = v2 * u[a];
    }
    auto p = bodies<D>({Species{"A", 0.5, 1.0}}, {Body{0, r1, w1}, Body{0, r2, w2}});
    EventParams params;
    params.restitution = xi;
    params.check_overlaps = true;
    // contact after the gap 3 closes at 1.7; run well past it
    const double t_hit = 3.0 / 1.7, t_end = 4.0;
    auto e = run_to<D>(p, periodic<D>(40.0), t_end, params);
    EXPECT_EQ(e.counters().pair_collisions, 1u);
    const auto s = e.snapshot();
    const Vec<D> a = s.velocity[by_tag(s, 0)], b = s.velocity[by_tag(s, 1)];
    const double after1 = xi == 1.0 ? v2 : 0.5 * (v1 + v2);
    const double after2 = xi == 1.0 ? v1 : 0.5 * (v1 + v2);
    for (int k = 0; k < D; ++k) {
        EXPECT_NEAR(a[k], after1 * u[k], 1e-12);
        EXPECT_NEAR(b[k], after2 * u[k], 1e-12);
    }
    // positions: contact at +-0.5 from the meeting point, then free flight
    const double meet = -2.0 + v1 * t_hit + 0.5; // contact point along u
    const Vec<D> ra = s.position[by_tag(s, 0)], rb = s.position[by_tag(s, 1)];
    for (int k = 0; k < D; ++k) {
        EXPECT_NEAR(ra[k], (meet - 0.5 + after1 * (t_end - t_hit)) * u[k], 1e-12);
        EXPECT_NEAR(rb[k], (meet + 0.5 + after2 * (t_end - t_hit)) * u[k], 1e-12);
    }
    const double mu = 0.5, g = v1 - v2;
    EXPECT_NEAR(e.counters().energy_lost, 0.5 * mu * g * g * (1.0 - xi * xi), 1e-14);
    // virial: J sigma with J = (1 + xi) mu g
    double vir = 0.0;
    for (int k = 0; k < D; ++k) vir += e.counters().virial[k];
    EXPECT_NEAR(vir, (1.0 + xi) * mu * g * 1.0, 1e-12);
    EXPECT_GT(vir, 0.0); // excess pressure is positive
    e.check_no_overlap();
}

TEST(ExactHeadOn, ElasticSwapsVelocities2D) {
    head_on_case<2>(1.0, Vec<2>{{1.0, 0.0}});
    head_on_case<2>(1.0, Vec<2>{{0.3, -0.8}});
}
TEST(ExactHeadOn, ElasticSwapsVelocities3D) {
    head_on_case<3>(1.0, Vec<3>{{0.0, 0.0, 1.0}});
    head_on_case<3>(1.0, Vec<3>{{0.3, -0.8, 0.5}});
}
TEST(ExactHeadOn, PerfectlyInelasticGivesCentreOfMassVelocity2D) {
    head_on_case<2>(0.0, Vec<2>{{1.0, 0.0}});
    head_on_case<2>(0.0, Vec<2>{{-0.6, 0.2}});
}
TEST(ExactHeadOn, PerfectlyInelasticGivesCentreOfMassVelocity3D) {
    head_on_case<3>(0.0, Vec<3>{{0.0, 1.0, 0.0}});
    head_on_case<3>(0.0, Vec<3>{{0.7, 0.2, -0.4}});
}

// ---- scattering off a fixed or very heavy particle -----------------------------------

TEST(ExactScattering, RightAngleOffFixedObstacle) {
    const double R = 1.0; // 0.3 + 0.7
    const Vec<2> out = scatter<2>(R / std::sqrt(2.0), INFINITY, Vec<2>{{0.0, 1.0}});
    // a unit-speed probe leaves straight "up" (away from the obstacle), speed unchanged
    EXPECT_NEAR(out[0], 0.0, 1e-12);
    EXPECT_NEAR(out[1], 1.0, 1e-12);
    EXPECT_NEAR(angle(Vec<2>{{1.0, 0.0}}, out), pi / 2, 1e-12);
}

TEST(ExactScattering, RightAngleOffVeryHeavyParticle) {
    const double R = 1.0;
    Vec<2> recoil;
    const Vec<2> out = scatter<2>(R / std::sqrt(2.0), 1e12, Vec<2>{{0.0, 1.0}}, &recoil);
    EXPECT_NEAR(angle(Vec<2>{{1.0, 0.0}}, out), pi / 2, 1e-9);
    EXPECT_NEAR(norm(out), 1.0, 1e-9);
    // the heavy particle recoils by about 2 m/M along the line of centres
    EXPECT_GT(norm(recoil), 0.0);
    EXPECT_LT(norm(recoil), 1e-11);
    Vec<3> recoil3;
    const Vec<3> out3 = scatter<3>(R / std::sqrt(2.0), 1e12, Vec<3>{{0.0, 0.6, 0.8}}, &recoil3);
    EXPECT_NEAR(angle(Vec<3>{{1.0, 0.0, 0.0}}, out3), pi / 2, 1e-9);
}

template <int D> void sweep_case(const Vec<D>& perp) {
    const double R = 1.0;
    Vec<D> in{};
    in[0] = 1.0;
    for (int k = 0; k <= 40; ++k) {
        const double b = R * 0.99 * k / 40.0;
        const Vec<D> out = scatter<D>(b, INFINITY, perp);
        const double theta = angle(in, out);
        EXPECT_NEAR(theta, pi - 2.0 * std::asin(b / R), 1e-9) << "b = " << b;
        EXPECT_NEAR(norm(out), 1.0, 1e-12);
        // the probe is deflected within the plane of incidence, away from the obstacle
        if (k > 0) {
            EXPECT_GT(dot(out, perp), 0.0);
        }
    }
    // b > R: no collision at all
    std::vector<double> start(D, 0.0), zero(D, 0.0), v(D, 0.0);
    start[0] = -5.0;
    for (int a = 0; a < D; ++a) start[a] += 1.01 * R * perp[a];
    v[0] = 1.0;
    auto p = bodies<D>({Species{"probe", 0.3, 1.0}, Species{"target", 0.7, INFINITY}},
                       {Body{0, start, v}, Body{1, zero, zero}});
    auto e = run_to<D>(p, walled<D>(30.0), 12.0);
    EXPECT_EQ(e.counters().pair_collisions, 0u);
}

TEST(ExactScattering, AngleSweep2D) {
    sweep_case<2>(Vec<2>{{0.0, 1.0}});
}
TEST(ExactScattering, AngleSweep3D) {
    sweep_case<3>(Vec<3>{{0.0, 0.6, -0.8}});
}

// ---- unequal masses: conservation and the closed-form result ---------------------------

template <int D> void unequal_mass_case() {
    const double m1 = 1.0, m2 = 3.7, r1 = 0.4, r2 = 0.65;
    std::vector<double> x1 = {-2.0, 0.3, -0.1}, x2 = {1.0, 0.0, 0.2};
    std::vector<double> w1 = {1.5, 0.1, 0.05}, w2 = {-0.5, 0.02, -0.03};
    x1.resize(D), x2.resize(D), w1.resize(D), w2.resize(D);
    auto p = bodies<D>({Species{"light", r1, m1}, Species{"heavy", r2, m2}},
                       {Body{0, x1, w1}, Body{1, x2, w2}});

    // closed form in long double: contact time, normal, post-collision velocities
    using ld = long double;
    ld dr[3], dv[3];
    ld b = 0, dv2 = 0, dr2 = 0;
    for (int a = 0; a < D; ++a) {
        dr[a] = static_cast<ld>(x1[a]) - x2[a];
        dv[a] = static_cast<ld>(w1[a]) - w2[a];
        b += dr[a] * dv[a];
        dv2 += dv[a] * dv[a];
        dr2 += dr[a] * dr[a];
    }
    const ld sig = r1 + r2;
    const ld tc = (-b - std::sqrt(b * b - dv2 * (dr2 - sig * sig))) / dv2;
    ld n[3], g = 0;
    for (int a = 0; a < D; ++a) {
        n[a] = (dr[a] + dv[a] * tc) / sig;
        g += dv[a] * n[a];
    }
    const ld J = -2.0L * g * (m1 * m2) / (m1 + m2);

    auto e = run_to<D>(p, periodic<D>(30.0), 5.0);
    ASSERT_EQ(e.counters().pair_collisions, 1u);
    ASSERT_LT(tc, 5.0L);
    const auto s = e.snapshot();
    const Vec<D> u1 = s.velocity[by_tag(s, 0)], u2 = s.velocity[by_tag(s, 1)];
    for (int a = 0; a < D; ++a) {
        EXPECT_NEAR(u1[a], static_cast<double>(w1[a] + J * n[a] / m1), 1e-12);
        EXPECT_NEAR(u2[a], static_cast<double>(w2[a] - J * n[a] / m2), 1e-12);
    }
    // conservation in one collision, to rounding
    double pscale = 0.0, e0 = 0.0, e1 = 0.0;
    for (int a = 0; a < D; ++a) {
        pscale += m1 * std::abs(w1[a]) + m2 * std::abs(w2[a]);
        e0 += 0.5 * (m1 * w1[a] * w1[a] + m2 * w2[a] * w2[a]);
        e1 += 0.5 * (m1 * u1[a] * u1[a] + m2 * u2[a] * u2[a]);
    }
    for (int a = 0; a < D; ++a) {
        const double before = m1 * w1[a] + m2 * w2[a], after = m1 * u1[a] + m2 * u2[a];
        EXPECT_NEAR(after, before, 1e-14 * pscale) << "axis " << a;
    }
    EXPECT_NEAR(e1, e0, 1e-14 * e0);
    EXPECT_NEAR(e.kinetic_energy(), e0, 1e-14 * e0);
    // virial of one collision: J n . r_ij = J sigma
    double vir = 0.0;
    for (int a = 0; a < D; ++a) vir += e.counters().virial[a];
    EXPECT_NEAR(vir, static_cast<double>(J * sig), 1e-12);
}

TEST(ExactUnequalMasses, ConserveMomentumAndEnergy2D) {
    unequal_mass_case<2>();
}
TEST(ExactUnequalMasses, ConserveMomentumAndEnergy3D) {
    unequal_mass_case<3>();
}

TEST(ExactObstacle, FixedParticleNeverMovesAndAbsorbsNoEnergy) {
    // a probe bouncing between a fixed post and a wall: elastic, the post stays put
    auto p = bodies<2>({Species{"probe", 0.5, 1.0}, Species{"post", 1.0, INFINITY}},
                       {Body{0, {-3.0, 0.0}, {1.0, 0.0}}, Body{1, {0.0, 0.0}, {0.0, 0.0}}});
    auto e = run_to<2>(p, walled<2>(10.0), 100.0);
    const auto s = e.snapshot();
    EXPECT_EQ(s.position[by_tag(s, 1)], (Vec<2>{{0.0, 0.0}}));
    EXPECT_EQ(norm2(s.velocity[by_tag(s, 1)]), 0.0);
    // gap 1.5 each way between x = -4.5 (wall contact) and x = -1.5 (post contact)
    EXPECT_NEAR(e.kinetic_energy(), 0.5, 1e-14);
    EXPECT_NEAR(norm(s.velocity[by_tag(s, 0)]), 1.0, 1e-14);
    // period 6 (free path 3 there and back): post hits at t = 1.5 + 6k, wall hits at 4.5 + 6k
    EXPECT_EQ(e.counters().pair_collisions, 17u);
    EXPECT_EQ(e.counters().wall_collisions, 16u);
}
