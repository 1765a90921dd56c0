// Exact event times: pair collision time against a brute-force root (bisection in long
// double), the bounded variant, wall times and neighbour-shell exit times.
#include "pedesis/core/rng.hpp"
#include "pedesis/event/prediction.hpp"

#include <gtest/gtest.h>

#include <cmath>

using namespace pedesis;

namespace {

// First root of |dr + dv t| = sigma for t >= 0, by bisection on the decreasing branch of
// the convex quadratic; `never` when the pair never comes within sigma.
template <int D> double brute_pair_time(const Vec<D>& dr, const Vec<D>& dv, double sigma) {
    auto f = [&](long double t) {
        long double s = 0.0L;
        for (int a = 0; a < D; ++a) {
            const long double x =
                static_cast<long double>(dr[a]) + static_cast<long double>(dv[a]) * t;
            s += x * x;
        }
        return s - static_cast<long double>(sigma) * sigma;
    };
    long double dv2 = 0.0L, b = 0.0L;
    for (int a = 0; a < D; ++a) {
        dv2 += static_cast<long double>(dv[a]) * dv[a];
        b += static_cast<long double>(dr[a]) * dv[a];
    }
    if (b >= 0.0L || dv2 == 0.0L) return never;
    const long double tmin = -b / dv2; // closest approach
    if (f(tmin) >= 0.0L) return never;
    long double lo = 0.0L, hi = tmin;
    for (int it = 0; it < 200; ++it) {
        const long double mid = 0.5L * (lo + hi);
        (f(mid) > 0.0L ? lo : hi) = mid;
    }
    return static_cast<double>(0.5L * (lo + hi));
}

template <int D> Vec<D> random_vec(CounterRng& rng, double scale) {
    Vec<D> v;
    for (int a = 0; a < D; ++a) v[a] = scale * rng.uniform(-1.0, 1.0);
    return v;
}

template <int D> void check_pair_times(std::uint64_t seed) {
    CounterRng rng(seed, RngStream::placement, D);
    int hits = 0, misses = 0;
    for (int trial = 0; trial < 20000; ++trial) {
        const double sigma = rng.uniform(0.2, 2.0);
        Vec<D> dr = random_vec<D>(rng, 4.0);
        if (norm(dr) <= sigma * 1.001) continue;
        const Vec<D> dv = random_vec<D>(rng, rng.uniform() < 0.5 ? 1.0 : 1e-3);
        const double t = pair_collision_time(dr, dv, sigma);
        const double ref = brute_pair_time(dr, dv, sigma);
        if (ref == never) {
            // a near-grazing miss may be predicted as a hit with a closest approach of
            // sigma to rounding; anything else must be `never`
            if (t != never) {
                const Vec<D> at = dr + dv * t;
                EXPECT_NEAR(norm(at), sigma, 1e-9 * sigma);
            }
            ++misses;
            continue;
        }
        ++hits;
        ASSERT_NE(t, never) << "trial " << trial;
        EXPECT_NEAR(t, ref, 1e-11 * ref + 1e-14) << "trial " << trial;
        // at the predicted time the pair touches
        EXPECT_NEAR(norm(dr + dv * t), sigma, 1e-11 * sigma);

        // bounded variant: identical when the event falls before the bound, `never` or
        // identical otherwise
        for (double factor : {0.5, 0.999, 1.001, 2.0}) {
            const double bound = ref * factor;
            const double tb = pair_collision_time_before(dr, dv, sigma, bound);
            if (t < bound) {
                EXPECT_EQ(tb, t);
            }
            if (tb != never) {
                EXPECT_EQ(tb, t);
            }
        }
    }
    EXPECT_GT(hits, 500);
    EXPECT_GT(misses, 1000);
}

} // namespace

TEST(Prediction, PairTimeMatchesBruteForce2D) {
    check_pair_times<2>(1);
}
TEST(Prediction, PairTimeMatchesBruteForce3D) {
    check_pair_times<3>(2);
}

