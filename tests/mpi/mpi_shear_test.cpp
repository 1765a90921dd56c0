// Lees-Edwards shear under mpirun: the domain decomposition has no sliding images, so a
// sheared run is refused on every process with one message (exit 2) naming the way out,
// and none waits for another.
#include "mpi/mpi_support.hpp"

namespace pedesis::test {
namespace {

class MpiShear : public ScratchDir {};

TEST_F(MpiShear, IsRefusedOnceWithTheWayOut) {
    write("sheared.toml", "dimension = 2\ndynamics = \"langevin\"\nseed = 2\n[box]\nlength = 24.0\n"
                          "shear_rate = 0.5\n[[species]]\nname = \"A\"\ncount = 200\n"
                          "radius = 0.5\n[initial]\nmin_distance = 0.9\n[[force]]\nname = \"wca\"\n"
                          "epsilon = 1.0\n[[integrator]]\nname = \"langevin\"\nT = 1.0\n"
                          "gamma = 1.0\n[run]\nsteps = 50\ndt = 0.005\n[output]\n"
                          "progress = false\n");
    const CliResult r = run_mpi(2, "run sheared.toml --out sheared", dir, 120);
    EXPECT_EQ(r.exit_code, 2) << r.output;
    std::size_t errors = 0;
    for (std::size_t at = r.output.find("pedesis: error:"); at != std::string::npos;
         at = r.output.find("pedesis: error:", at + 1))
        ++errors;
    EXPECT_EQ(errors, 1u) << r.output;
    EXPECT_NE(r.output.find("Lees–Edwards shear runs on one process: start it without mpirun"),
              std::string::npos)
        << r.output;
    EXPECT_FALSE(std::filesystem::exists(dir / "sheared" / "log.csv"));
}

} // namespace
} // namespace pedesis::test
