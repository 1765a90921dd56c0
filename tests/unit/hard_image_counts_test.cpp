// Image counts of the event and stepped engines: unwrapped positions (position + image *
// L) are continuous paths. A free particle's unwrapped position is x0 + v t across many
// boxes; in a gas, no particle's unwrapped position jumps between two close instants,
// through collisions, list rebuilds and wraps; a checkpoint carries the counts, and one
// written before them (event version 4, stepped version 2) still loads, with none crossed.
#include "pedesis/core/error.hpp"
#include "pedesis/event/event_engine.hpp"
#include "pedesis/stepped/stepped_engine.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <cstring>
#include <random>
#include <sstream>
#include <string>
#include <vector>

using namespace pedesis;

namespace {

// n^3 spheres of radius 0.5 on a cubic lattice of spacing 1.5 (packing fraction 0.155),
// Maxwell velocities at T = 1 with zero total momentum.
ParticleStore<3> lattice_gas(int n, unsigned seed) {
    ParticleStore<3> p;
    p.species_table = {Species{"A", 0.5, 1.0}};
    std::mt19937_64 rng(seed);
    std::normal_distribution<double> gauss;
    Vec<3> total{};
    const double L = 1.5 * n;
    for (int i = 0; i < n; ++i)
        for (int j = 0; j < n; ++j)
            for (int k = 0; k < n; ++k) {
                p.position.push_back(Vec<3>{{1.5 * i - 0.5 * L + 0.75, 1.5 * j - 0.5 * L + 0.75,
                                             1.5 * k - 0.5 * L + 0.75}});
                const Vec<3> v{{gauss(rng), gauss(rng), gauss(rng)}};
                p.velocity.push_back(v);
                total += v;
                p.tag.push_back(static_cast<std::uint32_t>(p.tag.size()));
                p.species.push_back(0);
            }
    for (auto& v : p.velocity) v -= total * (1.0 / static_cast<double>(p.size()));
    return p;
}

double max_speed(const ParticleStore<3>& p) {
    double most = 0.0;
    for (const auto& v : p.velocity) most = std::max(most, norm(v));
    return most;
}

std::vector<Vec<3>> unwrapped_of(const ParticleStore<3>& p, const std::vector<ImageCount<3>>& img,
                                 const Box<3>& box) {
    return unwrapped_positions<3>(box, p.position, img);
}

// Between instants dt apart no particle moves further than the fastest speed the gas can
// have (all its kinetic energy in one particle) times dt; a missed or spurious crossing
// is a jump of a box length.
void expect_continuous(const std::vector<Vec<3>>& before, const std::vector<Vec<3>>& after,
                       double bound, const char* who, double t) {
    for (std::size_t i = 0; i < before.size(); ++i)
        ASSERT_LE(norm(after[i] - before[i]), bound)
            << who << ": particle " << i << " at t = " << t;
}

TEST(HardImageCounts, AFreeParticleCrossesManyBoxesOnAStraightLine) {
    ParticleStore<3> p;
    p.species_table = {Species{"A", 0.5, 1.0}};
    p.position = {Vec<3>{{0.1, -0.2, 0.3}}, Vec<3>{{2.6, 2.3, 2.8}}};
    p.velocity = {Vec<3>{{1.7, -0.9, 0.45}}, Vec<3>{{1.7, -0.9, 0.45}}}; // never meet
    p.tag = {0, 1};
    p.species = {0, 0};
    const Box<3> box(Vec<3>{{5.0, 5.0, 5.0}}, {true, true, true});
    const double t = 37.25;
    EventEngine<3> event(p, box, EventParams{});
    StopLimits limits;
    limits.time = t;
    event.run(limits);
    std::vector<ImageCount<3>> img;
    const ParticleStore<3> now = event.snapshot(&img);
    SteppedParams sp;
    sp.dt = 0.01;
    SteppedEngine<3> stepped(p, box, sp);
    while (stepped.steps() < 3725) stepped.step();
    for (std::size_t k = 0; k < 2; ++k) {
        const std::size_t i = now.tag[k]; // the event engine's storage order is its own
        const Vec<3> expected = p.position[i] + p.velocity[i] * t;
        const Vec<3> u = unwrapped<3>(box, now.position[k], img[k]);
        const Vec<3> us = unwrapped<3>(box, stepped.particles().position[i], stepped.images()[i]);
        for (int a = 0; a < 3; ++a) {
            EXPECT_NEAR(u[a], expected[a], 1e-9) << "event, axis " << a;
            EXPECT_NEAR(us[a], expected[a], 1e-9) << "stepped, axis " << a;
        }
        EXPECT_EQ(img[k][0], 13) << "63.4 / 5 boxes along x"; // 0.1 + 63.325 = 63.425
        EXPECT_EQ(img[k], event.image_now(k));
        const std::vector<Vec<3>> all = event.unwrapped_now();
        EXPECT_EQ(all[k][0], u[0]);
    }
}

TEST(HardImageCounts, EventGasPathsStayContinuousThroughCollisionsAndRebuilds) {
    const ParticleStore<3> p = lattice_gas(6, 11);
    const Box<3> box(Vec<3>{{9.0, 9.0, 9.0}}, {true, true, true});
    EventEngine<3> e(p, box, EventParams{});
    double energy = 0.0;
    for (const auto& v : p.velocity) energy += 0.5 * norm2(v);
    const double fastest = std::sqrt(2.0 * energy);
    std::vector<ImageCount<3>> img;
    ParticleStore<3> s = e.snapshot(&img);
    std::vector<Vec<3>> before = unwrapped_of(s, img, box);
    const double dt = 0.05;
    std::uint64_t crossings = 0;
    for (int k = 1; k <= 400; ++k) {
        StopLimits limits;
        limits.time = k * dt;
        e.run(limits);
        s = e.snapshot(&img);
        const std::vector<Vec<3>> after = unwrapped_of(s, img, box);
        expect_continuous(before, after, fastest * dt * (1 + 1e-12) + 1e-12, "event", k * dt);
        before = after;
        crossings = 0;
        for (const auto& c : img) crossings += std::abs(c[0]) + std::abs(c[1]) + std::abs(c[2]);
    }
    EXPECT_GT(e.counters().pair_collisions, 5000u);
    EXPECT_GT(crossings, 200u) << "the particles must cross the box's faces";
}

TEST(HardImageCounts, SteppedGasPathsStayContinuousThroughCollisions) {
    const ParticleStore<3> p = lattice_gas(6, 12);
    const Box<3> box(Vec<3>{{9.0, 9.0, 9.0}}, {true, true, true});
    SteppedParams sp;
    sp.dt = 0.1 / (4.0 * max_speed(p)); // max_move 0.5 radii at 4 times today's fastest
    SteppedEngine<3> e(p, box, sp);
    double energy = 0.0;
    for (const auto& v : p.velocity) energy += 0.5 * norm2(v);
    const double fastest = std::sqrt(2.0 * energy);
    std::vector<Vec<3>> before = unwrapped_of(e.particles(), e.images(), box);
    std::uint64_t crossings = 0;
    for (int k = 1; k <= 2000; ++k) {
        e.step();
        const std::vector<Vec<3>> after = unwrapped_of(e.particles(), e.images(), box);
        expect_continuous(before, after, fastest * sp.dt * (1 + 1e-12) + 1e-12, "stepped",
                          e.time());
        before = after;
    }
    for (const auto& c : e.images()) crossings += std::abs(c[0]) + std::abs(c[1]) + std::abs(c[2]);
    EXPECT_GT(e.counters().pair_collisions, 1000u);
    EXPECT_GT(crossings, 50u);
}

// A version-5 event checkpoint (version-3 stepped) ends with the image counts (a u64
// count and n D int32), a flag and the flux moments, and a later version (`saved`) with
// `later` bytes more (the shear state: event 6, five 8-byte numbers; event 7, gravity's
// D components, the two next stochastic event times and the four driving records, 8
// bytes each; stepped 4, the rate): without them all, and with the version before the
// counts, it is the file an older pedesis wrote.
constexpr std::size_t moments_bytes = 1 + sizeof(FluxMoments<3>);
std::string older_version(std::string bytes, std::uint32_t saved, std::size_t later,
                          std::uint32_t version, std::size_t n) {
    std::uint32_t v = 0;
    std::memcpy(&v, bytes.data() + 8, 4);
    EXPECT_EQ(v, saved);
    std::memcpy(bytes.data() + 8, &version, 4);
    const std::size_t tail = 8 + n * 3 * sizeof(std::int32_t) + moments_bytes + later;
    std::uint64_t count = 0;
    std::memcpy(&count, bytes.data() + bytes.size() - tail, 8);
    EXPECT_EQ(count, n);
    bytes.resize(bytes.size() - tail);
    return bytes;
}

TEST(HardImageCounts, CheckpointsCarryTheCountsAndOlderOnesLoadWithNone) {
    const ParticleStore<3> p = lattice_gas(5, 13);
    const Box<3> box(Vec<3>{{7.5, 7.5, 7.5}}, {true, true, true});
    EventEngine<3> e(p, box, EventParams{});
    StopLimits limits;
    limits.time = 3.0;
    e.run(limits);
    std::ostringstream out;
    e.save(out);
    std::istringstream in(out.str());
    EventEngine<3> same = EventEngine<3>::load(in, EventParams{});
    std::istringstream old_in(older_version(out.str(), 8, 40 + (3 + 2 + 4 + 2) * 8, 4, p.size()));
    EventEngine<3> old = EventEngine<3>::load(old_in, EventParams{});
    limits.time = 6.0;
    e.run(limits);
    same.run(limits);
    old.run(limits);
    std::vector<ImageCount<3>> a, b, c;
    const ParticleStore<3> sa = e.snapshot(&a), sb = same.snapshot(&b), sc = old.snapshot(&c);
    EXPECT_EQ(a, b);
    EXPECT_EQ(sa.position, sb.position);
    EXPECT_EQ(sa.position, sc.position) << "the older file continues the same trajectory";
    // the older file's counts start from its particles' stored positions: they differ
    // from the full counts by what was crossed before t = 3 (a box at most in 3 time units
    // at these speeds, within one of the stored positions' own wrap)
    bool any_crossed_before = false;
    for (std::size_t i = 0; i < p.size(); ++i)
        for (int k = 0; k < 3; ++k) {
            EXPECT_LE(std::abs(a[i][k] - c[i][k]), 3) << "particle " << i;
            any_crossed_before = any_crossed_before || a[i][k] != c[i][k];
        }
    EXPECT_TRUE(any_crossed_before);

    SteppedParams sp;
    sp.dt = 0.01;
    SteppedEngine<3> st(p, box, sp);
    while (st.steps() < 300) st.step();
    std::ostringstream sout;
    st.save(sout);
    std::istringstream sin(sout.str());
    SteppedEngine<3> ssame = SteppedEngine<3>::load(sin, sp);
    EXPECT_EQ(ssame.images(), st.images());
    std::istringstream sold_in(older_version(sout.str(), 4, 8, 2, p.size()));
    SteppedEngine<3> sold = SteppedEngine<3>::load(sold_in, sp);
    for (const auto& k : sold.images()) EXPECT_EQ(k, (ImageCount<3>{}));
    while (st.steps() < 600) {
        st.step();
        sold.step();
    }
    EXPECT_EQ(st.particles().position, sold.particles().position);
}

TEST(HardImageCounts, ACheckpointWithCorruptCountsIsRefused) {
    const ParticleStore<3> p = lattice_gas(4, 14);
    const Box<3> box(Vec<3>{{6.0, 6.0, 6.0}}, {true, true, true});
    EventEngine<3> e(p, box, EventParams{});
    std::ostringstream out;
    e.save(out);
    std::string bytes = out.str();
    const std::size_t tail = 8 + p.size() * 3 * sizeof(std::int32_t) + moments_bytes;
    const std::uint64_t wrong = p.size() - 1;
    std::memcpy(bytes.data() + bytes.size() - tail, &wrong, 8);
    bytes.resize(bytes.size() - moments_bytes - 12);
    std::istringstream in(bytes);
    EXPECT_THROW(EventEngine<3>::load(in, EventParams{}), InputError);
}

} // namespace
