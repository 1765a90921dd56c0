#include "pedesis/core/stage.hpp"

#include <cstdio>
#include <cstdlib>
#include <cstring>

namespace pedesis {

void enter_stage(const char* name) {
    static const bool tracing = [] {
        const char* v = std::getenv("PEDESIS_TRACE_STAGES");
        return v != nullptr && std::strcmp(v, "1") == 0;
    }();
    if (!tracing) return;
    // one write per line, flushed: the reader may act on it before the stage ends
    std::fprintf(stderr, "pedesis: stage: %s\n", name);
    std::fflush(stderr);
}

} // namespace pedesis
