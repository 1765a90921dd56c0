// `pedesis sweep` under mpirun: the points shared among 2 and 3 processes give the same
// table as a serial run, byte for byte; bad input gives one message, not one per process,
// and exit code 2 (no process is left waiting).
#include "mpi/mpi_support.hpp"

namespace pedesis::test {
namespace {

class MpiSweep : public ScratchDir {};

// soft points (the engine whose threads and ranks matter most) and event points
const std::string soft_base =
    "dimension = 2\ndynamics = \"brownian\"\nseed = 1\n[box]\nlength = 20.0\n"
    "[[species]]\nname = \"A\"\ncount = 60\nradius = 0.5\n[initial]\npositions = \"random\"\n"
    "[[force]]\nname = \"harmonic\"\nk = 10.0\n[[force]]\nname = \"self_propulsion\"\n"
    "alpha = 1.0\n[[integrator]]\nname = \"brownian\"\nT = 0.1\ngamma = 1.0\n"
    "[[integrator]]\nname = \"brownian_rotation\"\nT = 0.1\ngamma = 1.0\n"
    "[run]\nsteps = 400\ndt = 0.005\n[output]\nlog_every = 100\nprogress = false\n"
    "formats = []\n";

TEST_F(MpiSweep, TwoAndThreeProcessesGiveTheSerialTable) {
    write("base.toml", soft_base);
    write("sweep.toml", "base = \"base.toml\"\n[vary]\n\"force.self_propulsion.alpha\" = "
                        "[0.5, 1.0, 2.0]\n\"box.length\" = [16.0, 20.0]\n");
    const CliResult serial = run_pedesis("sweep sweep.toml --out serial", dir, 300);
    ASSERT_EQ(serial.exit_code, 0) << serial.output;
    for (int p : {2, 3}) {
        const std::string out = "np" + std::to_string(p);
        const CliResult r = run_mpi(p, "sweep sweep.toml --out " + out, dir);
        ASSERT_EQ(r.exit_code, 0) << r.output;
        EXPECT_NE(r.output.find("on " + std::to_string(p) + " processes"), std::string::npos)
            << r.output;
        EXPECT_NE(r.output.find("(process " + std::to_string(p - 1) + ")"), std::string::npos)
            << r.output;
        EXPECT_EQ(read(out + "/sweep.csv"), read("serial/sweep.csv")) << p << " processes";
    }
    EXPECT_EQ(csv_columns(read("serial/sweep.csv")).cells.at("status").size(), 6u);
}

TEST_F(MpiSweep, BadInputGivesOneMessageAndExitCodeTwo) {
    write("base.toml", soft_base);
    write("bad.toml", "base = \"base.toml\"\n[vary]\n\"force.lj.epsilon\" = [1.0]\n");
    const CliResult r = run_mpi(3, "sweep bad.toml --out bad", dir);
    EXPECT_EQ(r.exit_code, 2) << r.output;
    std::size_t messages = 0;
    for (auto at = r.output.find("pedesis: error:"); at != std::string::npos;
         at = r.output.find("pedesis: error:", at + 1))
        ++messages;
    EXPECT_EQ(messages, 1u) << r.output;
    EXPECT_NE(r.output.find("has no [[force]] named 'lj'"), std::string::npos) << r.output;
}

// A point that fails on one process leaves no other waiting: exit 3 everywhere (within
// the 300 s kill timer of run_mpi), one closing message, the same table as serially.
TEST_F(MpiSweep, AFailingPointEndsEveryProcessWithExitThree) {
    write("failing.toml", sweep_with_a_failing_point(dir));
    const CliResult serial = run_pedesis("sweep failing.toml --out serial", dir, 120);
    ASSERT_EQ(serial.exit_code, 3) << serial.output;
    const CliResult r = run_mpi(2, "sweep failing.toml --out np2", dir);
    EXPECT_EQ(r.exit_code, 3) << r.output;
    const std::string closing = "a point of the sweep failed";
    EXPECT_NE(r.output.find(closing), std::string::npos) << r.output;
    EXPECT_EQ(r.output.find(closing), r.output.rfind(closing)) << r.output;
    // the table (statuses and summaries) is the serial one
    EXPECT_EQ(read("np2/sweep.csv"), read("serial/sweep.csv"));
}

// The hard-sphere engines run on one process: P copies of one run must not write one
// directory.
TEST_F(MpiSweep, AnEventRunUnderSeveralProcessesIsRefusedOnce) {
    const std::string config =
        std::string(PEDESIS_SOURCE_DIR) + "/examples/course_1_relaxation.toml";
    const CliResult r = run_mpi(2, "run '" + config + "' --out out", dir);
    EXPECT_EQ(r.exit_code, 2) << r.output;
    EXPECT_NE(r.output.find("the event engine runs on one process"), std::string::npos) << r.output;
    EXPECT_EQ(r.output.find("pedesis: error:"), r.output.rfind("pedesis: error:")) << r.output;
    EXPECT_FALSE(std::filesystem::exists(dir / "out"));
}

} // namespace
} // namespace pedesis::test
