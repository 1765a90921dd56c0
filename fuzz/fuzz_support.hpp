#pragma once
// What every fuzz target shares: the input as a file (the readers take paths, as users
// give them), and the one outcome allowed besides success.
#include "pedesis/core/error.hpp"

#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <string>
#include <unistd.h>
#include <vector>

namespace pedesis::fuzz {

// Removes `path` (a file or a directory) when the process exits normally, as libFuzzer
// does at the end of its runs. Each target keeps one scratch path per process and
// rewrites it for every input; without this every run left its own behind in /tmp. (A
// crash skips it, and the input that crashed is the file to look at.)
inline void remove_at_exit(const std::filesystem::path& path) {
    static std::vector<std::filesystem::path> paths;
    static const bool registered = [] {
        std::atexit([] {
            std::error_code ignored;
            for (const auto& p : paths) std::filesystem::remove_all(p, ignored);
        });
        return true;
    }();
    (void)registered;
    if (std::find(paths.begin(), paths.end(), path) == paths.end()) paths.push_back(path);
}

// A file of this process holding `data` (rewritten for every input).
inline std::filesystem::path as_file(const std::uint8_t* data, std::size_t size,
                                     const char* extension) {
    const auto path = std::filesystem::temp_directory_path() /
                      ("pedesis_fuzz_" + std::to_string(::getpid()) + extension);
    remove_at_exit(path);
    std::ofstream(path, std::ios::binary | std::ios::trunc)
        .write(reinterpret_cast<const char*>(data), static_cast<std::streamsize>(size));
    return path;
}

// Runs `f`; an InputError is the reader refusing the input, which is fine.
template <class F> int refusal_allowed(F&& f) {
    try {
        f();
    } catch (const InputError&) {
    }
    return 0;
}

} // namespace pedesis::fuzz
