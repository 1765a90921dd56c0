#pragma once
#include <CLI/CLI.hpp>

namespace pedesis::cli {
// `pedesis analyze`: plots of a run directory's outputs (speed, thermo, msd, order).
void add_analyze_command(CLI::App& app);
} // namespace pedesis::cli
