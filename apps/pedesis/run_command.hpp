#pragma once
#include <CLI/CLI.hpp>

namespace pedesis::cli {
// `pedesis run CONFIG.toml [--out DIR] [--restart CHECKPOINT]`
void add_run_command(CLI::App& app);
} // namespace pedesis::cli
