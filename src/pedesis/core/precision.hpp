#pragma once
// The precision of the soft engine's pair math (`precision` in a config): "double"
// everywhere, or "mixed": pair math and the positions it reads in float, integration and
// the sums of energies and virials in double (soft/pair_rows_mixed.hpp).
#include <cstdint>
#include <optional>
#include <string_view>

namespace pedesis {

enum class Precision : std::uint8_t { full, mixed };

inline std::string_view precision_name(Precision p) {
    return p == Precision::mixed ? "mixed" : "double";
}

// The precision a config's word names; none for another word.
inline std::optional<Precision> precision_named(std::string_view word) {
    if (word == "double") return Precision::full;
    if (word == "mixed") return Precision::mixed;
    return std::nullopt;
}

} // namespace pedesis
