// libFuzzer target: see resume_input in fuzz_resume_input.hpp.
#include "fuzz_resume_input.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    return pedesis::fuzz::refusal_allowed([&] { pedesis::fuzz::resume_input(data, size); });
}