TEST(Prediction, PairTimeSimpleCases) {
    // head-on, gap 2, closing speed 2: t = 1
    EXPECT_DOUBLE_EQ(pair_collision_time(Vec<2>{{3.0, 0.0}}, Vec<2>{{-2.0, 0.0}}, 1.0), 1.0);
    // receding
    EXPECT_EQ(pair_collision_time(Vec<2>{{3.0, 0.0}}, Vec<2>{{2.0, 0.0}}, 1.0), never);
    // at rest relative to each other
    EXPECT_EQ(pair_collision_time(Vec<2>{{3.0, 0.0}}, Vec<2>{{0.0, 0.0}}, 1.0), never);
    // passing side by side (closest approach 1.5 > sigma)
    EXPECT_EQ(pair_collision_time(Vec<2>{{3.0, 1.5}}, Vec<2>{{-1.0, 0.0}}, 1.0), never);
    // impact parameter b < sigma: t = (3 - sqrt(sigma^2 - b^2)) / |v|
    EXPECT_NEAR(pair_collision_time(Vec<3>{{3.0, 0.6, 0.0}}, Vec<3>{{-1.0, 0.0, 0.0}}, 1.0),
                3.0 - 0.8, 1e-15);
    // overlapping by a rounding error and approaching: collide at once
    EXPECT_EQ(pair_collision_time(Vec<2>{{1.0 - 1e-14, 0.0}}, Vec<2>{{-1.0, 0.0}}, 1.0), 0.0);
    // overlapping and receding: no event
    EXPECT_EQ(pair_collision_time(Vec<2>{{1.0 - 1e-14, 0.0}}, Vec<2>{{1.0, 0.0}}, 1.0), never);
    // touching and sliding tangentially: no event
    EXPECT_EQ(pair_collision_time(Vec<2>{{1.0, 0.0}}, Vec<2>{{0.0, 1.0}}, 1.0), never);
    // bounded variant with a bound beyond the event
    EXPECT_DOUBLE_EQ(pair_collision_time_before(Vec<2>{{3.0, 0.0}}, Vec<2>{{-2.0, 0.0}}, 1.0, 5.0),
                     1.0);
    EXPECT_EQ(pair_collision_time_before(Vec<2>{{3.0, 0.0}}, Vec<2>{{-2.0, 0.0}}, 1.0, 0.25),
              never);
}

TEST(Prediction, WallTime) {
    // box [-5, 5], radius 0.5: contact planes at -4.5 and 4.5
    EXPECT_DOUBLE_EQ(wall_collision_time(0.0, 1.0, -5.0, 5.0, 0.5), 4.5);
    EXPECT_DOUBLE_EQ(wall_collision_time(0.0, -2.0, -5.0, 5.0, 0.5), 2.25);
    EXPECT_DOUBLE_EQ(wall_collision_time(4.0, 0.25, -5.0, 5.0, 0.5), 2.0);
    EXPECT_EQ(wall_collision_time(1.0, 0.0, -5.0, 5.0, 0.5), never);
    // on the contact plane moving out (or past it by rounding): collide now
    EXPECT_EQ(wall_collision_time(4.5, 1.0, -5.0, 5.0, 0.5), 0.0);
    EXPECT_EQ(wall_collision_time(4.5 + 1e-15, 1.0, -5.0, 5.0, 0.5), 0.0);
    EXPECT_EQ(wall_collision_time(-4.5 - 1e-15, -1.0, -5.0, 5.0, 0.5), 0.0);
    // on the contact plane moving in: the far wall
    EXPECT_DOUBLE_EQ(wall_collision_time(4.5, -1.0, -5.0, 5.0, 0.5), 9.0);

    CounterRng rng(3, RngStream::placement, 0);
    for (int trial = 0; trial < 10000; ++trial) {
        const double lo = rng.uniform(-10.0, -1.0), hi = rng.uniform(1.0, 10.0),
                     rad = rng.uniform(0.01, 0.9);
        const double x = rng.uniform(lo + rad, hi - rad), v = rng.uniform(-3.0, 3.0);
        const double t = wall_collision_time(x, v, lo, hi, rad);
        const double target = v > 0 ? hi - rad : lo + rad;
        EXPECT_NEAR(x + v * t, target, 1e-12 * (hi - lo));
        EXPECT_GE(t, 0.0);
    }
}

TEST(Prediction, ShellExitTime) {
    CounterRng rng(4, RngStream::placement, 0);
    for (int trial = 0; trial < 10000; ++trial) {
        const double radius = rng.uniform(0.05, 1.0);
        Vec<3> d = random_vec<3>(rng, radius);
        if (norm(d) >= radius) continue;
        const Vec<3> v = random_vec<3>(rng, 2.0);
        const double t = shell_exit_time(d, v, radius);
        ASSERT_GT(t, 0.0);
        EXPECT_NEAR(norm(d + v * t), radius, 1e-12 * radius);
        // inside the shell before that time, outside after
        for (double f : {0.0, 0.25, 0.5, 0.9, 0.999}) EXPECT_LT(norm(d + v * (f * t)), radius);
        EXPECT_GT(norm(d + v * (1.001 * t)), radius);
    }
    // at rest: never; at or outside the shell: now
    EXPECT_EQ(shell_exit_time(Vec<2>{{0.1, 0.0}}, Vec<2>{{0.0, 0.0}}, 0.25), never);
    EXPECT_EQ(shell_exit_time(Vec<2>{{0.25, 0.0}}, Vec<2>{{-1.0, 0.0}}, 0.25), 0.0);
    EXPECT_EQ(shell_exit_time(Vec<2>{{0.3, 0.0}}, Vec<2>{{1.0, 0.0}}, 0.25), 0.0);
    EXPECT_DOUBLE_EQ(shell_exit_time(Vec<2>{{0.0, 0.0}}, Vec<2>{{0.5, 0.0}}, 0.25), 0.5);
    EXPECT_DOUBLE_EQ(shell_exit_time(Vec<2>{{0.1, 0.0}}, Vec<2>{{-1.0, 0.0}}, 0.25), 0.35);
}
