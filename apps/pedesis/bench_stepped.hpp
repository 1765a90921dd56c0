#pragma once
#include <CLI/CLI.hpp>

namespace pedesis::cli {
// `pedesis bench stepped`: particle-steps per second of the time-stepped hard-particle engine.
void add_bench_stepped(CLI::App& app);
} // namespace pedesis::cli
