#pragma once
// Counter-based random numbers (Philox4x32-10 from Random123). A draw is a pure
// function of (seed, stream, tag, counter), so results do not depend on thread
// count or particle order.
#include <Random123/philox.h>
#include <Random123/uniform.hpp>

#include <array>
#include <bit>
#include <cmath>
#include <cstdint>
#include <numbers>

namespace pedesis {

namespace detail {

// sin x and cos x for |x| <= pi/4 by their Taylor series up to x^15 and x^16 (the next
// terms are below 1e-16 relative). The integrators call these several times per
// particle and step, where libm's general sincos (with its range reduction) was the
// largest single cost.
inline void sincos_kernel(double x, double& s, double& c) {
    const double z = x * x;
    double ps = -1.0 / 1307674368000.0; // -1/15!
    ps = ps * z + 1.0 / 6227020800.0;
    ps = ps * z - 1.0 / 39916800.0;
    ps = ps * z + 1.0 / 362880.0;
    ps = ps * z - 1.0 / 5040.0;
    ps = ps * z + 1.0 / 120.0;
    ps = ps * z - 1.0 / 6.0;
    s = x + x * z * ps;
    double pc = 1.0 / 20922789888000.0; // 1/16!
    pc = pc * z - 1.0 / 87178291200.0;
    pc = pc * z + 1.0 / 479001600.0;
    pc = pc * z - 1.0 / 3628800.0;
    pc = pc * z + 1.0 / 40320.0;
    pc = pc * z - 1.0 / 720.0;
    pc = pc * z + 1.0 / 24.0;
    c = 1.0 - 0.5 * z + z * z * pc;
}

// sin(2 pi u) and cos(2 pi u) for u in [0, 1]. In turns the reduction to the nearest
// quarter is exact (4u and 4u - k are exact), so no multi-word pi is needed. Adding
// 1.5 * 2^52 rounds 4u to the integer k and leaves k in the low bits; the quadrant is
// then applied with bit masks, so that loops over many u vectorise (no branch, no
// integer conversion).
inline void sincos_turns(double u, double& s, double& c) {
    constexpr double shifter = 0x1.8p52;
    const double t = 4.0 * u;
    const double big = t + shifter;
    const double x = (t - (big - shifter)) * (0.5 * std::numbers::pi);
    double sx, cx;
    sincos_kernel(x, sx, cx);
    const auto k = std::bit_cast<std::uint64_t>(big);
    const std::uint64_t swap = 0 - (k & 1); // all ones in odd quadrants
    const auto bs = std::bit_cast<std::uint64_t>(sx), bc = std::bit_cast<std::uint64_t>(cx);
    const std::uint64_t sign = std::uint64_t{1} << 63;
    // quadrant k: (sin, cos) = (s, c), (c, -s), (-s, -c), (-c, s)
    s = std::bit_cast<double>(((bs & ~swap) | (bc & swap)) ^ ((k << 62) & sign));
    c = std::bit_cast<double>(((bc & ~swap) | (bs & swap)) ^ (((k + 1) << 62) & sign));
}

} // namespace detail

enum class RngStream : std::uint32_t {
    placement = 1,
    velocity = 2,
    orientation = 3,
    thermostat = 4,
    initial_director = 5,
};

class CounterRng {
  public:
    CounterRng(std::uint64_t seed, RngStream stream, std::uint32_t tag, std::uint32_t step = 0)
        : key_{{static_cast<std::uint32_t>(seed), static_cast<std::uint32_t>(seed >> 32)}},
          ctr_{{tag, step, static_cast<std::uint32_t>(stream), 0u}} {}

    // uniform in (0, 1]
    double uniform() {
        if (used_ == 2) refill();
        const std::uint64_t hi = out_[2 * used_], lo = out_[2 * used_ + 1];
        ++used_;
        const std::uint64_t bits = ((hi << 32) | lo) >> 11; // 53 random bits
        return (static_cast<double>(bits) + 1.0) * 0x1.0p-53;
    }
    double uniform(double a, double b) { return a + (b - a) * uniform(); }

    // Standard normal by Box-Muller; keeps the second value for the next call.
    double normal() {
        if (has_spare_) {
            has_spare_ = false;
            return spare_;
        }
        const double u1 = uniform(), u2 = uniform();
        const double r = std::sqrt(-2.0 * std::log(u1));
        spare_ = r * std::sin(2.0 * std::numbers::pi * u2);
        has_spare_ = true;
        return r * std::cos(2.0 * std::numbers::pi * u2);
    }

    // Two independent standard normals from the next two uniforms (Box-Muller, the same
    // pair that two calls of normal() would give, to rounding), for callers that need
    // them together and no state carried between calls.
    std::array<double, 2> normal_pair() {
        const double u1 = uniform(), u2 = uniform();
        const double r = std::sqrt(-2.0 * std::log(u1));
        double sn, cs;
        detail::sincos_turns(u2, sn, cs);
        return {r * cs, r * sn};
    }

  private:
    using Philox = r123::Philox4x32;
    void refill() {
        out_ = Philox()(ctr_, key_);
        ctr_[3]++;
        used_ = 0;
    }
    Philox::key_type key_;
    Philox::ctr_type ctr_;
    Philox::ctr_type out_{};
    int used_ = 2;
    bool has_spare_ = false;
    double spare_ = 0.0;
};

} // namespace pedesis
