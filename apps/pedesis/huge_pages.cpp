// Large arrays in transparent huge pages. The engines' per-particle arrays are read in
// an order set by the physics, not by memory: at 10^6 particles nearly every access to
// a neighbour's data misses the translation cache with 4 KiB pages. Where the kernel
// offers transparent huge pages only on request (the default "madvise" setting), the
// program asks for them on every allocation of 4 MiB or more, before the memory is first
// touched; with 2 MiB pages the 3D event engine ran about 6% faster at N = 10^6 (median
// of 6 alternated pairs, range 0.92-1.13; docs/performance.md). Everything else is left to malloc,
// and every block, small or large, is released with free().
//
// This replaces the global operator new of the pedesis program only; the library and
// the Python module allocate as usual.
#include <cstdlib>
#include <new>

#include <sys/mman.h>

namespace {

constexpr std::size_t huge_page = std::size_t{2} << 20;
constexpr std::size_t huge_threshold = std::size_t{4} << 20;

void* allocate(std::size_t size) {
    if (size >= huge_threshold) {
        const std::size_t rounded = (size + huge_page - 1) / huge_page * huge_page;
        if (void* p = std::aligned_alloc(huge_page, rounded)) {
            madvise(p, rounded, MADV_HUGEPAGE); // a refusal only costs speed
            return p;
        }
        throw std::bad_alloc();
    }
    if (void* p = std::malloc(size == 0 ? 1 : size)) return p;
    throw std::bad_alloc();
}

} // namespace

void* operator new(std::size_t size) {
    return allocate(size);
}
void* operator new[](std::size_t size) {
    return allocate(size);
}
void* operator new(std::size_t size, const std::nothrow_t&) noexcept {
    try {
        return allocate(size);
    } catch (...) {
        return nullptr;
    }
}
void* operator new[](std::size_t size, const std::nothrow_t&) noexcept {
    try {
        return allocate(size);
    } catch (...) {
        return nullptr;
    }
}
void operator delete(void* p) noexcept {
    std::free(p);
}
void operator delete[](void* p) noexcept {
    std::free(p);
}
void operator delete(void* p, std::size_t) noexcept {
    std::free(p);
}
void operator delete[](void* p, std::size_t) noexcept {
    std::free(p);
}
void operator delete(void* p, const std::nothrow_t&) noexcept {
    std::free(p);
}
void operator delete[](void* p, const std::nothrow_t&) noexcept {
    std::free(p);
}
