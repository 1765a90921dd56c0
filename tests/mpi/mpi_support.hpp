#pragma once
// The CLI under mpirun, for the tests of label mpi.
#include "cli/cli_support.hpp"

#include "pedesis/io/xyz_reader.hpp"

#include <algorithm>
#include <cmath>

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

// The largest distance between the same particle in the last frames of two runs.
inline double largest_difference(const std::filesystem::path& a, const std::filesystem::path& b) {
    const XyzReader ra(a), rb(b);
    EXPECT_EQ(ra.frames(), rb.frames());
    double worst = 0.0;
    for (std::size_t k = 0; k < std::min(ra.frames(), rb.frames()); ++k) {
        const XyzFrame fa = ra.frame(k), fb = rb.frame(k);
        EXPECT_EQ(fa.size(), fb.size());
        for (std::size_t i = 0; i < std::min(fa.size(), fb.size()); ++i)
            for (int c = 0; c < 3; ++c)
                worst = std::max(worst, std::abs(fa.position[i][c] - fb.position[i][c]));
    }
    return worst;
}

} // namespace pedesis::test
