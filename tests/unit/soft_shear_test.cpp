// Lees-Edwards shear in the soft engine's pieces: the box's sliding images by hand, the
// pair forces of every kernel set against a brute-force sum over minimum images, a free
// particle crossing the y faces under SLLOD (its position, image and laboratory velocity
// remapped as Lees and Edwards say, numbers worked by hand), Brownian streaming, and the
// GPU path's refusal.
#include "support/soft_builder.hpp"

#include "pedesis/core/error.hpp"
#include "pedesis/core/frame.hpp"
#include "pedesis/core/simd_level.hpp"
#include "pedesis/gpu/gpu_stepper.hpp"
#include "pedesis/soft/brownian.hpp"
#include "pedesis/soft/evolver.hpp"
#include "pedesis/soft/pair_force.hpp"
#include "pedesis/soft/pair_potentials.hpp"
#include "pedesis/soft/velocity_verlet.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <memory>
#include <string>

using namespace pedesis;

namespace {

Box<2> sheared_box(double lx, double ly, double offset) {
    Box<2> b(Vec<2>{{lx, ly}}, {true, true});
    b.set_shear_rate(1.0);
    b.set_shear_offset(offset);
    return b;
}

// Lx = 10, Ly = 8, the image above displaced by 3 along x.
TEST(ShearBox, WrapAndMinimumImageSlideTheImagesAcrossY) {
    const Box<2> box = sheared_box(10.0, 8.0, 3.0);
    // above the top face: down by L_y, back by the offset
    Vec<2> r{{4.0, 4.5}};
    Vec<2> shift = box.wrap(r);
    EXPECT_DOUBLE_EQ(r[0], 1.0);
    EXPECT_DOUBLE_EQ(r[1], -3.5);
    EXPECT_EQ(shift[0], 0.0);
    EXPECT_EQ(shift[1], 1.0);
    // below the bottom face: up, forward by the offset
    r = Vec<2>{{-4.0, -4.5}};
    shift = box.wrap(r);
    EXPECT_DOUBLE_EQ(r[0], -1.0);
    EXPECT_DOUBLE_EQ(r[1], 3.5);
    EXPECT_EQ(shift[1], -1.0);
    // the shift carries x across its own face: 4.9 + 3 = 7.9 is -2.1 one box on
    r = Vec<2>{{4.9, -4.5}};
    shift = box.wrap(r);
    EXPECT_NEAR(r[0], -2.1, 1e-12);
    EXPECT_DOUBLE_EQ(r[1], 3.5);
    EXPECT_EQ(shift[0], 1.0);
    EXPECT_EQ(shift[1], -1.0);
    // a pair 7 apart along y is 1 apart through the faces, its x difference less 3
    const Vec<2> d = box.minimum_image(Vec<2>{{1.0, 7.0}});
    EXPECT_DOUBLE_EQ(d[0], -2.0);
    EXPECT_DOUBLE_EQ(d[1], -1.0);
    const Vec<2> e = box.minimum_image(Vec<2>{{4.5, -7.5}});
    EXPECT_DOUBLE_EQ(e[0], -2.5); // 4.5 + 3 = 7.5, one box back
    EXPECT_DOUBLE_EQ(e[1], 0.5);
    // the laboratory velocity adds rate * y along x
    Box<2> fast = box;
    fast.set_shear_rate(0.5);
    const Vec<2> v = fast.lab_velocity(Vec<2>{{1.0, -2.0}}, Vec<2>{{0.25, 1.0}});
    EXPECT_DOUBLE_EQ(v[0], -0.75);
    EXPECT_DOUBLE_EQ(v[1], 1.0);
}

TEST(ShearBox, TheOffsetIsKeptInMinusHalfToHalfABox) {
    Box<2> box = sheared_box(10.0, 8.0, 0.0);
    for (const auto& [given, kept] : {std::pair{13.0, 3.0},
                                      {7.0, -3.0},
                                      {5.0, -5.0},
                                      {-5.0, -5.0},
                                      {-25.5, 4.5},
                                      {1e6 + 0.25, 0.25}}) {
        box.set_shear_offset(given);
        EXPECT_DOUBLE_EQ(box.shear_offset(), kept) << given;
    }
    box.set_shear_rate(0.5);
    box.shear_to_time(3.0); // 0.5 * 8 * 3 = 12
    EXPECT_DOUBLE_EQ(box.shear_offset(), 2.0);
    EXPECT_THROW(box.set_shear_rate(-1.0), InputError);
    EXPECT_THROW(box.set_shear_rate(std::nan("")), InputError);
    EXPECT_THROW(box.set_shear_offset(std::nan("")), InputError);
    Box<3> walled(Vec<3>{{5.0, 5.0, 5.0}}, {true, false, true});
    EXPECT_THROW(walled.set_shear_rate(1.0), InputError);
    walled.set_shear_rate(0.0); // none: fine
    EXPECT_FALSE(walled.sheared());
}

// Pair forces (harmonic, range 2) of a random dense system in a sheared box with every
// kernel set the CPU has, against the sum over all pairs by Box::minimum_image.
template <int D> void check_forces_against_brute_force(double L, std::size_t n) {
    const SimdLevel saved = simd_level();
    for (SimdLevel level : available_simd_levels())
        for (double offset : {0.0, 0.37 * L, -0.5 * L, 1.25}) {
            set_simd_level(level);
            auto s = test::random_soft_system<D>(n, L, 1.0, 7);
            s.box.set_shear_rate(1.0);
            s.box.set_shear_offset(offset);
            Evolver<D> e(s, 0.3);
            const HarmonicPair pair{10.0, 2.0};
            e.add_force(std::make_unique<PairForce<D, HarmonicPair>>("harmonic", pair));
            e.compute_forces();
            std::size_t across = 0;
            for (std::size_t i = 0; i < n; ++i) {
                Vec<D> f{};
                for (std::size_t j = 0; j < n; ++j) {
                    if (j == i) continue;
                    const Vec<D> d = s.box.minimum_image(s.p.position[i] - s.p.position[j]);
                    const double r = norm(d);
                    if (r >= 2.0) continue;
                    f += pair.force_over_r_at(r, 2.0) * d;
                    across += std::abs(s.p.position[i][1] - s.p.position[j][1]) > s.box.hi(1);
                }
                for (int a = 0; a < D; ++a)
                    ASSERT_NEAR(s.force[i][a], f[a], 1e-10)
                        << "particle " << i << ", axis " << a << ", offset " << offset << ", "
                        << simd_name(level);
            }
            EXPECT_GT(across, 20u);
        }
    set_simd_level(saved);
}

TEST(ShearForces, EveryKernelSetSumsTheSlidingImages2D) {
    check_forces_against_brute_force<2>(20.0, 300);
}

TEST(ShearForces, EveryKernelSetSumsTheSlidingImages3D) {
    check_forces_against_brute_force<3>(9.0, 300);
}

// A free particle under SLLOD moves on a straight line in the laboratory frame: from
// (1, 4.9) with peculiar velocity (0.3, 1) at rate 0.2 in a 10 x 10 box its laboratory
// velocity is (0.3 + 0.2 * 4.9, 1) = (1.28, 1). At t = 0.5 (50 steps of 0.01) it is at
// (1.64, 5.4) unwrapped: across the top face, where the offset is 0.2 * 10 * 0.5 = 1, so
// stored at (0.64, -4.6) with image (0, 1); its peculiar v_x is 0.3 - 0.2 * 1 * 0.5 = 0.2
// and its laboratory velocity there (0.2 + 0.2 * (-4.6), 1) = (-0.72, 1): the Lees-Edwards
// jump of -rate L_y. (Velocity Verlet's parts are exact flows: exact up to rounding.)
TEST(ShearMotion, AFreeParticleCrossesTheSlidingFaceAsLeesEdwardsSay) {
    SoftState<2> s;
    s.box = Box<2>(Vec<2>{{10.0, 10.0}}, {true, true});
    s.box.set_shear_rate(0.2);
    s.resize(1);
    s.p.species_table = {Species{"A", 0.5, 1.0}};
    s.p.position[0] = Vec<2>{{1.0, 4.9}};
    s.p.velocity[0] = Vec<2>{{0.3, 1.0}};
    s.director[0] = Vec<2>{{1.0, 0.0}};
    Evolver<2> e(s, 0.3);
    e.add_integrator(std::make_unique<VelocityVerletIntegrator<2>>());
    const Frame<2> before = s.frame();
    EXPECT_NEAR(before.lab_velocity(0)[0], 1.28, 1e-15);
    for (int k = 0; k < 50; ++k) e.evolve(0.01);
    EXPECT_NEAR(s.box.shear_offset(), 1.0, 1e-12);
    EXPECT_NEAR(s.p.position[0][0], 0.64, 1e-12);
    EXPECT_NEAR(s.p.position[0][1], -4.6, 1e-12);
    EXPECT_EQ(s.image[0][0], 0);
    EXPECT_EQ(s.image[0][1], 1);
    EXPECT_NEAR(s.p.velocity[0][0], 0.2, 1e-12);
    EXPECT_NEAR(s.p.velocity[0][1], 1.0, 1e-12);
    const Vec<2> lab = s.frame().lab_velocity(0);
    EXPECT_NEAR(lab[0], -0.72, 1e-12);
    EXPECT_NEAR(lab[1], 1.0, 1e-12);
    // unwrapped: the straight line, continued through the sliding image
    EXPECT_NEAR(s.unwrapped(0)[0], 1.64, 1e-12);
    EXPECT_NEAR(s.unwrapped(0)[1], 5.4, 1e-12);
}

// Overdamped, no force, no noise: the particle only streams, dx = rate y dt, and the
// velocity it keeps (the peculiar one) is zero.
TEST(ShearMotion, BrownianParticlesStreamWithTheFlow) {
    SoftState<2> s;
    s.box = Box<2>(Vec<2>{{10.0, 10.0}}, {true, true});
    s.box.set_shear_rate(0.5);
    s.resize(1);
    s.p.species_table = {Species{"A", 0.5, 1.0}};
    s.p.position[0] = Vec<2>{{-2.0, 3.0}};
    s.director[0] = Vec<2>{{1.0, 0.0}};
    Evolver<2> e(s, 0.3);
    e.add_integrator(std::make_unique<BrownianIntegrator<2>>(0.0, 1.0, 1));
    for (int k = 0; k < 20; ++k) e.evolve(0.01);
    EXPECT_NEAR(s.p.position[0][0], -2.0 + 0.5 * 3.0 * 0.2, 1e-12);
    EXPECT_DOUBLE_EQ(s.p.position[0][1], 3.0);
    EXPECT_EQ(s.p.velocity[0][0], 0.0);
    EXPECT_NEAR(s.frame().lab_velocity(0)[0], 1.5, 1e-15);
}

TEST(ShearGpu, TheDevicePathRefusesShearByName) {
    auto s = test::random_soft_system<2>(4, 30.0, 0.5, 1);
    s.box.set_shear_rate(0.5);
    Evolver<2> e(s, 0.5);
    e.add_integrator(std::make_unique<BrownianIntegrator<2>>(0.1, 1.0, 1));
    try {
        gpu_model(s, e);
        ADD_FAILURE() << "a sheared box was accepted";
    } catch (const InputError& err) {
        EXPECT_NE(std::string(err.what()).find("Lees–Edwards shear"), std::string::npos)
            << err.what();
    }
}

} // namespace
