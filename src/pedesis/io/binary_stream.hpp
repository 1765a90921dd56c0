#pragma once
// Raw little helpers for the binary checkpoint format: plain values and vectors of
// trivially copyable types, written exactly (bit for bit) as they are in memory.
#include "pedesis/core/box.hpp"
#include "pedesis/core/error.hpp"
#include "pedesis/core/species.hpp"

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

// Bytes left in the stream: a length read from the file may not promise more (a corrupt
// or crafted length must fail here, not in a huge allocation).
inline std::uint64_t remaining(std::istream& in) {
    const auto here = in.tellg();
    if (here < 0) return 0;
    in.seekg(0, std::ios::end);
    const auto end = in.tellg();
    in.seekg(here);
    return end > here ? static_cast<std::uint64_t>(end - here) : 0;
}

template <class T> void get(std::istream& in, T& v) {
    static_assert(std::is_trivially_copyable_v<T>);
    in.read(reinterpret_cast<char*>(&v), sizeof(T));
    if (!in) throw InputError("checkpoint: file is truncated or corrupt");
}

template <class T> void get(std::istream& in, std::vector<T>& v) {
    std::uint64_t n = 0;
    get(in, n);
    if (n > remaining(in) / sizeof(T))
        throw InputError("checkpoint: corrupt array length " + std::to_string(n) +
                         " (more than the file holds)");
    v.resize(n);
    in.read(reinterpret_cast<char*>(v.data()), static_cast<std::streamsize>(n * sizeof(T)));
    if (!in) throw InputError("checkpoint: file is truncated or corrupt");
}

inline void get(std::istream& in, std::string& s) {
    std::uint64_t n = 0;
    get(in, n);
    if (n > (1u << 20) || n > remaining(in)) throw InputError("checkpoint: corrupt string length");
    s.resize(n);
    in.read(s.data(), static_cast<std::streamsize>(n));
    if (!in) throw InputError("checkpoint: file is truncated or corrupt");
}

// What every engine's checkpoint begins with: a magic number naming the engine, a
// format version and the dimension; then the species table and the box. Written and
// checked in one place so that the engines' checkpoints cannot drift apart.
inline void put_header(std::ostream& out, std::uint64_t magic, std::uint32_t version, int dim) {
    put(out, magic);
    put(out, version);
    put<std::int32_t>(out, dim);
}

// `engine` names the checkpoint kind in the message, e.g. "event". Versions from `oldest`
// (0: only `version`) to `version` are read; returns the file's.
inline std::uint32_t get_header(std::istream& in, std::uint64_t magic, std::uint32_t version,
                                int dim, const std::string& engine, std::uint32_t oldest = 0) {
    std::uint64_t m = 0;
    std::uint32_t v = 0;
    std::int32_t d = 0;
    get(in, m);
    if (m != magic) throw InputError("checkpoint: not a pedesis " + engine + " checkpoint");
    get(in, v);
    if (v > version || v < (oldest ? oldest : version))
        throw InputError("checkpoint: unsupported version " + std::to_string(v));
    get(in, d);
    if (d != dim)
        throw InputError("checkpoint: written for dimension " + std::to_string(d) +
                         ", config asks for " + std::to_string(dim));
    return v;
}

inline void put(std::ostream& out, const std::vector<Species>& table) {
    put<std::uint64_t>(out, table.size());
    for (const auto& s : table) {
        put(out, s.name);
        put(out, s.radius);
        put(out, s.mass);
    }
}

inline void get(std::istream& in, std::vector<Species>& table) {
    std::uint64_t n = 0;
    get(in, n);
    if (n == 0 || n > 65535) throw InputError("checkpoint: corrupt species count");
    table.resize(n);
    for (auto& s : table) {
        get(in, s.name);
        get(in, s.radius);
        get(in, s.mass);
        if (!(s.radius > 0.0) || !(s.mass > 0.0))
            throw InputError("checkpoint: corrupt species '" + s.name + "'");
    }
}

template <int D> void put(std::ostream& out, const Box<D>& box) {
    for (int a = 0; a < D; ++a) {
        put(out, box.length(a));
        put<std::uint8_t>(out, box.periodic(a));
    }
}

template <int D> void get(std::istream& in, Box<D>& box) {
    Vec<D> L;
    std::array<bool, D> periodic{};
    for (int a = 0; a < D; ++a) {
        std::uint8_t flag = 0;
        get(in, L[a]);
        get(in, flag);
        periodic[a] = flag != 0;
    }
    box = Box<D>(L, periodic); // checks the lengths
}

} // namespace pedesis::binary
