#pragma once
// `pedesis render`: a run directory's trajectory drawn frame by frame into an MP4, a GIF,
// or a directory of PNG files. Nothing is simulated again; the frames are the run's own.
#include "pedesis/render/painter.hpp"
#include "pedesis/render/run_directory.hpp"

#include <cstddef>
#include <filesystem>
#include <optional>
#include <string>
#include <utility>
#include <vector>

namespace pedesis::render {

enum class OutputKind { mp4, gif, png_directory };

// From --out as typed: a trailing '/' or an existing directory means PNG frames, else the
// extension (.mp4, .gif, any case) decides. InputError for anything else.
OutputKind output_kind(const std::string& out);

struct RenderRequest {
    std::filesystem::path run_dir;
    std::string out; // as typed: a trailing '/' matters
    SourceKind source = SourceKind::automatic;
    std::optional<std::pair<int, int>> size;
    double fps = 30.0;
    std::size_t every = 1;
    ColourBy colour = ColourBy::species;
    std::optional<double> speed_max;
    std::optional<Slab> slab;
    bool arrows = true;
};

struct RenderReport {
    std::size_t frames = 0; // frames written
    std::string source;     // the file(s) read
    std::filesystem::path out;
    OutputKind kind = OutputKind::mp4;
    int width = 0, height = 0;
    double speed_max = 0.0; // the colour bar's top, for --color speed
    std::vector<std::string> notes;
};

// Renders and returns what was done. Bad input (options, run directory, frames, no ffmpeg
// for a movie) is an InputError; a movie is complete under its name or not there at all.
RenderReport render(const RenderRequest& request);

} // namespace pedesis::render
