// libFuzzer target: see view_request_input in fuzz_view_request_input.hpp.
#include "fuzz_view_request_input.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    pedesis::fuzz::view_request_input(data, size);
    return 0;
}
