// libFuzzer target: see run_input in fuzz_run_input.hpp. With PEDESIS_FUZZ_RUN_PRINT set
// in the environment it prints each input's config to stderr first, to replay a finding
// with `pedesis run`.
#include "fuzz_run_input.hpp"

#include <cstdio>
#include <cstdlib>

extern "C" int LLVMFuzzerInitialize(int*, char***) {
    // One thread: a hang or a report then replays the same way on every machine (results
    // do not depend on the thread count, and these systems are too small to split).
    setenv("OMP_NUM_THREADS", "1", 0);
    return 0;
}

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    static const bool print = std::getenv("PEDESIS_FUZZ_RUN_PRINT") != nullptr;
    if (print) std::fprintf(stderr, "%s", pedesis::fuzz::run_config_text(data, size).c_str());
    return pedesis::fuzz::refusal_allowed([&] { pedesis::fuzz::run_input(data, size); });
}
