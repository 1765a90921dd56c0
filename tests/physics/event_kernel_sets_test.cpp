// The event engine's predictions under every kernel set this CPU runs (core/
// simd_level.hpp): the AVX2 and AVX-512 sets scan a particle's neighbour list with a
// batch kernel (event/pair_times.hpp), four pairs per instruction, and must pick the
// partner and time the scalar loop (the sse2 set) picks, so that a run is the same to
// the last bit in every set: dense and dilute, 2D and 3D, periodic and walled, one size
// and two, elastic and inelastic, and a perfect lattice with equal speeds, where many
// pairs tie.
#include "pedesis/core/simd_level.hpp"
#include "pedesis/event/event_engine.hpp"
#include "support/gas_builder.hpp"

#include <gtest/gtest.h>

#include <bit>
#include <cstdint>
#include <string>
#include <vector>

using namespace pedesis;
using pedesis::test::same_bits;

namespace {

struct KernelSetGuard {
    SimdLevel saved = simd_level();
    ~KernelSetGuard() { set_simd_level(saved); }
};

template <int D> struct RunResult {
    std::uint64_t pair_collisions = 0, wall_collisions = 0;
    double kinetic = 0.0;
    ParticleStore<D> state;
};

template <int D>
RunResult<D> run_with(SimdLevel level, const test::Gas<D>& gas, const EventParams& params,
                      std::uint64_t collisions) {
    set_simd_level(level); // the engine takes its kernel when it is made
    EventEngine<D> e(gas.particles, gas.box, params);
    StopLimits lim;
    lim.pair_collisions = collisions;
    e.run(lim);
    return {e.counters().pair_collisions, e.counters().wall_collisions, e.kinetic_energy(),
            e.snapshot()};
}

template <int D>
void expect_every_set_runs_the_same(const test::GasSpec<D>& spec, const EventParams& params,
                                    const std::string& what) {
    SCOPED_TRACE(what);
    KernelSetGuard guard;
    const test::Gas<D> gas = test::make_gas(spec);
    const std::uint64_t collisions = 20 * gas.particles.size();
    const RunResult<D> reference = run_with(SimdLevel::sse2, gas, params, collisions);
    ASSERT_EQ(reference.pair_collisions, collisions) << "the run stopped early";
    for (const SimdLevel level : available_simd_levels()) {
        SCOPED_TRACE(simd_name(level));
        const RunResult<D> r = run_with(level, gas, params, collisions);
        EXPECT_EQ(r.pair_collisions, reference.pair_collisions);
        EXPECT_EQ(r.wall_collisions, reference.wall_collisions);
        EXPECT_EQ(std::bit_cast<std::uint64_t>(r.kinetic),
                  std::bit_cast<std::uint64_t>(reference.kinetic));
        std::size_t differ = 0;
        for (std::size_t i = 0; i < gas.particles.size(); ++i)
            differ += r.state.tag[i] != reference.state.tag[i] ||
                      !same_bits(r.state.position[i], reference.state.position[i]) ||
                      !same_bits(r.state.velocity[i], reference.state.velocity[i]);
        EXPECT_EQ(differ, 0u) << "particles whose position or velocity differ in a bit";
    }
}

TEST(EventKernelSets, DenseSpheres) {
    test::GasSpec<3> spec;
    spec.species = {test::SpeciesSpec{2048, 0.5, 1.0, -1.0}};
    spec.eta = 0.45;
    expect_every_set_runs_the_same(spec, EventParams{}, "3D, periodic, eta 0.45");
}

TEST(EventKernelSets, InelasticMixtureBetweenWalls) {
    test::GasSpec<3> spec;
    spec.species = {test::SpeciesSpec{600, 0.5, 1.0, -1.0}, test::SpeciesSpec{600, 0.3, 0.4, -1.0}};
    spec.eta = 0.3;
    spec.periodic = false;
    spec.placement = test::Placement::random;
    EventParams params;
    params.restitution = 0.8;
    params.wall_restitution = 0.9;
    expect_every_set_runs_the_same(spec, params, "3D mixture, walls, restitution 0.8");
}

TEST(EventKernelSets, DiskMixtures) {
    test::GasSpec<2> dense;
    dense.species = {test::SpeciesSpec{1500, 0.5, 1.0, -1.0},
                     test::SpeciesSpec{500, 0.35, 0.5, -1.0}};
    dense.eta = 0.70;
    expect_every_set_runs_the_same(dense, EventParams{}, "2D, periodic, eta 0.70");
    test::GasSpec<2> dilute = dense;
    dilute.eta = 0.05;
    dilute.periodic = false;
    dilute.placement = test::Placement::random;
    expect_every_set_runs_the_same(dilute, EventParams{}, "2D, walls, eta 0.05");
}

TEST(EventKernelSets, LatticeWithEqualSpeeds) {
    test::GasSpec<3> spec;
    spec.species = {test::SpeciesSpec{4 * 8 * 8 * 8, 0.5, 1.0, -1.0}};
    spec.eta = 0.40;
    spec.velocity = VelocityKind::equal_speed;
    expect_every_set_runs_the_same(spec, EventParams{}, "fcc, equal speeds");
}

} // namespace
