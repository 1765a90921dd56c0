#pragma once
// What the viewer page reads of a run besides frame arrays, in the JSON the server sends
// and the exported page embeds: the run's description and its log.
#include "pedesis/render/frame_source.hpp"

#include <nlohmann/json.hpp>

#include <filesystem>

namespace pedesis::view {

// run, source, dimension, box_lo, box_length, periodic, frames, particles, species
// (name, radius), fields (what the frames can give: frame_arrays.hpp), from frame 0; and
// scenery, from the run's config.toml (render/scenery.hpp): containers (shape, radius,
// centre, axis), traps (centres) and gravity (unit directions of the pull).
nlohmann::json run_info(render::FrameSource& source, const render::Frame& first,
                        const std::filesystem::path& run_dir);

// The run directory's log.csv (or the log.csv.part of a run still going) as
// {"columns": [...], "rows": [[...], ...]}; empty when there is none.
nlohmann::json read_log(const std::filesystem::path& run_dir);

} // namespace pedesis::view
