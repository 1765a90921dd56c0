#pragma once
// The natural logarithm of the integrators' Box-Muller, for uniforms in (0, 1]: a loop
// of it runs several values per SIMD instruction, where the C library's log is one call
// per value (in the 2D ABP step, those calls and the chains waiting on them were a
// tenth of the time). Plain double arithmetic, no fused multiply-adds: every kernel set
// and every vector width gives each value the same bits. Error below one ulp.
#include <bit>
#include <cstdint>

namespace pedesis {

// ln x for a positive normal double x (not for 0, subnormals, infinities or NaN).
inline double noise_log(double x) {
    // x = 2^k m with m in [sqrt(1/2), sqrt(2)): adding the distance from sqrt(1/2)'s
    // bits to 1's carries into the exponent field exactly when x's mantissa is at least
    // sqrt(2), so that field then holds k + 1023, and the low 52 bits put back on
    // sqrt(1/2)'s give m.
    constexpr std::uint64_t one = 0x3ff0000000000000, sqrt_half = 0x3fe6a09e667f3bcd;
    constexpr std::uint64_t mantissa = 0x000fffffffffffff;
    const std::uint64_t shifted = std::bit_cast<std::uint64_t>(x) + (one - sqrt_half);
    const double m = std::bit_cast<double>((shifted & mantissa) + sqrt_half);
    // k as a double without an integer conversion (none is packed before AVX-512):
    // 2^52 + (k + 1023) has the field as its low bits
    const double k =
        std::bit_cast<double>(0x4330000000000000 | (shifted >> 52)) - (0x1p52 + 1023.0);
    // ln m = ln((1 + s) / (1 - s)) = 2 s + 2 s^3 / 3 + ..., s = f / (2 + f), f = m - 1,
    // |s| < 0.172; the series' tail as a minimax polynomial in s^2 (fdlibm's
    // coefficients), and ln 2 in two parts so that k ln 2 loses nothing
    const double f = m - 1.0;
    const double s = f / (2.0 + f);
    const double z = s * s;
    const double tail =
        z * (6.666666666666735130e-01 +
             z * (3.999999999940941908e-01 +
                  z * (2.857142874366239149e-01 +
                       z * (2.222219843214978396e-01 +
                            z * (1.818357216161805012e-01 +
                                 z * (1.531383769920937332e-01 + z * 1.479819860511658591e-01))))));
    const double half_f2 = 0.5 * f * f;
    constexpr double ln2_hi = 6.93147180369123816490e-01, ln2_lo = 1.90821492927058770002e-10;
    return k * ln2_hi - ((half_f2 - (s * (half_f2 + tail) + k * ln2_lo)) - f);
}

} // namespace pedesis
