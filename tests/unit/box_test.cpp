// Box: minimum image and wrapping against brute force, on periodic and walled axes.
#include "pedesis/core/box.hpp"
#include "pedesis/core/rng.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>

using namespace pedesis;

namespace {

// brute force: the image d - k L (|k| <= 3) of smallest magnitude
double brute_min_image(double d, double L) {
    double best = d;
    for (int k = -3; k <= 3; ++k)
        if (std::abs(d - k * L) < std::abs(best)) best = d - k * L;
    return best;
}

} // namespace

TEST(Box, RejectsBadLengths) {
    EXPECT_THROW((Box<2>(Vec<2>{{0.0, 1.0}}, {true, true})), InputError);
    EXPECT_THROW((Box<2>(Vec<2>{{-1.0, 1.0}}, {true, true})), InputError);
    EXPECT_THROW(
        (Box<3>(Vec<3>{{1.0, std::numeric_limits<double>::quiet_NaN(), 1.0}}, {true, true, true})),
        InputError);
    EXPECT_THROW(
        (Box<3>(Vec<3>{{1.0, 1.0, std::numeric_limits<double>::infinity()}}, {true, true, true})),
        InputError);
}

TEST(Box, CentredAtOrigin) {
    Box<3> box(Vec<3>{{2.0, 4.0, 6.0}}, {true, false, true});
    for (int a = 0; a < 3; ++a) {
        EXPECT_DOUBLE_EQ(box.lo(a), -0.5 * box.length(a));
        EXPECT_DOUBLE_EQ(box.hi(a), 0.5 * box.length(a));
    }
    EXPECT_DOUBLE_EQ(box.volume(), 48.0);
    EXPECT_TRUE(box.any_wall());
    EXPECT_FALSE((Box<2>(Vec<2>{{1.0, 1.0}}, {true, true}).any_wall()));
}

TEST(Box, MinimumImageMatchesBruteForce) {
    const Vec<3> L{{3.0, 7.5, 10.0}};
    Box<3> box(L, {true, false, true});
    CounterRng rng(11, RngStream::placement, 0);
    for (int trial = 0; trial < 20000; ++trial) {
        Vec<3> d;
        for (int a = 0; a < 3; ++a) d[a] = rng.uniform(-1.499, 1.499) * L[a];
        const Vec<3> m = box.minimum_image(d);
        // walled axis: untouched
        EXPECT_EQ(m[1], d[1]);
        for (int a : {0, 2}) {
            EXPECT_LE(std::abs(m[a]), 0.5 * L[a] * (1 + 1e-15));
            EXPECT_NEAR(std::abs(m[a]), std::abs(brute_min_image(d[a], L[a])), 1e-12 * L[a]);
            // m differs from d by a whole number of box lengths
            const double k = (d[a] - m[a]) / L[a];
            EXPECT_NEAR(k, std::round(k), 1e-12);
        }
    }
}

TEST(Box, MinimumImageIsAntisymmetric) {
    Box<2> box(Vec<2>{{5.0, 5.0}}, {true, true});
    CounterRng rng(12, RngStream::placement, 0);
    for (int trial = 0; trial < 1000; ++trial) {
        Vec<2> r1{{rng.uniform(-2.5, 2.5), rng.uniform(-2.5, 2.5)}};
        Vec<2> r2{{rng.uniform(-2.5, 2.5), rng.uniform(-2.5, 2.5)}};
        const Vec<2> a = box.minimum_image(r1 - r2), b = box.minimum_image(r2 - r1);
        // except exactly at +-L/2, the image of -d is -image(d)
        EXPECT_NEAR(norm(a), norm(b), 1e-12);
    }
}

