#pragma once
#include <CLI/CLI.hpp>

namespace pedesis::cli {
// `pedesis render`: movie or PNG frames of a run directory's trajectory (Cairo, ffmpeg).
void add_render_command(CLI::App& app);
} // namespace pedesis::cli
