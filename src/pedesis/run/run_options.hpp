#pragma once
// What the command line adds to a config for every engine's run.
#include "pedesis/core/communicator.hpp"

#include <filesystem>
#include <optional>
#include <string>

namespace pedesis {

struct RunOptions {
    std::filesystem::path out_dir;
    std::optional<std::filesystem::path> restart; // checkpoint to continue from
    std::filesystem::path config_path;
    // The config as run, where it is not config_path's text (--set): the run directory's
    // config.toml.
    std::optional<std::string> config_text;
    // The processes one soft-engine run is divided among (null: this one alone). Only
    // process 0 writes the run directory and prints; the others compute.
    Communicator* comm = nullptr;
    // `--device`: where a soft-engine run steps ("cpu" or "gpu"), over the config's
    // [run] device.
    std::optional<std::string> device;
};

} // namespace pedesis
