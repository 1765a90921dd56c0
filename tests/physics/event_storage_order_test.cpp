// The event engine stores a fresh start along a space-filling curve (Hilbert in 2D,
// Morton in 3D; ties by tag). So the order the particles come in must not matter: the
// same particles handed over in lattice order and shuffled give the same trajectory to
// the last bit (compared by tag, counters included). And the storage must be local:
// particles in contact lie close in memory even when the input order was random.
#include "pedesis/event/event_engine.hpp"
#include "pedesis/setup/lattice.hpp"
#include "pedesis/setup/velocities.hpp"
#include "support/gas_builder.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <bit>
#include <cstdint>
#include <random>
#include <string>
#include <vector>

using namespace pedesis;
using pedesis::test::same_bits;

namespace {

// A gas on a lattice (fcc or hexagonal) with Maxwell-Boltzmann velocities; with
// `mixture`, every third particle is a smaller species (radius ratio 0.6).
template <int D>
ParticleStore<D> lattice_gas(const Box<D>& box, std::size_t n, double radius, bool mixture) {
    ParticleStore<D> p;
    p.species_table = {Species{"A", radius, 1.0}, Species{"B", 0.6 * radius, 0.5}};
    p.resize(n);
    Vec<D> lo, hi;
    std::array<bool, D> closed;
    for (int a = 0; a < D; ++a) {
        closed[a] = !box.periodic(a);
        const double inset = closed[a] ? radius : 0.0;
        lo[a] = box.lo(a) + inset;
        hi[a] = box.hi(a) - inset;
    }
    p.position =
        lattice_sites<D>(D == 2 ? LatticeKind::hexagonal : LatticeKind::fcc, lo, hi, closed, n);
    VelocitySpec vs;
    vs.kind = VelocityKind::maxwell_boltzmann;
    vs.temperature = 1.0;
    for (std::size_t i = 0; i < n; ++i) {
        p.tag[i] = static_cast<std::uint32_t>(i);
        p.species[i] = mixture && i % 3 == 2 ? 1 : 0;
        p.velocity[i] = draw_velocity<D>(vs, p.species_table[p.species[i]].mass, 7, p.tag[i]);
    }
    return p;
}

template <int D> ParticleStore<D> shuffled(ParticleStore<D> p, std::uint64_t seed) {
    std::vector<std::uint32_t> order(p.size());
    for (std::size_t i = 0; i < order.size(); ++i) order[i] = static_cast<std::uint32_t>(i);
    std::shuffle(order.begin(), order.end(), std::mt19937_64(seed));
    p.apply_order(order);
    return p;
}

template <int D>
void expect_same_trajectory(const Box<D>& box, const ParticleStore<D>& p, double run_time) {
    EventEngine<D> a(p, box, EventParams{});
    EventEngine<D> b(shuffled(p, 11), box, EventParams{});
    StopLimits lim;
    lim.time = run_time;
    a.run(lim);
    b.run(lim);
    ASSERT_GT(a.counters().pair_collisions, 10 * p.size()) << "too short a run to tell";
    EXPECT_EQ(a.counters().pair_collisions, b.counters().pair_collisions);
    EXPECT_EQ(std::bit_cast<std::uint64_t>(a.kinetic_energy()),
              std::bit_cast<std::uint64_t>(b.kinetic_energy()));
    const auto sa = a.snapshot(), sb = b.snapshot();
    const auto ia = sa.index_of_tags(), ib = sb.index_of_tags();
    std::size_t differ = 0;
    for (std::size_t t = 0; t < p.size(); ++t)
        differ += !same_bits(sa.position[ia[t]], sb.position[ib[t]]) ||
                  !same_bits(sa.velocity[ia[t]], sb.velocity[ib[t]]);
    EXPECT_EQ(differ, 0u) << "particles whose position or velocity differ in a bit";
}

TEST(EventStorageOrder, TrajectoryDoesNotDependOnTheInputOrder3D) {
    const Box<3> box(Vec<3>::filled(15.3), {true, true, true}); // packing fraction 0.30
    expect_same_trajectory(box, lattice_gas(box, 2048, 0.5, false), 8.0);
}

TEST(EventStorageOrder, TrajectoryDoesNotDependOnTheInputOrderMixtureWithWalls2D) {
    const Box<2> box(Vec<2>{{50.0, 46.0}}, {false, true});
    expect_same_trajectory(box, lattice_gas(box, 1600, 0.5, true), 12.0);
}

// lazy_particles() is a copy the engine fills from its per-particle records when asked:
// after a run its velocities, tags and species must be those of the moment (as the
// snapshot has them), and each position the snapshot's taken back along its velocity to
// the particle's own time, between 0 and now. Asked again after more collisions, it must
// not hand back the earlier copy.
template <int D> void expect_lazy_particles_current(EventEngine<D>& e, double until) {
    StopLimits lim;
    lim.time = until;
    e.run(lim);
    const ParticleStore<D>& lazy = e.lazy_particles();
    const ParticleStore<D> now = e.snapshot();
    ASSERT_EQ(lazy.size(), e.size());
    ASSERT_EQ(lazy.tag, now.tag);
    ASSERT_EQ(lazy.species, now.species);
    std::size_t wrong_velocity = 0, off_line = 0, out_of_time = 0;
    for (std::size_t i = 0; i < e.size(); ++i) {
        wrong_velocity += !same_bits(lazy.velocity[i], now.velocity[i]);
        const Vec<D> v = lazy.velocity[i];
        const Vec<D> d = e.box().minimum_image(now.position[i] - lazy.position[i]);
        const double v2 = norm2(v);
        const double tau = v2 > 0.0 ? dot(d, v) / v2 : 0.0; // how long ago it was there
        off_line += norm(d - v * tau) > 1e-9 * (1.0 + norm(d));
        out_of_time += !(tau >= -1e-12 && tau <= e.time() * (1.0 + 1e-12));
    }
    EXPECT_EQ(wrong_velocity, 0u) << "at t = " << e.time();
    EXPECT_EQ(off_line, 0u) << "lazy positions not on the line back from the present ones";
    EXPECT_EQ(out_of_time, 0u) << "lazy positions from before the start or after now";
}

TEST(EventStorageOrder, LazyParticlesAreTheRecordsOfTheMoment3D) {
    const Box<3> box(Vec<3>::filled(15.3), {true, true, true});
    EventEngine<3> e(lattice_gas(box, 2048, 0.5, false), box, EventParams{});
    expect_lazy_particles_current(e, 1.0);
    const auto first = e.lazy_particles().velocity;
    expect_lazy_particles_current(e, 2.0);
    std::size_t changed = 0;
    for (std::size_t i = 0; i < first.size(); ++i)
        changed += !same_bits(first[i], e.lazy_particles().velocity[i]);
    EXPECT_GT(changed, first.size() / 2) << "most particles collide in one time unit";
}

TEST(EventStorageOrder, LazyParticlesAreTheRecordsOfTheMomentMixtureWithWalls2D) {
    const Box<2> box(Vec<2>{{50.0, 46.0}}, {false, true});
    EventEngine<2> e(lattice_gas(box, 1600, 0.5, true), box, EventParams{});
    expect_lazy_particles_current(e, 1.5);
    expect_lazy_particles_current(e, 3.0);
}

// Contacts of a shuffled 3D start: with the curve's order, the median distance in
// storage between touching particles is a few dozen places; in random order it would be
// about N / 3.
TEST(EventStorageOrder, NeighboursAreStoredNearEachOther) {
    const Box<3> box(Vec<3>::filled(24.0), {true, true, true});
    const std::size_t n = 4 * 16 * 16 * 16; // fcc, nearest-neighbour distance 1.06
    const EventEngine<3> e(shuffled(lattice_gas(box, n, 0.5, false), 5), box, EventParams{});
    const auto& p = e.lazy_particles();
    std::vector<std::size_t> gaps;
    for (std::size_t i = 0; i < n; ++i)
        for (std::size_t j = i + 1; j < n; ++j)
            if (norm2(box.minimum_image(p.position[i] - p.position[j])) < 1.1 * 1.1)
                gaps.push_back(j - i);
    ASSERT_EQ(gaps.size(), 6 * n); // 12 contacts each
    std::nth_element(gaps.begin(), gaps.begin() + gaps.size() / 2, gaps.end());
    EXPECT_LT(gaps[gaps.size() / 2], n / 50) << "median storage distance of touching pairs";
}

} // namespace
