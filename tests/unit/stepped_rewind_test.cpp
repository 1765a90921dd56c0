// Seed 002's rewind: two particles placed overlapping with known velocities, moved back
// by the time the formula gives, must be exactly touching (to rounding), and the time
// must be the moment the pair entered the overlap, also for a pair that is already
// separating again. Exact answers are checked where they are known in closed form.
#include "pedesis/stepped/rewind.hpp"

#include <gtest/gtest.h>

#include <cmath>

using namespace pedesis;

namespace {

template <int D>
double distance_after_rewind(Vec<D> ri, Vec<D> rj, Vec<D> vi, Vec<D> vj, double tau) {
    return norm((ri - vi * tau) - (rj - vj * tau));
}

} // namespace

TEST(SteppedRewind, HeadOnPairHasTheClosedFormTime) {
    // centres 0.8 apart, contact distance 1, closing at 2: they touched 0.1 ago
    const Vec<2> ri{{-0.4, 0.0}}, rj{{0.4, 0.0}}, vi{{1.0, 0.0}}, vj{{-1.0, 0.0}};
    const double tau = contact_rewind_time(ri - rj, vi - vj, 1.0);
    EXPECT_NEAR(tau, 0.1, 1e-15);
    EXPECT_NEAR(distance_after_rewind(ri, rj, vi, vj, tau), 1.0, 1e-15);
}

TEST(SteppedRewind, ObliqueUnequalRadiiTouchExactly2D) {
    // radii 0.3 and 1.1 (contact 1.4), impact parameter 0.9, each moving
    const double sigma = 0.3 + 1.1;
    const Vec<2> ri{{0.25, 0.9}}, rj{{1.1, 0.0}}, vi{{2.0, -0.2}}, vj{{-0.5, 0.3}};
    ASSERT_LT(norm(ri - rj), sigma);
    const double tau = contact_rewind_time(ri - rj, vi - vj, sigma);
    ASSERT_GT(tau, 0.0);
    EXPECT_NEAR(distance_after_rewind(ri, rj, vi, vj, tau), sigma, 1e-14);
    // and the pair was approaching at that moment, outside a moment earlier
    const Vec<2> dr = (ri - vi * tau) - (rj - vj * tau);
    EXPECT_LT(dot(dr, vi - vj), 0.0);
    EXPECT_GT(distance_after_rewind(ri, rj, vi, vj, tau * 1.001), sigma);
}

TEST(SteppedRewind, ThreeDimensionsTouchExactly) {
    const double sigma = 1.0;
    const Vec<3> ri{{0.1, 0.2, 0.3}}, rj{{0.6, -0.1, 0.7}}, vi{{0.3, -1.0, 2.0}},
        vj{{-0.7, 0.4, -0.1}};
    ASSERT_LT(norm(ri - rj), sigma);
    const double tau = contact_rewind_time(ri - rj, vi - vj, sigma);
    EXPECT_NEAR(distance_after_rewind(ri, rj, vi, vj, tau), sigma, 1e-14);
}

TEST(SteppedRewind, SeparatingPairIsRewoundToItsEntry) {
    // the pair crossed more than half of its overlap within the step: at the end it is
    // separating (dr . dv > 0) but still overlapping. Seed 002 assumes an approaching
    // pair; the entry root is still the right one.
    const Vec<2> vi{{1.0, 0.0}}, vj{{0.0, 0.0}};
    // at t = 0 the pair touches at x = -sqrt(1 - 0.6^2) = -0.8; now 1.2 later, x = 0.4
    const Vec<2> ri{{0.4, 0.6}}, rj{{0.0, 0.0}};
    ASSERT_GT(dot(ri - rj, vi - vj), 0.0);
    const double tau = contact_rewind_time(ri - rj, vi - vj, 1.0);
    EXPECT_NEAR(tau, 1.2, 1e-14);
    EXPECT_NEAR(distance_after_rewind(ri, rj, vi, vj, tau), 1.0, 1e-14);
}

TEST(SteppedRewind, ShallowOverlapHasNoCancellation) {
    // a pair that has just touched: tau ~ 1e-12 must come out with full relative accuracy
    const double eps = 1e-12;
    const Vec<2> ri{{0.0, 0.0}}, rj{{1.0 - eps, 0.0}}, vi{{1.0, 0.0}}, vj{{0.0, 0.0}};
    const double tau = contact_rewind_time(ri - rj, vi - vj, 1.0);
    EXPECT_NEAR(tau / eps, 1.0, 1e-4);
}

TEST(SteppedRewind, PairWithoutRelativeMotionHasNoEntry) {
    const Vec<2> ri{{0.0, 0.0}}, rj{{0.5, 0.0}}, v{{1.0, 2.0}};
    EXPECT_LT(contact_rewind_time(ri - rj, v - v, 1.0), 0.0);
}
