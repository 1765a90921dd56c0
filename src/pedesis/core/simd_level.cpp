#include "pedesis/core/simd_level.hpp"

#include <atomic>
#include <cstdlib>
#include <stdexcept>

namespace pedesis {

namespace {

bool cpu_has(SimdLevel level) {
#if PEDESIS_SIMD_DISPATCH
    // libgcc's checks include the operating system's support (XGETBV) for the registers
    switch (level) {
    case SimdLevel::sse2:
        return true;
    case SimdLevel::avx2:
        return __builtin_cpu_supports("avx2") && __builtin_cpu_supports("fma");
    case SimdLevel::avx512:
        return cpu_has(SimdLevel::avx2) && __builtin_cpu_supports("avx512f") &&
               __builtin_cpu_supports("avx512dq") && __builtin_cpu_supports("avx512vl") &&
               __builtin_cpu_supports("avx512bw");
    }
    return false;
#else
    return level == SimdLevel::sse2;
#endif
}

std::string names_of(const std::vector<SimdLevel>& levels) {
    std::string s;
    for (SimdLevel l : levels) s += (s.empty() ? "" : ", ") + std::string(simd_name(l));
    return s;
}

SimdLevel chosen_at_start() {
    const std::vector<SimdLevel> here = available_simd_levels();
    const char* asked = std::getenv("PEDESIS_SIMD");
    if (asked == nullptr || *asked == '\0') return here.back();
    const std::optional<SimdLevel> level = parse_simd_level(asked);
    if (!level)
        throw std::invalid_argument("PEDESIS_SIMD = \"" + std::string(asked) +
                                    "\": not a kernel set (sse2, avx2 or avx512)");
    if (!cpu_has(*level))
        throw std::invalid_argument("PEDESIS_SIMD = \"" + std::string(asked) +
                                    "\": this CPU or build runs only " + names_of(here));
    return *level;
}

// -1 until first asked
std::atomic<int> current{-1};

} // namespace

const char* simd_name(SimdLevel level) {
    switch (level) {
    case SimdLevel::sse2:
        return "sse2";
    case SimdLevel::avx2:
        return "avx2";
    case SimdLevel::avx512:
        return "avx512";
    }
    return "?";
}

std::optional<SimdLevel> parse_simd_level(std::string_view name) {
    for (SimdLevel l : {SimdLevel::sse2, SimdLevel::avx2, SimdLevel::avx512})
        if (name == simd_name(l)) return l;
    return std::nullopt;
}

std::vector<SimdLevel> available_simd_levels() {
    std::vector<SimdLevel> levels;
    for (SimdLevel l : {SimdLevel::sse2, SimdLevel::avx2, SimdLevel::avx512})
        if (cpu_has(l)) levels.push_back(l);
    return levels;
}

SimdLevel simd_level() {
    int level = current.load(std::memory_order_relaxed);
    if (level < 0) {
        level = static_cast<int>(chosen_at_start());
        current.store(level, std::memory_order_relaxed);
    }
    return static_cast<SimdLevel>(level);
}

void set_simd_level(SimdLevel level) {
    if (!cpu_has(level))
        throw std::invalid_argument(std::string("kernel set ") + simd_name(level) +
                                    ": this CPU or build runs only " +
                                    names_of(available_simd_levels()));
    current.store(static_cast<int>(level), std::memory_order_relaxed);
}

} // namespace pedesis
