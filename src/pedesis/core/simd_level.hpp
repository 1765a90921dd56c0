#pragma once
// The instruction set the CPU kernels run with, chosen once per process. The default
// build targets any x86-64 (SSE2); the hot loops are also compiled for AVX2+FMA and
// AVX-512 (PEDESIS_SIMD_TARGET_*), and the best set this CPU offers is used unless the
// environment variable PEDESIS_SIMD names another ("sse2", "avx2", "avx512").
// Within one set results are bit-identical for any thread count and storage order.
// Between sets the last bits of forces differ: AVX2 and AVX-512 fuse multiply-adds and
// sum a row's own force in four lanes (docs/engines.md, "CPU kernel sets").
#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace pedesis {

enum class SimdLevel : int { sse2 = 0, avx2 = 1, avx512 = 2 };

const char* simd_name(SimdLevel level);
std::optional<SimdLevel> parse_simd_level(std::string_view name);

// The sets this CPU (and this build) can run, sse2 first.
std::vector<SimdLevel> available_simd_levels();

// The set in use: PEDESIS_SIMD if set, else the best available. Throws
// std::invalid_argument (with a message for the user) if PEDESIS_SIMD names an unknown
// set or one this CPU lacks; the CLI checks this at start (exit 2).
SimdLevel simd_level();

// For tests and benchmarks: use `level` from now on; throws std::invalid_argument if the
// CPU lacks it.
void set_simd_level(SimdLevel level);

} // namespace pedesis

// Function attributes that compile one function for a set. The kernels are written once,
// always_inline, and wrapped by one function per set; what they inline is compiled for
// that set, and nothing the default code calls is.
#if defined(__x86_64__) && defined(__GNUC__)
#define PEDESIS_SIMD_DISPATCH 1
#define PEDESIS_SIMD_TARGET_AVX2 [[gnu::target("avx2,fma")]]
#if defined(__clang__) // (clang's target attribute has no vector-width preference)
#define PEDESIS_SIMD_TARGET_AVX512 [[gnu::target("avx512f,avx512dq,avx512vl,avx512bw,avx2,fma")]]
#else
#define PEDESIS_SIMD_TARGET_AVX512                                                                 \
    [[gnu::target("avx512f,avx512dq,avx512vl,avx512bw,avx2,fma,prefer-vector-width=512")]]
#endif
#else
#define PEDESIS_SIMD_DISPATCH 0
#endif
