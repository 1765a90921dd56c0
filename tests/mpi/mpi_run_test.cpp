// `pedesis run` of the soft engine divided among 2 and 3 MPI processes (domain
// decomposition, soft/domain_decomposition.hpp) against the same run on one process.
//
// The bound for positions: each process sums the forces on its particles over its own
// half list, in another order than one process does, so a force differs by a few units
// in the last place (~1e-16 relative) at each step. The noise is keyed by tag and step,
// so it is the same on every process. Over the few hundred steps below, measured
// differences are 1e-14 to 1e-12 sigma (overdamped ABP, which damps them); 1e-9 sigma
// leaves three orders of magnitude for other machines and compilers, and is still ten
// million times smaller than one step's displacement (~1e-2 sigma), so a particle that
// was lost, duplicated, given another's noise or a missing neighbour's force fails it.
#include "mpi/mpi_support.hpp"

#include "pedesis/io/xyz_reader.hpp"

#include <fmt/format.h>

#include <cmath>
#include <numeric>

namespace pedesis::test {
namespace {

constexpr double position_bound = 1e-9;

// The tutorial's ABP system (harmonic repulsion, self-propulsion, polar alignment,
// translational and rotational noise), small and at a density where every particle has
// neighbours.
std::string abp_config(int dimension, int steps, double alpha = 1.0, int count = 400) {
    const double length = dimension == 2 ? 24.0 : 9.0;
    return fmt::format("dimension = {}\ndynamics = \"brownian\"\nseed = 7\n[box]\nlength = {}\n"
                       "[[species]]\nname = \"A\"\ncount = {}\nradius = 0.5\n"
                       "[initial]\npositions = \"random\"\nmin_distance = 0.8\n"
                       "[[force]]\nname = \"harmonic\"\nk = 50.0\n"
                       "[[force]]\nname = \"self_propulsion\"\nalpha = {}\n"
                       "[[torque]]\nname = \"polar_align\"\nJ = 0.5\na = 1.5\n"
                       "[[integrator]]\nname = \"brownian\"\nT = 0.05\ngamma = 1.0\n"
                       "[[integrator]]\nname = \"brownian_rotation\"\nT = 0.1\ngamma = 1.0\n"
                       "[neighbor_list]\nskin = 0.4\n"
                       "[run]\ndt = 0.002\nsteps = {}\n"
                       "[output]\nlog_every = 50\nsnapshot_every = 100\ncheckpoint_every = 100\n"
                       "formats = [\"xyz\"]\nprogress = false\n",
                       dimension, length, count, alpha, steps);
}

std::size_t occurrences(const std::string& text, const std::string& what) {
    std::size_t n = 0;
    for (auto at = text.find(what); at != std::string::npos; at = text.find(what, at + 1)) ++n;
    return n;
}

class MpiRun : public ScratchDir {
  protected:
    // `extra`: more tables for the config (one-body forces)
    void expect_processes_follow_serial(int dimension, const std::string& extra = "");
};

void MpiRun::expect_processes_follow_serial(int dimension, const std::string& extra) {
    MpiRun& t = *this;
    t.write("abp.toml", abp_config(dimension, 400) + extra);
    const CliResult serial = run_pedesis("run abp.toml --out serial", t.dir, 120);
    ASSERT_EQ(serial.exit_code, 0) << serial.output;
    for (int p : {2, 3}) {
        const std::string out = "np" + std::to_string(p);
        const CliResult r = run_mpi(p, "run abp.toml --out " + out, t.dir);
        ASSERT_EQ(r.exit_code, 0) << r.output;
        EXPECT_NE(r.output.find(std::to_string(p) + " MPI processes, domains"), std::string::npos)
            << r.output;
        // one process talks
        EXPECT_EQ(occurrences(r.output, "pedesis: done"), 1u) << r.output;
        const double d =
            largest_difference(t.dir / "serial/trajectory.xyz", t.dir / (out + "/trajectory.xyz"));
        EXPECT_LT(d, position_bound) << p << " processes, " << dimension << "D";
        // the log has the serial rows and columns; its values agree to far better than
        // its 10 digits would show a lost particle. The processes rebuild their lists
        // together when a particle has moved skin/2, one process only when a pair could
        // be missing (NeighborList::needs_rebuild): no more often.
        const CsvColumns s = csv_columns(t.read("serial/log.csv"));
        const CsvColumns m = csv_columns(t.read(out + "/log.csv"));
        ASSERT_EQ(s.names, m.names);
        for (const std::string& name : s.names) {
            ASSERT_EQ(s.cells.at(name).size(), m.cells.at(name).size());
            for (std::size_t k = 0; k < s.cells.at(name).size(); ++k) {
                const double a = std::stod(s.cells.at(name)[k]), b = std::stod(m.cells.at(name)[k]);
                if (name == "list_rebuilds")
                    EXPECT_LE(a, b) << "row " << k;
                else
                    EXPECT_NEAR(a, b, 1e-8 * std::max(1.0, std::abs(a))) << name << " row " << k;
            }
        }
    }
}

TEST_F(MpiRun, TwoAndThreeProcessesFollowTheSerialTrajectoryIn2D) {
    expect_processes_follow_serial(2);
}

TEST_F(MpiRun, TwoAndThreeProcessesFollowTheSerialTrajectoryIn3D) {
    expect_processes_follow_serial(3);
}

// One-body forces (a container that starts with particles in its harmonic wall, gravity,
// a trap) and their log columns (wall_pressure_sphere, gravity_energy, trap_energy:
// sums over every process's particles) as on one process.
TEST_F(MpiRun, ContainerGravityAndTrapFollowTheSerialRun) {
    expect_processes_follow_serial(
        2, "[[force]]\nname = \"wall\"\nshape = \"sphere\"\npotential = \"harmonic\"\n"
           "k = 5.0\nradius = 12.5\n[[force]]\nname = \"gravity\"\nforce = 0.2\n"
           "[[force]]\nname = \"harmonic_trap\"\nk = 0.05\ncentre = [1.0, -2.0]\n");
}

// Threads and processes combine: 2 processes of 2 OpenMP threads each give the
// trajectory of 2 processes of one thread bit for bit (each process's force sums are in
// an order that does not depend on its threads). Passive waiting keeps the 4 threads on
// 2 cores from spinning against each other.
TEST_F(MpiRun, ThreadsInsideProcessesChangeNoBit) {
    write("abp.toml", abp_config(2, 300));
    const CliResult one = run_mpi(2, "run abp.toml --out one_thread --threads 1", dir);
    ASSERT_EQ(one.exit_code, 0) << one.output;
    const CliResult two =
        shell("OMP_WAIT_POLICY=passive timeout -s KILL 300 '" + std::string(PEDESIS_MPIEXEC) +
                  "' --allow-run-as-root --oversubscribe -np 2 '" + PEDESIS_BINARY +
                  "' run abp.toml --out two_threads --threads 2",
              dir);
    ASSERT_EQ(two.exit_code, 0) << two.output;
    EXPECT_EQ(read("two_threads/trajectory.xyz"), read("one_thread/trajectory.xyz"));
    EXPECT_EQ(read("two_threads/log.csv"), read("one_thread/log.csv"));
}

// Inertial dynamics: the Kob-Andersen Lennard-Jones mixture (3D, two species, pair
// parameters per species pair) under Langevin and NVE velocity Verlet, whose forces of
// the step before travel with a migrating particle. A dense LJ liquid amplifies round-off
// faster than overdamped ABP (measured: 1e-5 sigma after 400 NVE steps), so the runs are
// 60 steps long, where the measured difference is below 1e-12 sigma.
TEST_F(MpiRun, LangevinAndNveFollowTheSerialTrajectory) {
    for (const std::string dynamics : {"langevin", "nve"}) {
        const std::string integrator = "name = \"" + dynamics + "\"\n" +
                                       (dynamics == "langevin" ? "T = 1.0\ngamma = 1.0\n" : "");
        write(
            "ka.toml",
            "dimension = 3\ndynamics = \"" + dynamics +
                "\"\nseed = 5\n[box]\nlength = 9.41\n"
                "[[species]]\nname = \"A\"\ncount = 800\nradius = 0.5\n"
                "[[species]]\nname = \"B\"\ncount = 200\nradius = 0.44\n"
                "[initial]\npositions = \"random\"\nmin_distance = 0.8\n"
                "velocities = \"maxwell_boltzmann\"\ntemperature = 1.0\n"
                "[[force]]\nname = \"lj\"\nepsilon = 1.0\nsigma = 1.0\ncutoff = 2.5\nshift = true\n"
                "[[force.pairs]]\nspecies = [\"A\", \"B\"]\nepsilon = 1.5\nsigma = 0.8\n"
                "[[force.pairs]]\nspecies = [\"B\", \"B\"]\nepsilon = 0.5\nsigma = 0.88\n"
                "[[integrator]]\n" +
                integrator +
                "[neighbor_list]\nskin = 0.3\n[run]\nsteps = 60\ndt = 0.002\n"
                "[output]\nlog_every = 20\nsnapshot_every = 30\nformats = [\"xyz\"]\n"
                "progress = false\n");
        const std::string& tag = dynamics;
        const CliResult serial = run_pedesis("run ka.toml --out serial_" + tag, dir, 120);
        ASSERT_EQ(serial.exit_code, 0) << serial.output;
        const CliResult r = run_mpi(3, "run ka.toml --out np3_" + tag, dir);
        ASSERT_EQ(r.exit_code, 0) << r.output;
        EXPECT_LT(largest_difference(dir / ("serial_" + tag + "/trajectory.xyz"),
                                     dir / ("np3_" + tag + "/trajectory.xyz")),
                  position_bound)
            << dynamics;
    }
}

// Long-run statistics: 20,000 steps of the 2D ABP system on one and on two processes.
// The time averages of the pressure and the polar order agree within three standard
// errors (from 10 block means of the one-process log after its first tenth), and the
// final MSD within three times its statistical error, which for the mean of N squared
// 2D displacements is about MSD / sqrt(N) (the variance of a 2D Gaussian r^2 is
// <r^2>^2).
TEST_F(MpiRun, LongRunAveragesAgreeWithinTheirErrors) {
    std::string config = abp_config(2, 20000);
    config.replace(config.find("snapshot_every = 100"), 20, "snapshot_every = 0");
    config.replace(config.find("checkpoint_every = 100"), 22, "checkpoint_every = 0");
    write("long.toml", config);
    const CliResult serial = run_pedesis("run long.toml --out serial", dir, 300);
    ASSERT_EQ(serial.exit_code, 0) << serial.output;
    const CliResult r = run_mpi(2, "run long.toml --out np2", dir);
    ASSERT_EQ(r.exit_code, 0) << r.output;
    const CsvColumns one = csv_columns(read("serial/log.csv"));
    const CsvColumns two = csv_columns(read("np2/log.csv"));
    auto values = [](const CsvColumns& c, const std::string& name) {
        std::vector<double> v;
        for (const std::string& cell : c.cells.at(name)) v.push_back(std::stod(cell));
        return v;
    };
    for (const std::string name : {"pressure", "polar_order"}) {
        const std::vector<double> a = values(one, name), b = values(two, name);
        ASSERT_EQ(a.size(), 401u);
        ASSERT_EQ(b.size(), a.size());
        const std::size_t first = a.size() / 10, blocks = 10;
        const std::size_t per = (a.size() - first) / blocks;
        std::vector<double> means;
        double mean_a = 0.0, mean_b = 0.0;
        for (std::size_t k = 0; k < blocks; ++k) {
            double m = 0.0;
            for (std::size_t i = first + k * per; i < first + (k + 1) * per; ++i) {
                m += a[i] / per;
                mean_a += a[i] / (per * blocks);
                mean_b += b[i] / (per * blocks);
            }
            means.push_back(m);
        }
        double var = 0.0;
        for (double m : means) var += (m - mean_a) * (m - mean_a) / (blocks - 1);
        const double standard_error = std::sqrt(var / blocks);
        EXPECT_GT(standard_error, 0.0) << name;
        EXPECT_NEAR(mean_b, mean_a, 3.0 * standard_error) << name;
    }
    const double msd_a = values(one, "msd").back(), msd_b = values(two, "msd").back();
    EXPECT_NEAR(msd_b, msd_a, 3.0 * msd_a / std::sqrt(400.0));
}

// Fast swimmers (v0 = 20: 0.04 sigma per step, a domain of 8 sigma in 200 steps) cross
// the boundaries between three domains again and again; none is lost or doubled. Hard,
// fast collisions amplify the rounding differences more than the slow system does
// (measured 6e-9 sigma after 600 steps, 8e-8 after 1200): the bound is 1e-6 sigma, still
// 40,000 times smaller than one step's move.
TEST_F(MpiRun, SwimmersThatCrossDomainsAgainAndAgainStayOnTheSerialTrajectory) {
    write("fast.toml", abp_config(2, 600, 20.0, 150));
    const CliResult serial = run_pedesis("run fast.toml --out serial", dir, 120);
    ASSERT_EQ(serial.exit_code, 0) << serial.output;
    const CliResult r = run_mpi(3, "run fast.toml --out np3", dir);
    ASSERT_EQ(r.exit_code, 0) << r.output;
    EXPECT_LT(largest_difference(dir / "serial/trajectory.xyz", dir / "np3/trajectory.xyz"), 1e-6);
    // the particles did cross: a mean squared displacement of many domain widths
    const CsvColumns log = csv_columns(read("np3/log.csv"));
    EXPECT_GT(std::stod(log.cells.at("msd").back()), 8.0 * 8.0);
}

// A checkpoint written by 2 processes continues on 1 and on 3, and both continuations
// follow the uninterrupted serial run (to the bound: the restart rebuilds its lists).
TEST_F(MpiRun, ACheckpointOfTwoProcessesRestartsOnOneAndOnThree) {
    write("first.toml", abp_config(2, 200));
    write("whole.toml", abp_config(2, 400));
    const CliResult whole = run_pedesis("run whole.toml --out whole", dir, 120);
    ASSERT_EQ(whole.exit_code, 0) << whole.output;
    const CliResult first = run_mpi(2, "run first.toml --out first", dir);
    ASSERT_EQ(first.exit_code, 0) << first.output;
    const CliResult one =
        run_pedesis("run whole.toml --out one --restart first/checkpoint.bin", dir, 120);
    ASSERT_EQ(one.exit_code, 0) << one.output;
    const CliResult three =
        run_mpi(3, "run whole.toml --out three --restart first/checkpoint.bin", dir);
    ASSERT_EQ(three.exit_code, 0) << three.output;
    // the continuations hold frames 3 and 4 (steps 300 and 400); the whole run 0..4
    const XyzReader w(dir / "whole/trajectory.xyz"), a(dir / "one/trajectory.xyz"),
        b(dir / "three/trajectory.xyz");
    ASSERT_EQ(a.frames(), 2u);
    ASSERT_EQ(b.frames(), 2u);
    const XyzFrame fw = w.frame(w.frames() - 1), fa = a.frame(1), fb = b.frame(1);
    ASSERT_EQ(fa.size(), fw.size());
    ASSERT_EQ(fb.size(), fw.size());
    for (std::size_t i = 0; i < fw.size(); ++i)
        for (int c = 0; c < 3; ++c) {
            EXPECT_NEAR(fa.position[i][c], fw.position[i][c], position_bound) << i;
            EXPECT_NEAR(fb.position[i][c], fw.position[i][c], position_bound) << i;
        }
    EXPECT_EQ(csv_columns(read("three/log.csv")).cells.at("step").back(), "400");
}

// Three domains of a box 4 sigma wide would be 1.33 sigma thin, less than the cutoff
// plus skin (1.4): refused before anything is written, once, exit 2 on every process.
TEST_F(MpiRun, ADomainThinnerThanTheInteractionRangeIsRefusedOnce) {
    std::string config = abp_config(2, 10, 1.0, 4);
    config.replace(config.find("length = 24"), 11, "length = 4");
    write("thin.toml", config);
    const CliResult r = run_mpi(3, "run thin.toml --out thin", dir);
    EXPECT_EQ(r.exit_code, 2) << r.output;
    EXPECT_EQ(occurrences(r.output, "pedesis: error:"), 1u) << r.output;
    EXPECT_NE(r.output.find("thinner than the interaction range"), std::string::npos) << r.output;
    EXPECT_FALSE(std::filesystem::exists(dir / "thin"));
}

// The error paths leave no process waiting for another (run_mpi's kill timer would
// turn a deadlock into exit 137): each ends every process with the serial exit code and
// one message.
// Walls on an axis cannot be cut into periodic domains: one message, exit 2, naming the
// way out.
TEST_F(MpiRun, AWalledBoxIsRefusedOnceWithTheWayOut) {
    std::string config =
        abp_config(2, 10) + "[[force]]\nname = \"wall\"\npotential = \"harmonic\"\nk = 10.0\n";
    config.replace(config.find("length = 24"), 11,
                   "length = 24\nboundary = [\"wall\", \"periodic\"]");
    write("walled.toml", config);
    const CliResult r = run_mpi(2, "run walled.toml --out walled", dir, 120);
    EXPECT_EQ(r.exit_code, 2) << r.output;
    EXPECT_EQ(occurrences(r.output, "pedesis: error:"), 1u) << r.output;
    EXPECT_NE(r.output.find("a walled box runs on one process; start it without mpirun"),
              std::string::npos)
        << r.output;
}

TEST_F(MpiRun, BadConfigGivesOneMessageAndExitTwo) {
    std::string config = abp_config(2, 10);
    config.replace(config.find("polar_align"), 11, "polar_aline");
    write("bad.toml", config);
    const CliResult r = run_mpi(3, "run bad.toml --out bad", dir, 120);
    EXPECT_EQ(r.exit_code, 2) << r.output;
    EXPECT_EQ(occurrences(r.output, "pedesis: error:"), 1u) << r.output;
    EXPECT_NE(r.output.find("polar_aline"), std::string::npos) << r.output;
}

// Only process 0 writes: when it cannot (the run directory is a file), the others must
// not go on to wait for it.
TEST_F(MpiRun, AnUnwritableRunDirectoryStopsEveryProcess) {
    write("abp.toml", abp_config(2, 100));
    write("taken", "a file where the run directory should be\n");
    const CliResult r = run_mpi(2, "run abp.toml --out taken", dir, 120);
    EXPECT_EQ(r.exit_code, 2) << r.output;
    EXPECT_EQ(occurrences(r.output, "pedesis: error:"), 1u) << r.output;
    EXPECT_EQ(read("taken"), "a file where the run directory should be\n");
}

// Two particles at the same place, in the domain of process 1 (x > 0 of a 2 x 1 grid)
// or across the face between the domains: bad input, refused at set-up as on one process
// (exit 2, one message naming both, nothing written), not a NaN at the first log row.
TEST_F(MpiRun, CoincidentParticlesAreRefusedOnceOnEveryProcess) {
    for (const std::string at : {"[6.0, 1.0]", "[0.0, 1.0]"}) {
        write("same.toml", "dimension = 2\ndynamics = \"brownian\"\nseed = 2\n[box]\n"
                           "length = 24.0\n[[species]]\nname = \"A\"\ncount = 40\n"
                           "radius = 0.5\n[[species]]\nname = \"B\"\nposition = " +
                               at + "\nradius = 0.5\n[[species]]\nname = \"C\"\nposition = " + at +
                               "\nradius = 0.5\n[initial]\npositions = \"random\"\n"
                               "min_distance = 1.2\n[[force]]\nname = \"harmonic\"\nk = 10.0\n"
                               "[[integrator]]\nname = \"brownian\"\nT = 0.1\ngamma = 1.0\n"
                               "[run]\ndt = 0.01\nsteps = 10\n[output]\nprogress = false\n");
        const CliResult r = run_mpi(2, "run same.toml --out same", dir, 120);
        EXPECT_EQ(r.exit_code, 2) << at << r.output;
        EXPECT_EQ(occurrences(r.output, "pedesis: error:"), 1u) << at << r.output;
        EXPECT_NE(r.output.find("particles 40 and 41 start at the same position"),
                  std::string::npos)
            << at << r.output;
        EXPECT_FALSE(std::filesystem::exists(dir / "same" / "log.csv")) << at;
    }
}

// The line of `output` that holds `what` ("" if none).
std::string line_with(const std::string& output, const std::string& what) {
    const auto at = output.find(what);
    if (at == std::string::npos) return "";
    const auto begin = output.rfind('\n', at);
    const auto start = begin == std::string::npos ? 0 : begin + 1;
    return output.substr(start, output.find('\n', at) - start);
}

// Two coincident pairs from an [initial] file: particles 0 and 1 in the domain of the
// last process (every coordinate L/4), 2 and 3 in that of process 0, one at x = -L/2 and
// one at x = +L/2 (the same place through the periodic boundary). Every process count
// must name the pair one process names, whichever process finds which pair.
TEST_F(MpiRun, CoincidentParticlesFromAFileGiveTheSerialMessage) {
    for (const int d : {2, 3}) {
        const double half = d == 2 ? 12.0 : 6.0;
        const std::string rest = d == 2 ? "" : fmt::format(", {}", -half / 2);
        const std::string a = fmt::format("[{}, {}{}]", half / 2, half / 2,
                                          d == 2 ? "" : fmt::format(", {}", half / 2));
        write("start.json",
              fmt::format("{{\"system\": {{\"particles\": [{{\"id\": 0, \"r\": {}}}, "
                          "{{\"id\": 1, \"r\": {}}}, {{\"id\": 2, \"r\": [{}, {}{}]}}, "
                          "{{\"id\": 3, \"r\": [{}, {}{}]}}]}}}}\n",
                          a, a, -half, -half / 2, rest, half, -half / 2, rest));
        write("same.toml", fmt::format("dimension = {}\ndynamics = \"langevin\"\nseed = 2\n"
                                       "[box]\nlength = {}\n[[species]]\nname = \"A\"\n"
                                       "radius = 0.5\n[initial]\nfile = \"start.json\"\n"
                                       "[[force]]\nname = \"harmonic\"\nk = 10.0\n"
                                       "[[integrator]]\nname = \"langevin\"\nT = 0.1\n"
                                       "gamma = 1.0\n[run]\ndt = 0.01\nsteps = 10\n"
                                       "[output]\nprogress = false\n",
                                       d, 2 * half));
        const CliResult serial = run_pedesis("run same.toml --out serial", dir, 120);
        ASSERT_EQ(serial.exit_code, 2) << serial.output;
        const std::string message = line_with(serial.output, "pedesis: error:");
        ASSERT_NE(message.find("particles 0 and 1 start at the same position"), std::string::npos)
            << serial.output;
        for (const int p : {2, 3}) {
            const CliResult r = run_mpi(p, "run same.toml --out np", dir, 120);
            EXPECT_EQ(r.exit_code, 2) << d << "D, " << p << " processes: " << r.output;
            EXPECT_EQ(occurrences(r.output, "pedesis: error:"), 1u) << r.output;
            EXPECT_EQ(line_with(r.output, "pedesis: error:"), message)
                << d << "D, " << p << " processes: " << r.output;
            EXPECT_FALSE(std::filesystem::exists(dir / "np" / "log.csv"));
        }
    }
}

// Two particles placed almost on top of each other in the domain of process 1 (x > 0 of
// a 2 x 1 grid) blow up at the first step there; every process stops with exit 3, the
// message of process 1 is printed once (by process 0), and the run directory keeps its
// last good frame.
TEST_F(MpiRun, ABlowUpOnOneProcessStopsAllWithItsMessage) {
    write("blow.toml", "dimension = 2\ndynamics = \"brownian\"\nseed = 2\n[box]\nlength = 24.0\n"
                       "[[species]]\nname = \"A\"\ncount = 40\nradius = 0.5\n"
                       "[[species]]\nname = \"B\"\nposition = [6.0, 1.0]\nradius = 0.5\n"
                       "[[species]]\nname = \"C\"\nposition = [6.05, 1.0]\nradius = 0.5\n"
                       "[initial]\npositions = \"random\"\nmin_distance = 1.2\n"
                       "[[force]]\nname = \"harmonic\"\nk = 2000.0\n"
                       "[[integrator]]\nname = \"brownian\"\nT = 0.0\ngamma = 1.0\n"
                       "[run]\ndt = 0.01\nsteps = 100\n"
                       "[output]\nlog_every = 10\nsnapshot_every = 10\nformats = [\"xyz\"]\n"
                       "progress = false\n");
    const CliResult r = run_mpi(2, "run blow.toml --out blow", dir, 120);
    EXPECT_EQ(r.exit_code, 3) << r.output;
    EXPECT_EQ(occurrences(r.output, "pedesis: run stopped:"), 1u) << r.output;
    EXPECT_NE(r.output.find("more than 0.5 (the neighbour-list skin)"), std::string::npos)
        << r.output;
    EXPECT_NE(r.output.find("the last good snapshot is frame 0"), std::string::npos) << r.output;
    const XyzReader frames(dir / "blow/trajectory.xyz");
    EXPECT_EQ(frames.frames(), 1u);
}

} // namespace
} // namespace pedesis::test
