#pragma once
#include <CLI/CLI.hpp>

namespace pedesis::cli {
// `pedesis bench event`: throughput of the event-driven engine on a periodic box of
// equal spheres (or disks) at packing fraction eta, no output.
void add_bench_event(CLI::App& bench);
} // namespace pedesis::cli
