// noise_log, the integrators' own logarithm, against the C library's: within one ulp
// over the uniforms Box-Muller takes ((j + 1) 2^-53) and over every binade they span,
// exact where the logarithm is (1, powers of two to their k ln 2 rounding), and the same
// in a vectorized loop as alone.
#include "pedesis/core/noise_log.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <limits>
#include <random>
#include <vector>

using namespace pedesis;

namespace {

// |a - b| in units of the last place of b.
double ulps(double a, double b) {
    const double b_abs = std::abs(b);
    const double ulp = std::nextafter(b_abs, std::numeric_limits<double>::infinity()) - b_abs;
    return std::abs(a - b) / ulp;
}

TEST(NoiseLog, WithinOneUlpOfTheLibraryOverTheUniforms) {
    std::mt19937_64 bits(20261128);
    double worst = 0.0;
    std::size_t differ = 0, n = 0;
    for (int binade = 0; binade <= 53; ++binade)
        for (int k = 0; k < 20000; ++k) {
            // the uniforms' form, scaled into each binade down to the smallest, 2^-53
            const double u =
                std::ldexp((static_cast<double>(bits() >> 11) + 1.0) * 0x1p-53, -binade);
            if (u < 0x1p-53) continue;
            const double ours = noise_log(u), library = std::log(u);
            worst = std::max(worst, ulps(ours, library));
            differ += ours != library ? 1 : 0;
            ++n;
        }
    EXPECT_LE(worst, 1.0) << differ << " of " << n << " differ";
    // nearly always the same double: a few percent differ, by one ulp
    EXPECT_LT(differ, n / 10) << n;
}

TEST(NoiseLog, ExactAtOneAndNearItsEdges) {
    EXPECT_EQ(noise_log(1.0), 0.0);
    // the reduction's edges: m at sqrt(1/2) and just below sqrt(2), and 1 - ulp
    for (double x : {std::sqrt(0.5), std::nextafter(std::sqrt(2.0) / 2.0, 1.0),
                     std::nextafter(std::sqrt(2.0), 1.0) / 2.0, std::nextafter(1.0, 0.0), 0.5, 0.25,
                     0x1p-53, 0.75, 0.999999})
        EXPECT_LE(ulps(noise_log(x), std::log(x)), 1.0) << x;
    for (int k = 1; k <= 53; ++k)
        EXPECT_LE(ulps(noise_log(std::ldexp(1.0, -k)), std::log(std::ldexp(1.0, -k))), 1.0) << k;
}

TEST(NoiseLog, TheSameInALoopAsAlone) {
    std::vector<double> u(1000), r(1000);
    for (std::size_t k = 0; k < u.size(); ++k) u[k] = (static_cast<double>(k) + 0.5) / 1000.0;
    for (std::size_t k = 0; k < u.size(); ++k) r[k] = noise_log(u[k]);
    for (std::size_t k = 0; k < u.size(); ++k) {
        volatile double x = u[k]; // one at a time, outside the loop's vectors
        EXPECT_EQ(r[k], noise_log(x)) << u[k];
    }
}

} // namespace
