#pragma once
// What every fuzz target shares: the input as a file (the readers take paths, as users
// give them), and the one outcome allowed besides success.
#include "pedesis/core/error.hpp"

#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <string>
#include <unistd.h>

namespace pedesis::fuzz {

// A file of this process holding `data` (rewritten for every input).
inline std::filesystem::path as_file(const std::uint8_t* data, std::size_t size,
                                     const char* extension) {
    const auto path = std::filesystem::temp_directory_path() /
                      ("pedesis_fuzz_" + std::to_string(::getpid()) + extension);
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
