#pragma once
// What the command line adds to a config for every engine's run.
#include <filesystem>
#include <optional>

namespace pedesis {

struct RunOptions {
    std::filesystem::path out_dir;
    std::optional<std::filesystem::path> restart; // checkpoint to continue from
    std::filesystem::path config_path;
};

} // namespace pedesis
