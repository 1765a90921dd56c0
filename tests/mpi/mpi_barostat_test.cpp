// [barostat] under mpirun: refused with exit 2 and one message naming the table (the
// domains would have to follow the box), before any output; on one process under mpirun
// the run is the serial one.
#include "mpi/mpi_support.hpp"

using namespace pedesis::test;

class MpiBarostat : public ScratchDir {};

TEST_F(MpiBarostat, TwoProcessesAreRefusedWithAMessage) {
    const std::string example = std::string(PEDESIS_SOURCE_DIR) + "/examples/lj_npt.toml";
    const CliResult r = run_mpi(2, "run '" + example + "' --out two", dir, 120);
    EXPECT_EQ(r.exit_code, 2) << r.output;
    EXPECT_NE(r.output.find("table 'barostat': the barostat runs on one process"),
              std::string::npos)
        << r.output;
    EXPECT_EQ(r.output.find("internal error"), std::string::npos) << r.output;
    EXPECT_FALSE(std::filesystem::exists(dir / "two" / "log.csv"));
    const CliResult one = run_mpi(
        1, "run '" + example + "' --out one --set run.steps=200 --set output.progress=false", dir,
        120);
    EXPECT_EQ(one.exit_code, 0) << one.output;
}