TEST(Box, WrapLandsInHalfOpenIntervalAndReportsShift) {
    const Vec<2> L{{4.0, 10.0}};
    Box<2> box(L, {true, false});
    CounterRng rng(13, RngStream::placement, 0);
    for (int trial = 0; trial < 20000; ++trial) {
        Vec<2> r{{rng.uniform(-5.0, 5.0) * L[0], rng.uniform(-0.5, 0.5) * L[1]}};
        const Vec<2> orig = r;
        const Vec<2> shift = box.wrap(r);
        EXPECT_GE(r[0], -0.5 * L[0]);
        EXPECT_LT(r[0], 0.5 * L[0]);
        EXPECT_EQ(shift[0], std::round(shift[0]));
        EXPECT_NEAR(orig[0] - shift[0] * L[0], r[0], 1e-12 * L[0] * (1 + std::abs(shift[0])));
        // walled axis untouched
        EXPECT_EQ(r[1], orig[1]);
        EXPECT_EQ(shift[1], 0.0);
    }
}

TEST(Box, WrapEdgeCases) {
    Box<1> box(Vec<1>{{10.0}}, {true});
    auto wrapped = [&](double x) {
        Vec<1> r{{x}};
        box.wrap(r);
        return r[0];
    };
    EXPECT_EQ(wrapped(5.0), -5.0);  // +L/2 belongs to the other side
    EXPECT_EQ(wrapped(-5.0), -5.0); // -L/2 stays
    EXPECT_EQ(wrapped(0.0), 0.0);
    EXPECT_EQ(wrapped(15.0), -5.0);
    EXPECT_EQ(wrapped(25.0), 5.0 - 10.0);
    EXPECT_NEAR(wrapped(7.0), -3.0, 1e-15);
    EXPECT_NEAR(wrapped(-7.0), 3.0, 1e-15);
    // just below -L/2: the result must not be rounded onto +L/2
    for (double eps : {1e-18, 1e-17, 1e-16, 1e-15, 1e-14}) {
        const double x = wrapped(-5.0 - eps);
        EXPECT_GE(x, -5.0);
        EXPECT_LT(x, 5.0);
    }
    // a value already inside is never changed
    for (double x : {-4.999999999, -1e-300, 1e-300, 4.999999999}) EXPECT_EQ(wrapped(x), x);
}

TEST(Box, WrapJustBelowHalfLengthStaysInside) {
    // r just below +L/2: (r + L/2) / L can round up to exactly 1, so floor gives k = 1 and
    // r - L lands just below -L/2, outside the promised interval [-L/2, L/2). (The
    // foundation's wrap did exactly that for 5 - 1e-15 in a box of 10; regression test.)
    Box<1> box(Vec<1>{{10.0}}, {true});
    for (double eps : {1e-16, 1e-15, 2e-15, 1e-14, 1e-12}) {
        Vec<1> r{{5.0 - eps}};
        const double before = r[0];
        box.wrap(r);
        EXPECT_GE(r[0], -5.0) << "wrap(" << before << ") = " << r[0];
        EXPECT_LT(r[0], 5.0) << "wrap(" << before << ") = " << r[0];
    }
    // the same in a box whose length is not a power-of-two multiple
    Box<1> odd(Vec<1>{{7.3}}, {true});
    for (int k = 1; k <= 8; ++k) {
        Vec<1> r{{std::nextafter(3.65, 0.0)}};
        for (int s = 1; s < k; ++s) r[0] = std::nextafter(r[0], 0.0);
        const double before = r[0];
        odd.wrap(r);
        EXPECT_GE(r[0], -3.65) << "wrap(" << before << ") = " << r[0];
        EXPECT_LT(r[0], 3.65);
    }
}

TEST(Box, ContainsHonoursMarginOnWallAxesOnly) {
    Box<2> box(Vec<2>{{10.0, 4.0}}, {true, false});
    EXPECT_TRUE(box.contains(Vec<2>{{100.0, 0.0}}, 0.5)); // periodic axis never excludes
    EXPECT_TRUE(box.contains(Vec<2>{{0.0, 1.5}}, 0.5));
    EXPECT_FALSE(box.contains(Vec<2>{{0.0, 1.51}}, 0.5));
    EXPECT_FALSE(box.contains(Vec<2>{{0.0, -1.51}}, 0.5));
    EXPECT_TRUE(box.contains(Vec<2>{{0.0, 2.0}}, 0.0));
    EXPECT_FALSE(box.contains(Vec<2>{{0.0, 2.0001}}, 0.0));
}
