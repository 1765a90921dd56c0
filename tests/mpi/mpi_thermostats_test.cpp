// The NVT thermostats (`bussi`, `nose_hoover`) on 2 and 3 MPI processes: the kinetic
// energy they rescale by is summed over the processes, every process draws Bussi's same
// random numbers and keeps the same chain, so the run follows the one-process trajectory
// (to the rounding of the force and energy sums, as mpi_run_test.cpp's bound says), and
// its log's conserved_energy is the one-process value. A checkpoint of a 2-process run
// (of the step grid) continues on 2 processes bit for bit: the bath's state is in it.
#include "mpi/mpi_support.hpp"

#include "pedesis/io/xyz_reader.hpp"

#include <algorithm>
#include <cmath>
#include <string>

namespace pedesis::test {
namespace {

class MpiThermostats : public ScratchDir {};

// A 3D LJ liquid of 864 particles (fcc, rho = 0.8442) started hot.
std::string lj_config(const std::string& thermostat, int steps = 100) {
    return "dimension = 3\ndynamics = \"" + thermostat +
           "\"\nseed = 5\n[box]\nlength = 10.0776\n"
           "[[species]]\nname = \"A\"\ncount = 864\nradius = 0.5\n"
           "[initial]\npositions = \"fcc\"\nvelocities = \"maxwell_boltzmann\"\n"
           "temperature = 1.5\n"
           "[[force]]\nname = \"lj\"\nepsilon = 1.0\nsigma = 1.0\ncutoff = 2.5\nshift = true\n"
           "[[integrator]]\nname = \"" +
           thermostat +
           "\"\nT = 0.8\ntau = 0.05\n"
           "[neighbor_list]\nskin = 0.3\n[run]\nsteps = " +
           std::to_string(steps) +
           "\ndt = 0.004\n"
           "[output]\nlog_every = 20\nsnapshot_every = 50\ncheckpoint_every = 50\n"
           "formats = [\"xyz\"]\n"
           "progress = false\n";
}

TEST_F(MpiThermostats, TwoAndThreeProcessesFollowTheSerialRun) {
    for (const std::string thermostat : {"bussi", "nose_hoover"}) {
        write("lj.toml", lj_config(thermostat));
        const CliResult serial = run_pedesis("run lj.toml --out serial_" + thermostat, dir, 120);
        ASSERT_EQ(serial.exit_code, 0) << serial.output;
        const CsvColumns one = csv_columns(read("serial_" + thermostat + "/log.csv"));
        for (int p : {2, 3}) {
            const std::string out = "np" + std::to_string(p) + "_" + thermostat;
            const CliResult r = run_mpi(p, "run lj.toml --out " + out, dir, 120);
            ASSERT_EQ(r.exit_code, 0) << r.output;
            // the bound of mpi_run_test.cpp: sums in another order, 1e-16 per step
            EXPECT_LT(largest_difference(dir / ("serial_" + thermostat + "/trajectory.xyz"),
                                         dir / (out + "/trajectory.xyz")),
                      1e-9)
                << thermostat << " on " << p;
            const CsvColumns many = csv_columns(read(out + "/log.csv"));
            const auto h1 = one.numbers("conserved_energy"), hp = many.numbers("conserved_energy");
            const auto t1 = one.numbers("temperature"), tp = many.numbers("temperature");
            ASSERT_EQ(h1.size(), hp.size());
            for (std::size_t k = 0; k < h1.size(); ++k) {
                EXPECT_NEAR(hp[k], h1[k], 1e-8 * std::abs(h1[k])) << thermostat << " row " << k;
                EXPECT_NEAR(tp[k], t1[k], 1e-9) << thermostat << " row " << k;
            }
            // the thermostat acted: from 1.5 towards 0.8
            EXPECT_LT(tp.back(), 1.2) << thermostat;
        }
    }
}

TEST_F(MpiThermostats, ACheckpointOfTwoProcessesContinuesBitForBitOnTwo) {
    for (const std::string thermostat : {"bussi", "nose_hoover"}) {
        write("half.toml", lj_config(thermostat, 50));
        write("whole.toml", lj_config(thermostat, 100));
        const std::string whole = "whole_" + thermostat, half = "half_" + thermostat;
        ASSERT_EQ(run_mpi(2, "run whole.toml --out " + whole, dir, 120).exit_code, 0);
        ASSERT_EQ(run_mpi(2, "run half.toml --out " + half, dir, 120).exit_code, 0);
        const std::string cont = "cont_" + thermostat;
        const CliResult r = run_mpi(
            2, "run whole.toml --out " + cont + " --restart " + half + "/checkpoint.bin", dir, 120);
        ASSERT_EQ(r.exit_code, 0) << r.output;
        // the continuation's frame at step 100 and its log rows after step
        // 50, bit for bit
        const XyzReader w(dir / whole / "trajectory.xyz"), c(dir / cont / "trajectory.xyz");
        ASSERT_EQ(c.frames(), 1u); // step 100 (the checkpoint's step 50 is the half run's)
        const XyzFrame fw = w.frame(w.frames() - 1), fc = c.frame(0);
        ASSERT_EQ(fw.size(), fc.size());
        ASSERT_EQ(fw.velocity.size(), fw.size());
        EXPECT_TRUE(fw.position == fc.position && fw.velocity == fc.velocity) << thermostat;
        const std::string la = read(whole + "/log.csv"), lb = read(cont + "/log.csv");
        ASSERT_NE(lb.find("conserved_energy"), std::string::npos);
        EXPECT_NE(la.find(lb.substr(lb.find('\n') + 1)), std::string::npos) << thermostat << "\n"
                                                                            << la << "\n"
                                                                            << lb;
    }
}

} // namespace
} // namespace pedesis::test
