#pragma once
#include <CLI/CLI.hpp>

namespace pedesis::cli {
// `pedesis view`: a run directory in the browser (docs/view.md).
void add_view_command(CLI::App& app);
} // namespace pedesis::cli
