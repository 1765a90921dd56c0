#pragma once
// What every run driver does first with its output directory: create it (snapshots/ is
// FrameWriters', made only for the formats that write there), remove results of an
// earlier run there that must not pass for this run's, and keep a copy of the config
// beside the results, one that runs again from anywhere: `pedesis run DIR/config.toml`
// (a relative [initial] file made absolute; docs/formats.md).
#include "pedesis/core/error.hpp"
#include "pedesis/io/atomic_file.hpp"
#include "pedesis/io/resume_record.hpp"
#include "pedesis/run/analysis_outputs.hpp"
#include "pedesis/setup/config_overrides.hpp"

#include <filesystem>
#include <fstream>
#include <optional>
#include <sstream>
#include <string>
#include <vector>

namespace pedesis {

// Where a finished run's close keeps the checkpoint before its final one, until the close
// is complete: a run killed inside that close continues from it (--resume).
inline constexpr const char* previous_checkpoint_file = "checkpoint.previous.bin";

enum class RunStart { fresh, restarted, resumed };

// The text of the run directory's config.toml: `config_text` (the config as run, where
// --set changed it) or the file's, with a relative [initial] file made absolute.
inline std::string run_directory_config(const std::filesystem::path& config_path,
                                        const std::optional<std::string>& config_text) {
    std::string text;
    if (config_text) {
        text = *config_text;
    } else {
        std::ifstream cfg(config_path);
        std::stringstream file;
        file << cfg.rdbuf();
        text = file.str();
    }
    return with_initial_file_anchored(text, config_path);
}

// `stale_results`: the engine's own; the plots and the movie made of an earlier run there
// (analysis_outputs.hpp) go too, and so do the record of an earlier run's checkpoints
// (io/resume_record.hpp) and, for a fresh run (`fresh`, not --restart, whose checkpoint
// may be this directory's), its checkpoint. `config_text`: the config as run, where it is
// not the file's text (--set). A run continued in place (--resume) calls it with
// `resumed`: its own checkpoints stay.
inline void prepare_run_directory(const std::filesystem::path& out_dir,
                                  const std::filesystem::path& config_path,
                                  const std::optional<std::string>& config_text,
                                  const std::vector<const char*>& stale_results, RunStart start) {
    std::error_code ec;
    std::filesystem::create_directories(out_dir, ec);
    if (ec)
        throw InputError(out_dir.string() + ": cannot create output directory: " + ec.message());
    for (const char* stale : stale_results) std::filesystem::remove(out_dir / stale, ec);
    if (start != RunStart::resumed) {
        std::filesystem::remove(out_dir / checkpoint_record_file, ec);
        std::filesystem::remove(out_dir / previous_checkpoint_file, ec);
    }
    if (start == RunStart::fresh) std::filesystem::remove(out_dir / "checkpoint.bin", ec);
    for (const AnalysisOutput& plot : analysis_outputs)
        std::filesystem::remove(out_dir / plot.file, ec);
    std::filesystem::remove(out_dir / default_movie, ec);
    const std::string text = run_directory_config(config_path, config_text);
    write_file_atomically(out_dir / "config.toml", [&](std::ostream& out) { out << text; });
}

// The checkpoint a finished run's close is about to replace, kept as
// previous_checkpoint_file (a hard link where the file system has them); nothing where
// the run wrote none.
inline void keep_previous_checkpoint(const std::filesystem::path& dir) {
    const std::filesystem::path checkpoint = dir / "checkpoint.bin";
    const std::filesystem::path kept = dir / previous_checkpoint_file;
    std::error_code ec;
    std::filesystem::remove(kept, ec);
    if (!std::filesystem::exists(checkpoint, ec)) return;
    std::filesystem::create_hard_link(checkpoint, kept, ec);
    if (ec) std::filesystem::copy_file(checkpoint, kept, ec);
    if (ec) throw InputError(kept.string() + ": cannot keep the checkpoint: " + ec.message());
}

} // namespace pedesis
