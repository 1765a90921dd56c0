#pragma once
// sin and cos of the integrators and of the normal deviates (Box-Muller), shared by the
// CPU engine and the CUDA kernels (src/pedesis/gpu/) so that both draw the same numbers:
// C++17, PEDESIS_HD.
#include "pedesis/core/host_device.hpp"

#include <cstdint>
#include <cstring>

namespace pedesis::detail {

// pi as the closest double (std::numbers::pi, which C++17 lacks)
constexpr double pi = 3.141592653589793238462643383279502884;

// The bits of a double and back (std::bit_cast, which C++17 lacks).
PEDESIS_HD inline std::uint64_t double_bits(double x) {
#if defined(__CUDA_ARCH__)
    return static_cast<std::uint64_t>(__double_as_longlong(x));
#else
    std::uint64_t u;
    std::memcpy(&u, &x, sizeof u);
    return u;
#endif
}
PEDESIS_HD inline double bits_double(std::uint64_t u) {
#if defined(__CUDA_ARCH__)
    return __longlong_as_double(static_cast<long long>(u));
#else
    double x;
    std::memcpy(&x, &u, sizeof x);
    return x;
#endif
}

// sin x and cos x for |x| <= pi/4 by their Taylor series up to x^15 and x^16 (the next
// terms are below 1e-16 relative). The integrators call these several times per
// particle and step, where libm's general sincos (with its range reduction) was the
// largest single cost.
PEDESIS_HD inline void sincos_kernel(double x, double& s, double& c) {
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
PEDESIS_HD inline void sincos_turns(double u, double& s, double& c) {
    constexpr double shifter = 0x1.8p52;
    const double t = 4.0 * u;
    const double big = t + shifter;
    const double x = (t - (big - shifter)) * (0.5 * pi);
    double sx, cx;
    sincos_kernel(x, sx, cx);
    const std::uint64_t k = double_bits(big);
    const std::uint64_t swap = 0 - (k & 1); // all ones in odd quadrants
    const std::uint64_t bs = double_bits(sx), bc = double_bits(cx);
    const std::uint64_t sign = std::uint64_t{1} << 63;
    // quadrant k: (sin, cos) = (s, c), (c, -s), (-s, -c), (-c, s)
    s = bits_double(((bs & ~swap) | (bc & swap)) ^ ((k << 62) & sign));
    c = bits_double(((bc & ~swap) | (bs & swap)) ^ (((k + 1) << 62) & sign));
}

} // namespace pedesis::detail
