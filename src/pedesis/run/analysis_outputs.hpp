#pragma once
// The files `pedesis analyze KIND` and `pedesis render` write into a run directory unless
// told otherwise: results of the run there, which a new run into that directory removes
// (run_directory.hpp) so that a plot of the earlier run does not pass for one of this.
#include <array>
#include <string_view>

namespace pedesis {

struct AnalysisOutput {
    std::string_view kind; // pedesis analyze KIND
    const char* file;
};

inline constexpr std::array<AnalysisOutput, 8> analysis_outputs{{
    {"speed", "speed_distribution.png"},
    {"thermo", "thermo.png"},
    {"msd", "msd.png"},
    {"order", "order.png"},
    {"structure", "structure.png"},
    {"bond_order", "bond_order.png"},
    {"clusters", "clusters.png"},
    {"transport", "transport.png"},
}};

inline constexpr const char* default_movie = "movie.mp4"; // pedesis render RUN_DIR

} // namespace pedesis
