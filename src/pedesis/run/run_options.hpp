#pragma once
// What the command line adds to a config for every engine's run.
#include "pedesis/core/communicator.hpp"
#include "pedesis/io/resume_record.hpp"

#include <fmt/format.h>

#include <filesystem>
#include <map>
#include <optional>
#include <string>
#include <vector>

namespace pedesis {

struct RunOptions {
    std::filesystem::path out_dir;
    std::optional<std::filesystem::path> restart; // checkpoint to continue from
    std::filesystem::path config_path;
    // The config as run, where it is not config_path's text (--set): the run directory's
    // config.toml.
    std::optional<std::string> config_text;
    // The --set that gave each key, by its dotted path ("run.time" -> "--set run.time=10"),
    // for messages that say what to change.
    std::map<std::string, std::string> set_keys;
    // The processes one soft-engine run is divided among (null: this one alone). Only
    // process 0 writes the run directory and prints; the others compute.
    Communicator* comm = nullptr;
    // `--device`: where a soft-engine run steps ("cpu" or "gpu"), over the config's
    // [run] device.
    std::optional<std::string> device;
    // `--resume`: the marks of out_dir's checkpoints (checkpoint.outputs.json), `restart`
    // being one of that directory's checkpoints. Its outputs are cut back to that
    // checkpoint's marks and continued in place (run/resume.hpp).
    std::optional<std::vector<OutputMarks>> resume_marks;
    // [output] checkpoint_seconds: a checkpoint at the first row or frame after each
    // interval of wall-clock time (0: none).
    double checkpoint_seconds = 0.0;
};

// A --restart whose checkpoint already meets the [run] stop condition `why` ("time"):
// which one, and where to raise it, on the command line where a --set gave it.
inline std::string raise_stop(const RunOptions& o, const std::string& why) {
    const auto set = o.set_keys.find("run." + why);
    if (set == o.set_keys.end())
        return fmt::format("stop condition ({}); raise it in [run] to continue", why);
    return fmt::format("stop condition ({}, from {}); raise it (--set run.{}=...) to continue", why,
                       set->second, why);
}

} // namespace pedesis
