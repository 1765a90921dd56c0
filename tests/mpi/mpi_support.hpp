#pragma once
// The CLI under mpirun, for the tests of label mpi.
#include "cli/cli_support.hpp"

namespace pedesis::test {

// mpirun as root needs --allow-run-as-root; --oversubscribe lets 3 processes share the
// 2 cores of a small machine. The kill timer turns a deadlock into a failure.
inline CliResult run_mpi(int processes, const std::string& args, const std::filesystem::path& cwd,
                         int seconds = 300) {
    return shell("timeout -s KILL " + std::to_string(seconds) + " '" +
                     std::string(PEDESIS_MPIEXEC) + "' --allow-run-as-root --oversubscribe -np " +
                     std::to_string(processes) + " '" + PEDESIS_BINARY + "' " + args,
                 cwd);
}

} // namespace pedesis::test
