#pragma once
// The magic word that begins each engine's checkpoint payload (io/checkpoint_file.hpp is
// the envelope around it), and what a --restart given another engine's checkpoint is told.
#include <fmt/format.h>

#include <cstdint>
#include <string>

namespace pedesis {

constexpr std::uint64_t event_checkpoint_magic = 0x31304e5552444550ull;   // "PEDRUN01"
constexpr std::uint64_t stepped_checkpoint_magic = 0x31305054535f4550ull; // "PE_STP01"
constexpr std::uint64_t soft_checkpoint_magic = 0x31544653444550ull;      // "PEDSFT1"

// The engines as a config chooses them.
inline constexpr const char* event_engine = "the event engine (dynamics = \"event\")";
inline constexpr const char* stepped_engine = "the stepped engine (dynamics = \"stepped\")";
inline constexpr const char* soft_engine = "the soft engine (dynamics = \"brownian\", "
                                           "\"langevin\" or \"nve\")";

// Why a checkpoint that begins with `word` is not one `this_engine` continues from.
inline std::string foreign_checkpoint(std::uint64_t word, const char* this_engine) {
    const char* its = word == event_checkpoint_magic     ? event_engine
                      : word == stepped_checkpoint_magic ? stepped_engine
                      : word == soft_checkpoint_magic    ? soft_engine
                                                         : nullptr;
    if (!its) return fmt::format("not a checkpoint of {} (nor of another engine)", this_engine);
    return fmt::format("a checkpoint of {}, and this config runs {}; continue it with a config "
                       "of its engine",
                       its, this_engine);
}

} // namespace pedesis
