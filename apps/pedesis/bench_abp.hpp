#pragma once
#include <CLI/CLI.hpp>

namespace pedesis::cli {
// `pedesis bench abp`: throughput of the soft/active engine on the ABP tutorial's system
// scaled to N particles, no output.
void add_bench_abp(CLI::App& bench);
} // namespace pedesis::cli
