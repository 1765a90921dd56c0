#pragma once
// `pedesis view RUN --export FILE.html`: the viewer page with the run inside, one file
// that opens offline in any browser (for a course page or an e-mail).
#include <cstdint>
#include <filesystem>

namespace pedesis::view {

struct ExportOptions {
    std::filesystem::path run_dir;
    std::filesystem::path output;
    std::size_t every = 1; // every k-th frame (the last is always kept)
    // Larger pages take browsers tens of seconds and gigabytes to open.
    std::uint64_t max_bytes = std::uint64_t{256} << 20;
};

// Writes the page (atomically: a file under the final name is complete). InputError if
// the run has no trajectory, the build has no page, or the data would pass max_bytes
// (the message gives the estimate and the --every that would fit).
void export_page(const ExportOptions& options);

} // namespace pedesis::view
