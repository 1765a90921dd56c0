#pragma once
// A run directory's config.toml as a table for the renderer's forgiving readers
// (run_directory.cpp, scenery.cpp): missing or unparsable gives nothing, never an error.
#include <toml++/toml.h>

#include <filesystem>
#include <optional>
#include <system_error>

namespace pedesis::render {

inline std::optional<toml::table> parse_config_table(const std::filesystem::path& file) {
    std::error_code ec;
    if (!std::filesystem::is_regular_file(file, ec)) return std::nullopt;
    try {
        return toml::parse_file(file.string());
    } catch (const toml::parse_error&) {
        return std::nullopt;
    }
}

// 2 or 3 as the run reads it (3 when absent; anything but 2 would not run).
inline int config_dimension(const toml::table& config) {
    return config["dimension"].value<int>().value_or(3) == 2 ? 2 : 3;
}

} // namespace pedesis::render
