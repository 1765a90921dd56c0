#pragma once
// Four doubles in one vector, in GCC's vector types: a kernel written with them once is
// compiled for the registers of each kernel set it is inlined into (core/simd_level.hpp;
// AVX2: one ymm per four lanes). Arithmetic on lanes rounds each lane as the scalar
// expression does, except that GCC contracts a * b + c into a fused multiply-add
// wherever the target has FMA (in ISO C++ mode too): a kernel that must give the
// scalar code's bits is compiled for a target without FMA (event/pair_times.hpp).
#include <cmath>
#include <cstdint>

namespace pedesis {

using lanes4 = double __attribute__((vector_size(32)));
using mask4 = std::int64_t __attribute__((vector_size(32)));
// Eight floats (the mixed-precision pair rows, soft/pair_rows_mixed.hpp), four of them,
// and the mask of eight.
using lanes8f = float __attribute__((vector_size(32)));
using lanes4f = float __attribute__((vector_size(16)));
using mask8 = std::int32_t __attribute__((vector_size(32)));

[[gnu::always_inline]] inline lanes4 lane_sqrt(lanes4 x) {
    lanes4 r;
    for (int l = 0; l < 4; ++l) r[l] = std::sqrt(x[l]);
    return r;
}
[[gnu::always_inline]] inline lanes8f lane_sqrt(lanes8f x) {
    lanes8f r;
    for (int l = 0; l < 8; ++l) r[l] = std::sqrt(x[l]);
    return r;
}

// yes where m is set (all ones), no elsewhere
[[gnu::always_inline]] inline lanes4 select(mask4 m, lanes4 yes, lanes4 no) {
    return reinterpret_cast<lanes4>((reinterpret_cast<mask4>(yes) & m) |
                                    (reinterpret_cast<mask4>(no) & ~m));
}
[[gnu::always_inline]] inline lanes8f select(mask8 m, lanes8f yes, lanes8f no) {
    return reinterpret_cast<lanes8f>((reinterpret_cast<mask8>(yes) & m) |
                                     (reinterpret_cast<mask8>(no) & ~m));
}

} // namespace pedesis
