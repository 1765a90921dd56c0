#include "pedesis/core/huge_pages.hpp"

#include <cstdint>
#include <fstream>
#include <string>

#if defined(__linux__)
#include <sys/mman.h>
#endif

namespace pedesis {

void back_with_huge_pages(const void* data, std::size_t bytes) {
#if defined(__linux__) && defined(MADV_HUGEPAGE)
    // x86-64's one huge page size below 1 GiB (the PMD level)
    constexpr std::uintptr_t huge = std::uintptr_t{2} << 20;
    const auto start = reinterpret_cast<std::uintptr_t>(data);
    const std::uintptr_t lo = (start + huge - 1) & ~(huge - 1);
    const std::uintptr_t hi = (start + bytes) & ~(huge - 1);
    if (data == nullptr || hi <= lo) return;
    // Only whole huge pages inside the range: the pages at its ends may hold other
    // allocations, and a partly used huge page would count 2 MiB of resident memory.
    void* const first = reinterpret_cast<void*>(lo);
    const std::size_t length = hi - lo;
    ::madvise(first, length, MADV_HUGEPAGE);
#ifndef MADV_COLLAPSE
    constexpr int MADV_COLLAPSE = 25; // linux/mman.h since 6.1; older glibc headers lack it
#endif
    ::madvise(first, length, MADV_COLLAPSE);
#else
    (void)data;
    (void)bytes;
#endif
}

std::size_t huge_page_bytes() {
    std::ifstream in("/proc/self/smaps_rollup");
    std::string key;
    std::size_t kib = 0;
    while (in >> key) {
        if (key == "AnonHugePages:") {
            in >> kib;
            return kib * 1024;
        }
        in.ignore(1 << 12, '\n');
    }
    return 0;
}

} // namespace pedesis
