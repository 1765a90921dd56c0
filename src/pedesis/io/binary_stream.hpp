#pragma once
// Raw little helpers for the binary checkpoint format: plain values and vectors of
// trivially copyable types, written exactly (bit for bit) as they are in memory.
#include "pedesis/core/error.hpp"

#include <cstdint>
#include <istream>
#include <ostream>
#include <string>
#include <type_traits>
#include <vector>

namespace pedesis::binary {

template <class T> void put(std::ostream& out, const T& v) {
    static_assert(std::is_trivially_copyable_v<T>);
    out.write(reinterpret_cast<const char*>(&v), sizeof(T));
}

template <class T> void put(std::ostream& out, const std::vector<T>& v) {
    static_assert(std::is_trivially_copyable_v<T>);
    put<std::uint64_t>(out, v.size());
    out.write(reinterpret_cast<const char*>(v.data()),
              static_cast<std::streamsize>(v.size() * sizeof(T)));
}

inline void put(std::ostream& out, const std::string& s) {
    put<std::uint64_t>(out, s.size());
    out.write(s.data(), static_cast<std::streamsize>(s.size()));
}

template <class T> void get(std::istream& in, T& v) {
    static_assert(std::is_trivially_copyable_v<T>);
    in.read(reinterpret_cast<char*>(&v), sizeof(T));
    if (!in) throw InputError("checkpoint: file is truncated or corrupt");
}

template <class T> void get(std::istream& in, std::vector<T>& v) {
    std::uint64_t n = 0;
    get(in, n);
    if (n > (std::uint64_t{1} << 40) / sizeof(T))
        throw InputError("checkpoint: corrupt array length");
    v.resize(n);
    in.read(reinterpret_cast<char*>(v.data()), static_cast<std::streamsize>(n * sizeof(T)));
    if (!in) throw InputError("checkpoint: file is truncated or corrupt");
}

inline void get(std::istream& in, std::string& s) {
    std::uint64_t n = 0;
    get(in, n);
    if (n > (1u << 20)) throw InputError("checkpoint: corrupt string length");
    s.resize(n);
    in.read(s.data(), static_cast<std::streamsize>(n));
    if (!in) throw InputError("checkpoint: file is truncated or corrupt");
}

} // namespace pedesis::binary
