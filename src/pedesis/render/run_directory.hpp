#pragma once
// Finds the trajectory of a run directory: the best of what the run wrote.
#include "pedesis/render/frame_source.hpp"
#include "pedesis/render/scenery.hpp"

#include <filesystem>
#include <memory>
#include <string>
#include <vector>

namespace pedesis::render {

enum class SourceKind { automatic, gsd, xyz, json };

struct OpenedRun {
    std::unique_ptr<FrameSource> source;
    std::vector<std::string> notes; // worth telling the user (an unfinished run's file, ...)
    Scenery scenery;                // from config.toml: containers, traps, gravity
};

// The facts config.toml gives, each left unknown when the file is missing or does not say
// (a broken config does not stop a render: the frames themselves are what counts).
RunFacts read_run_facts(const std::filesystem::path& config_toml);

// `automatic` takes trajectory.gsd (directors, every soft run), else trajectory.xyz, else
// snapshots/frame_*.json; for each, the complete file, else the ".part" file an
// unfinished run leaves. Another kind takes that format only. A missing directory, one
// without any trajectory, or one whose trajectory has no frames is an InputError.
OpenedRun open_run_directory(const std::filesystem::path& dir, SourceKind kind);

} // namespace pedesis::render
