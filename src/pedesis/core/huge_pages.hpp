#pragma once
// Large arrays read at random (the event engine's per-particle state at 10^6 particles:
// each event touches a few particles anywhere in some 200 MB) spend much of their time
// in page-table walks with 4 KiB pages: the TLB covers a few MiB. Linux backs memory with
// 2 MiB pages where a program asks for it (transparent huge pages in "madvise" mode, the
// usual default), and malloc does not ask.
#include <cstddef>
#include <vector>

namespace pedesis {

// Asks the kernel to back the whole 2 MiB pages inside [data, data + bytes) with huge
// pages from now on, and to collapse the ones already in use (MADV_COLLAPSE, Linux 6.1
// and later; a copy, about 0.1 s per GiB). The contents do not change. Ranges smaller
// than one huge page, kernels without the feature and THP set to "never" leave the
// memory as it was: the call is only advice, and never fails.
void back_with_huge_pages(const void* data, std::size_t bytes);

template <class T, class A> void back_with_huge_pages(const std::vector<T, A>& v) {
    back_with_huge_pages(v.data(), v.size() * sizeof(T));
}

// Bytes of this process's memory backed by huge pages now (AnonHugePages of
// /proc/self/smaps_rollup); 0 where the system does not say.
std::size_t huge_page_bytes();

} // namespace pedesis
