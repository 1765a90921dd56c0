#pragma once
// The machine's physical memory, for refusing inputs that cannot fit before anything
// is allocated for them (a message with the estimate beats std::bad_alloc an hour in).
#include <unistd.h>

namespace pedesis {

// In bytes; 0 where the system does not say.
inline double physical_memory_bytes() {
    const long pages = ::sysconf(_SC_PHYS_PAGES), page = ::sysconf(_SC_PAGE_SIZE);
    return pages > 0 && page > 0 ? static_cast<double>(pages) * static_cast<double>(page) : 0.0;
}

} // namespace pedesis
