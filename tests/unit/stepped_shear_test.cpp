// Lees-Edwards shear in the stepped engine, against results worked out by hand and exact
// balances: a free particle crossing the sliding face lands where the offset puts it, with
// its peculiar velocity; two particles meet across the face in the step that holds the
// moment their images touch, and leave it with the velocities of a collision at exact
// contact; the energy the flow feeds in, -rate G_xy, is exactly the change of the peculiar
// kinetic energy (the kinetic stress integrated exactly within the steps, walls on z
// included); no pair overlaps at the end of a step in dense, strongly sheared gases (a
// brute-force scan of every pair and image); a checkpoint continues bit for bit; a rate
// whose flow alone outruns max_move is refused.
#include "support/sheared_gas.hpp"

#include "pedesis/core/error.hpp"
#include "pedesis/stepped/stepped_engine.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <limits>
#include <random>
#include <sstream>
#include <string>

using namespace pedesis;

namespace {

SteppedParams params_with(double dt) {
    SteppedParams p;
    p.dt = dt;
    return p;
}

TEST(SteppedShear, AFreeParticleCrossingTheSlidingFaceLandsWhereTheOffsetPutsIt) {
    // x = 0, y = 4.5 in a 10 x 10 box at rate 0.2; peculiar velocity (0.3, 1): the
    // laboratory velocity is (1.2, 1). At t = 2 the straight flight is at (2.4, 6.5), past
    // the top face: y wraps to -3.5 and x moves back by the offset 0.2 * 10 * 2 = 4, to
    // -1.6; the laboratory v_x loses 0.2 * 10 = 2, so the peculiar v_x is
    // -0.8 - 0.2 * (-3.5) = -0.1 (as just before the face: 1.2 - 0.2 * 6.5).
    ParticleStore<2> p;
    p.species_table = {Species{"A", 0.5, 1.0}};
    p.position = {Vec<2>{{0.0, 4.5}}};
    p.velocity = {Vec<2>{{0.3, 1.0}}};
    p.tag = {0};
    p.species = {0};
    SteppedEngine<2> e(p, test::sheared_box<2>(10.0, 0.2), params_with(0.01));
    for (int k = 0; k < 200; ++k) e.step();
    ASSERT_DOUBLE_EQ(e.time(), 2.0);
    const ParticleStore<2>& s = e.particles();
    EXPECT_NEAR(s.position[0][0], -1.6, 1e-12);
    EXPECT_NEAR(s.position[0][1], -3.5, 1e-12);
    EXPECT_NEAR(s.velocity[0][0], -0.1, 1e-12);
    EXPECT_NEAR(s.velocity[0][1], 1.0, 1e-12);
    EXPECT_NEAR(e.velocity(0)[0], -0.1 + 0.2 * -3.5, 1e-12); // inside: the laboratory's
    EXPECT_NEAR(e.box().shear_offset(), 4.0, 1e-12);
    EXPECT_NEAR(e.kinetic_energy(), 0.5 * (0.01 + 1.0), 1e-12);
    EXPECT_EQ(e.images()[0][1], 1);
}

// A at (0, 4.55) and B at (-3, -4.55), at rest in the flow in a 10 x 10 box at rate 0.1.
// B's image above, at height 5.45, drifts along x relative to A at 0.1 * 0.9 = 0.09 from
// -3; contact (a distance 1 at a height difference 0.9) comes when it is sqrt(0.19) short
// of A: at t* = (3 - sqrt(0.19)) / 0.09 = 28.49... There r_A - r_image = (s, -0.9) with
// s = sqrt(0.19), the relative velocity is (-0.09, 0), and the elastic collision gives A
// 0.09 s (s, -0.9) (B the opposite): the laboratory velocities after it are those plus
// the flow's +-0.455, whatever the step, if the rewind found the exact contact.
template <int D> void expect_meeting_across_the_face(const Vec<D>& a, const Vec<D>& b, int sign) {
    const double dt = 0.05, t_star = (3.0 - std::sqrt(0.19)) / 0.09, s = std::sqrt(0.19);
    SteppedEngine<D> e(test::particle_pair<D>(a, b), test::sheared_box<D>(10.0, 0.1),
                       params_with(dt));
    while (e.counters().pair_collisions == 0 && e.time() < 40.0) e.step();
    ASSERT_EQ(e.counters().pair_collisions, 1u);
    // the step that holds t*
    EXPECT_EQ(e.steps(), static_cast<std::uint64_t>(std::ceil(t_star / dt)));
    const double kick = 0.09 * s;
    EXPECT_NEAR(e.velocity(0)[0], sign * (0.455 + kick * s), 1e-9);
    EXPECT_NEAR(e.velocity(0)[1], -sign * kick * 0.9, 1e-9);
    EXPECT_NEAR(e.velocity(1)[0], -sign * (0.455 + kick * s), 1e-9);
    EXPECT_NEAR(e.velocity(1)[1], sign * kick * 0.9, 1e-9);
    // the collision's virial J n_x r_y with J = 0.09 s (equal masses, unit reduced mass 1/2:
    // the impulse on A, 0.09 s, along n = (s, -0.9))
    EXPECT_NEAR(e.counters().virial[3], kick * s * -0.9, 1e-9);
}

// Two fixed obstacles whose images slide into each other across the face: they pass
// through each other (neither can move) and the step ends. Before, the pair's approach was
// found again after every "collision" that changed nothing, and the step never ended
// (found by fuzz_run).
TEST(SteppedShear, FixedObstaclesPassThroughEachOthersSlidingImages) {
    ParticleStore<2> p = test::particle_pair<2>(Vec<2>{{0.0, 4.55}}, Vec<2>{{-3.0, -4.55}});
    p.species_table[0].mass = std::numeric_limits<double>::infinity();
    SteppedEngine<2> e(p, test::sheared_box<2>(10.0, 0.1), params_with(0.05));
    for (int k = 0; k < 1200; ++k) e.step(); // t = 60: the images met near t = 28.5
    EXPECT_EQ(e.counters().pair_collisions, 0u);
    EXPECT_EQ(e.particles().position[0][1], 4.55);
    EXPECT_EQ(e.particles().position[1][1], -4.55);
}

TEST(SteppedShear, TwoParticlesMeetAcrossTheFaceWhenTheirImagesLineUp) {
    expect_meeting_across_the_face<2>(Vec<2>{{0.0, 4.55}}, Vec<2>{{-3.0, -4.55}}, 1);
    // in 3D across the face below (B above A's image): the roles swapped
    expect_meeting_across_the_face<3>(Vec<3>{{-3.0, -4.55, 0.2}}, Vec<3>{{0.0, 4.55, 0.2}}, -1);
}

// The flow's power: dK/dt = -rate V P_xy with V P_xy = Σ m c_x c_y + the collisions'
// virial, so K(t) - K(0) = -rate G_xy exactly (elastic collisions, late ones too, conserve
// the energy of a pair in the laboratory frame; a wall on z leaves c_x c_y alone), to
// rounding, however the steps cut the flights. At each step's end no pair overlaps.
template <int D>
void expect_energy_balance(double rate, int n, double spacing, bool wall_z, double dt, int steps) {
    SteppedEngine<D> e(test::sheared_lattice_gas<D>(n, spacing, 7, wall_z),
                       test::sheared_box<D>(spacing * n, rate, wall_z), params_with(dt));
    const double k0 = e.kinetic_energy();
    double closest = std::numeric_limits<double>::infinity();
    for (int k = 0; k < steps; ++k) {
        e.step();
        if (k % 10 == 9)
            closest = std::min(closest, test::closest_approach(e.particles(), e.box()));
    }
    const FluxMoments<D> m = e.flux_moments();
    const double g_xy = m.kinetic_integral[3] + e.counters().virial[3];
    EXPECT_NEAR(e.kinetic_energy() - k0, -rate * g_xy, 1e-9 * k0)
        << "K0 " << k0 << ", -rate G_xy " << -rate * g_xy;
    EXPECT_GT(-rate * g_xy, 0.05 * k0); // the flow did feed in energy
    // the sums carried through every event are those of the peculiar velocities now (the
    // walls flip c_z: c_x c_z and c_y c_z)
    SymTensor now{};
    for (const auto& c : e.particles().velocity) add_sym_outer<D>(now, c, c, 1.0);
    for (int c = 0; c < 6; ++c) EXPECT_NEAR(m.kinetic[c], now[c], 1e-9 * k0) << c;
    EXPECT_GT(e.counters().pair_collisions, 10u * e.size());
    if (wall_z) {
        EXPECT_GT(e.counters().wall_collisions, 100u);
    }
    // (missed grazing collisions can leave a pair that overlapped within a step a hair
    // inside contact at its end; a pair through another across the face, a whole depth)
    EXPECT_GE(closest, 1.0 - 1e-6);
}

TEST(SteppedShear, TheFlowFeedsInExactlyThePowerOfTheShearStress2D) {
    // 144 disks on a square lattice (cell faces hold particles), strongly sheared
    expect_energy_balance<2>(1.0, 12, 1.25, false, 0.005, 1600);
}

TEST(SteppedShear, TheFlowFeedsInExactlyThePowerOfTheShearStress3DWithWallsOnZ) {
    expect_energy_balance<3>(0.5, 6, 1.4, true, 0.005, 1200);
}

TEST(SteppedShear, ACheckpointContinuesBitForBit) {
    const SteppedParams params = params_with(0.005);
    SteppedEngine<3> a(test::sheared_lattice_gas<3>(6, 1.3, 5, false),
                       test::sheared_box<3>(7.8, 0.4), params);
    for (int k = 0; k < 300; ++k) a.step();
    std::ostringstream out;
    a.save(out);
    std::istringstream in(out.str());
    SteppedEngine<3> b = SteppedEngine<3>::load(in, params);
    EXPECT_EQ(b.box().shear_rate(), 0.4);
    EXPECT_EQ(b.box().shear_offset(), a.box().shear_offset());
    for (int k = 0; k < 300; ++k) {
        a.step();
        b.step();
    }
    EXPECT_EQ(a.counters().pair_collisions, b.counters().pair_collisions);
    const ParticleStore<3>&sa = a.particles(), &sb = b.particles();
    for (std::size_t i = 0; i < sa.size(); ++i)
        for (int c = 0; c < 3; ++c) {
            ASSERT_EQ(sa.position[i][c], sb.position[i][c]) << i;
            ASSERT_EQ(sa.velocity[i][c], sb.velocity[i][c]) << i;
        }
    const FluxMoments<3> ma = a.flux_moments(), mb = b.flux_moments();
    for (int c = 0; c < 6; ++c) EXPECT_EQ(ma.kinetic_integral[c], mb.kinetic_integral[c]) << c;
}

TEST(SteppedShear, RefusesARateWhoseFlowAloneOutrunsMaxMove) {
    // the flow moves touching particles (1 apart in y) 5 * 1 * 0.06 = 0.3 a step, 0.6
    // radii, more than max_move = 0.5
    try {
        SteppedEngine<2> e(test::sheared_lattice_gas<2>(8, 1.5, 1, false),
                           test::sheared_box<2>(12.0, 5.0), params_with(0.06));
        FAIL() << "accepted";
    } catch (const InputError& err) {
        const std::string m = err.what();
        EXPECT_NE(m.find("[box] shear_rate = 5"), std::string::npos) << m;
        EXPECT_NE(m.find("[stepped] dt = 0.06"), std::string::npos) << m;
    }
    // at dt = 0.04, 0.4 radii: accepted
    EXPECT_NO_THROW(SteppedEngine<2>(test::sheared_lattice_gas<2>(8, 1.5, 1, false),
                                     test::sheared_box<2>(12.0, 5.0), params_with(0.04)));
}

} // namespace
