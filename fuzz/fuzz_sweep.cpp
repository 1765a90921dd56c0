// libFuzzer target: see sweep_input in fuzz_inputs.hpp.
#include "fuzz_inputs.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    return pedesis::fuzz::refusal_allowed([&] { pedesis::fuzz::sweep_input(data, size); });
}
