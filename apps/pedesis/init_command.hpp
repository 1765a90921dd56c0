#pragma once
#include <CLI/CLI.hpp>

namespace pedesis::cli {
// `pedesis init random`: writes an initial configuration in the ABP tutorial's JSON.
void add_init_command(CLI::App& app);
} // namespace pedesis::cli
