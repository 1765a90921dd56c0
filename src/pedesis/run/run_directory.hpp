#pragma once
// What every run driver does first with its output directory: create it (snapshots/ is
// FrameWriters', made only for the formats that write there), remove results of an
// earlier run there that must not pass for this run's, and keep a copy of the config
// beside the results, one that runs again from anywhere: `pedesis run DIR/config.toml`
// (a relative [initial] file made absolute; docs/formats.md).
#include "pedesis/core/error.hpp"
#include "pedesis/io/atomic_file.hpp"
#include "pedesis/run/analysis_outputs.hpp"
#include "pedesis/setup/config_overrides.hpp"

#include <filesystem>
#include <fstream>
#include <optional>
#include <sstream>
#include <string>
#include <vector>

namespace pedesis {

// `stale_results`: the engine's own; the plots and the movie made of an earlier run there
// (analysis_outputs.hpp) go too. `config_text`: the config as run, where it is not the
// file's text (--set).
inline void prepare_run_directory(const std::filesystem::path& out_dir,
                                  const std::filesystem::path& config_path,
                                  const std::optional<std::string>& config_text,
                                  const std::vector<const char*>& stale_results) {
    std::error_code ec;
    std::filesystem::create_directories(out_dir, ec);
    if (ec)
        throw InputError(out_dir.string() + ": cannot create output directory: " + ec.message());
    for (const char* stale : stale_results) std::filesystem::remove(out_dir / stale, ec);
    for (const AnalysisOutput& plot : analysis_outputs)
        std::filesystem::remove(out_dir / plot.file, ec);
    std::filesystem::remove(out_dir / default_movie, ec);
    std::string text;
    if (config_text) {
        text = *config_text;
    } else {
        std::ifstream cfg(config_path);
        std::stringstream file;
        file << cfg.rdbuf();
        text = file.str();
    }
    text = with_initial_file_anchored(text, config_path);
    write_file_atomically(out_dir / "config.toml", [&](std::ostream& out) { out << text; });
}

} // namespace pedesis
