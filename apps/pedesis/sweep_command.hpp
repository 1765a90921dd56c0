#pragma once
// `pedesis sweep SWEEP.toml`: a parameter sweep (run/sweep.hpp), serially, shared among
// the processes of `mpirun -np P`, or one shard of a job array (--shard I/N).
#include <CLI/CLI.hpp>

namespace pedesis::cli {

void add_sweep_command(CLI::App& app);

} // namespace pedesis::cli
