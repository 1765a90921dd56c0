#pragma once
// What every run driver does first with its output directory: create it (snapshots/ is
// FrameWriters', made only for the formats that write there), remove results of an
// earlier run there that must not pass for this run's, and keep a copy of the config
// beside the results.
#include "pedesis/core/error.hpp"
#include "pedesis/io/atomic_file.hpp"

#include <filesystem>
#include <fstream>
#include <sstream>
#include <vector>

namespace pedesis {

inline void prepare_run_directory(const std::filesystem::path& out_dir,
                                  const std::filesystem::path& config_path,
                                  const std::vector<const char*>& stale_results) {
    std::error_code ec;
    std::filesystem::create_directories(out_dir, ec);
    if (ec)
        throw InputError(out_dir.string() + ": cannot create output directory: " + ec.message());
    for (const char* stale : stale_results) std::filesystem::remove(out_dir / stale, ec);
    std::ifstream cfg(config_path);
    std::stringstream text;
    text << cfg.rdbuf();
    write_file_atomically(out_dir / "config.toml", [&](std::ostream& out) { out << text.str(); });
}

} // namespace pedesis
