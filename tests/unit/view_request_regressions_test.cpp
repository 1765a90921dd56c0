// The viewer server's fuzz seeds and every request that once broke it
// (fuzz/{corpus,regressions}/fuzz_view_request/), sent through the fuzz target's own code
// (fuzz/fuzz_view_request_input.hpp) in every build: after each, the server must still
// answer a real request. Under `make sanitize` a memory or UB error in it fails the run.
#include "fuzz/fuzz_view_request_input.hpp"

#include <gtest/gtest.h>

#include <fstream>
#include <iterator>
#include <vector>

namespace fs = std::filesystem;

TEST(ViewRequestRegressions, TheServerAnswersAfterEveryInput) {
    int files = 0;
    for (const char* kind : {"corpus", "regressions"}) {
        const fs::path dir = fs::path(PEDESIS_SOURCE_DIR) / "fuzz" / kind / "fuzz_view_request";
        if (!fs::is_directory(dir)) continue;
        for (const auto& entry : fs::directory_iterator(dir)) {
            std::ifstream in(entry.path(), std::ios::binary);
            const std::vector<char> bytes(std::istreambuf_iterator<char>(in), {});
            SCOPED_TRACE(entry.path().string());
            EXPECT_NO_THROW(pedesis::fuzz::view_request_input(
                reinterpret_cast<const std::uint8_t*>(bytes.data()), bytes.size()));
            ++files;
        }
    }
    EXPECT_GE(files, 7);
}
