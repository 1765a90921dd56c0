#pragma once
#include <CLI/CLI.hpp>

namespace pedesis::cli {
// `pedesis validate`: the physics validation suite (python3 -m pedesis.validate).
void add_validate_command(CLI::App& app);
} // namespace pedesis::cli
