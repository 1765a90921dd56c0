// Issue 26: SIGINT, SIGTERM and SIGHUP end every command within a second wherever it is.
// Each command runs with PEDESIS_TRACE_STAGES=1, which names each stage on standard
// error as it begins; the test sends the signal as soon as the chosen stage is named,
// with that stage made long enough (a large lattice, file or config) that the signal
// lands inside it. During set-up the process must end by the signal itself, leaving no
// file that looks complete; inside the run loop the clean stop applies (every file
// complete under its final name, then the same signal, or exit code 75 after SIGTERM).
#include "cli/cli_support.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <csignal>
#include <fstream>
#include <thread>
#include <unistd.h>

namespace pedesis::test {
namespace {

namespace fs = std::filesystem;
using Clock = std::chrono::steady_clock;

struct Ended {
    int signal = 0;      // the signal that ended it, 0 if it exited
    int exit_code = -1;  // when it exited
    double seconds = -1; // from the signal to the end
    std::string output;
    std::vector<std::string> stages; // in the order named
};

std::vector<std::string> stages_named(const std::string& output) {
    const std::string tag = "pedesis: stage: ";
    std::vector<std::string> stages;
    std::istringstream in(output);
    for (std::string line; std::getline(in, line);)
        if (line.rfind(tag, 0) == 0) stages.push_back(line.substr(tag.size()));
    return stages;
}

class InterruptStages : public ScratchDir {
  protected:
    // Starts `pedesis ARGS...` in dir, waits until its output names `stage` for the
    // `occurrence`-th time (or, for an empty stage, holds `line`), sends `sig` and waits
    // for the end. A wait past 120 s kills it and fails.
    Ended signal_in(const std::vector<std::string>& args, const std::string& stage, int sig,
                    int occurrence = 1, const std::string& line = "") {
        const fs::path console = dir / ("console_" + std::to_string(++runs_) + ".txt");
        const pid_t pid = start_pedesis(dir, console, args, {"PEDESIS_TRACE_STAGES=1"});
        const auto give_up = Clock::now() + std::chrono::seconds(120);
        const auto reached = [&] {
            std::ifstream in(console);
            const std::string out(std::istreambuf_iterator<char>(in), {});
            if (!line.empty()) return out.find(line) != std::string::npos;
            const auto named = stages_named(out);
            return std::count(named.begin(), named.end(), stage) >= occurrence;
        };
        int status = 0;
        bool ended_early = false;
        while (!reached() && Clock::now() < give_up) {
            if (waitpid(pid, &status, WNOHANG) == pid) {
                ended_early = true;
                break;
            }
            std::this_thread::sleep_for(std::chrono::milliseconds(1));
        }
        Ended e;
        if (ended_early) {
            ADD_FAILURE() << "it ended before the stage '" << stage << "' was named";
        } else {
            const auto sent = Clock::now();
            kill(pid, sig);
            while (waitpid(pid, &status, WNOHANG) == 0) {
                if (Clock::now() > give_up) {
                    kill(pid, SIGKILL);
                    waitpid(pid, &status, 0);
                    ADD_FAILURE() << "it did not end after the signal";
                    break;
                }
                std::this_thread::sleep_for(std::chrono::milliseconds(2));
            }
            e.seconds = std::chrono::duration<double>(Clock::now() - sent).count();
        }
        if (WIFSIGNALED(status)) e.signal = WTERMSIG(status);
        if (WIFEXITED(status)) e.exit_code = WEXITSTATUS(status);
        std::ifstream in(console);
        e.output.assign(std::istreambuf_iterator<char>(in), {});
        e.stages = stages_named(e.output);
        return e;
    }

    // Ended by `sig` within a second while still in `stage`, leaving in `out` no file
    // that passes for complete (a .part file may stay; it never passes for one).
    void expect_ended_in_set_up(const Ended& e, const std::string& stage, int sig,
                                const std::string& out) {
        EXPECT_EQ(e.signal, sig) << "exit code " << e.exit_code << ": " << e.output;
        EXPECT_LT(e.seconds, 1.0) << e.output;
        ASSERT_FALSE(e.stages.empty()) << e.output;
        EXPECT_EQ(e.stages.back(), stage) << "the signal came after the stage: " << e.output;
        std::error_code ec;
        if (!fs::is_directory(dir / out, ec)) return;
        for (const auto& f : fs::recursive_directory_iterator(dir / out)) {
            const std::string name = f.path().filename().string();
            for (const char* complete :
                 {"log.csv", "trajectory.gsd", "trajectory.xyz", "checkpoint.bin", "summary.json"})
                EXPECT_NE(name, complete) << f.path() << " looks complete: " << e.output;
        }
    }

    // Ended within a second through the clean stop, the run directory complete: by
    // exit code 75 ("checkpointed, resume me") after SIGTERM or SIGUSR1, by the signal
    // itself after SIGINT or SIGHUP.
    void expect_clean_stop(const Ended& e, int sig, const std::string& out) {
        if (sig == SIGTERM || sig == SIGUSR1)
            EXPECT_EQ(e.exit_code, 75) << "signal " << e.signal << ": " << e.output;
        else
            EXPECT_EQ(e.signal, sig) << "exit code " << e.exit_code << ": " << e.output;
        EXPECT_LT(e.seconds, 1.0) << e.output;
        EXPECT_NE(e.output.find("interrupted by signal " + std::to_string(sig)), std::string::npos)
            << e.output;
        for (const auto& f : fs::directory_iterator(dir / out))
            EXPECT_EQ(f.path().string().find(".part"), std::string::npos) << f.path();
        for (const char* name : {"log.csv", "trajectory.gsd", "checkpoint.bin", "summary.json"})
            EXPECT_TRUE(fs::exists(dir / out / name)) << name << " missing: " << e.output;
    }

    int runs_ = 0;
};

// A Brownian run of harmonic disks or spheres of radius 0.5, started as `start` says.
std::string soft_config(int dimension, const std::string& start, std::uint64_t steps,
                        const std::string& extra = "") {
    return "dimension = " + std::to_string(dimension) + "\ndynamics = \"brownian\"\nseed = 5\n" +
           start +
           "[[force]]\nname = \"harmonic\"\nk = 10.0\n"
           "[[integrator]]\nname = \"brownian\"\nT = 0.1\ngamma = 1.0\n"
           "[run]\nsteps = " +
           std::to_string(steps) + "\ndt = 0.0001\n" + extra;
}

// `count` spheres on an fcc lattice at the density of in.lj.
std::string fcc_config(std::size_t count, const std::string& extra = "",
                       std::uint64_t steps = 1000000000) {
    const double length = std::cbrt(static_cast<double>(count) / 0.8442);
    return soft_config(3,
                       "[box]\nlength = " + std::to_string(length) +
                           "\n[[species]]\nname = \"A\"\ncount = " + std::to_string(count) +
                           "\nradius = 0.5\n[initial]\npositions = \"fcc\"\n",
                       steps, extra);
}

const std::string quiet_output = "[output]\nprogress = false\nformats = [\"gsd\"]\n";

TEST_F(InterruptStages, ParsingTheConfig) {
    // a million numbers in a key of its own: seconds of parsing before any check
    std::string padding = "padding = [";
    for (int k = 0; k < 1000000; ++k) padding += "1.25,";
    padding += "1.0]\n";
    write("big.toml", padding + fcc_config(4000) + quiet_output);
    const Ended e = signal_in({"run", "big.toml", "--out", "out"}, "reading the config", SIGTERM);
    expect_ended_in_set_up(e, "reading the config", SIGTERM, "out");
}

TEST_F(InterruptStages, ReadingALargeInitialFile) {
    {
        std::ofstream f(dir / "start.json");
        const int side = 70; // 343,000 particles, 30 MB of JSON
        f << "{\"system\":{\"box\":{\"Lx\":" << side << ",\"Ly\":" << side << ",\"Lz\":" << side
          << "},\"particles\":[";
        for (int k = 0; k < side * side * side; ++k) {
            const int x = k % side, y = (k / side) % side, z = k / (side * side);
            f << (k ? "," : "") << "{\"id\":" << k << ",\"r\":[" << x - side / 2 + 0.25 << ","
              << y - side / 2 + 0.25 << "," << z - side / 2 + 0.25 << "]}";
        }
        f << "]}}\n";
    }
    write("file.toml", soft_config(3,
                                   "[initial]\nfile = \"start.json\"\n[[species]]\nname = "
                                   "\"A\"\nradius = 0.5\n",
                                   10) +
                           quiet_output);
    const Ended e =
        signal_in({"run", "file.toml", "--out", "out"}, "reading a particle file", SIGINT);
    expect_ended_in_set_up(e, "reading a particle file", SIGINT, "out");
}

TEST_F(InterruptStages, PlacingParticlesAtRandom) {
    write("random.toml", soft_config(2,
                                     "[box]\nlength = 2000.0\n[[species]]\nname = \"A\"\n"
                                     "count = 1000000\nradius = 0.5\n[initial]\n"
                                     "positions = \"random\"\n",
                                     10) +
                             quiet_output);
    const Ended e =
        signal_in({"run", "random.toml", "--out", "out"}, "placing particles at random", SIGHUP);
    expect_ended_in_set_up(e, "placing particles at random", SIGHUP, "out");
}

TEST_F(InterruptStages, PlacingALattice) {
    write("lattice.toml", fcc_config(4 * 70 * 70 * 70) + quiet_output);
    const Ended e = signal_in({"run", "lattice.toml", "--out", "out", "--threads", "1"},
                              "placing particles on a lattice", SIGTERM);
    expect_ended_in_set_up(e, "placing particles on a lattice", SIGTERM, "out");
}

TEST_F(InterruptStages, TheFirstListBuild) {
    write("list.toml", fcc_config(4 * 50 * 50 * 50) + quiet_output);
    const Ended e = signal_in({"run", "list.toml", "--out", "out", "--threads", "1"},
                              "building the neighbour list", SIGINT);
    expect_ended_in_set_up(e, "building the neighbour list", SIGINT, "out");
}

// Inside the loop: a list rebuild and a frame of 32,000 particles (every 20 steps, with
// a skin so small that the list is rebuilt every few steps) end in the clean stop. The
// set-up builds three lists (the input checked, then two for the sort before the first
// step): the fourth build is the run's.
TEST_F(InterruptStages, AListRebuildInTheRun) {
    write("rebuild.toml", fcc_config(4 * 20 * 20 * 20, "[neighbor_list]\nskin = 0.05\n") +
                              quiet_output + "snapshot_every = 20\nlog_every = 20\n");
    const Ended e = signal_in({"run", "rebuild.toml", "--out", "out", "--threads", "1"},
                              "building the neighbour list", SIGTERM, 4);
    expect_clean_stop(e, SIGTERM, "out");
}

TEST_F(InterruptStages, WritingAFrameInTheRun) {
    write("frames.toml",
          fcc_config(4 * 20 * 20 * 20) + quiet_output + "snapshot_every = 20\nlog_every = 20\n");
    const Ended e = signal_in({"run", "frames.toml", "--out", "out", "--threads", "1"},
                              "writing a frame", SIGINT, 3);
    expect_clean_stop(e, SIGINT, "out");
}

// pedesis sweep: a point's set-up ends the sweep at once; its table is that of the last
// clean state (none yet: no point was done).
TEST_F(InterruptStages, SweepInAPointsSetUp) {
    write("base.toml", fcc_config(4 * 50 * 50 * 50) + quiet_output);
    write("sweep.toml", "base = \"base.toml\"\nout = \"sw\"\n[vary]\nseed = [1, 2]\n");
    const Ended e = signal_in({"sweep", "sweep.toml", "--threads", "1"},
                              "building the neighbour list", SIGTERM);
    expect_ended_in_set_up(e, "building the neighbour list", SIGTERM, "sw");
}

// pedesis render: reading its source, and drawing (where it stops between frames and
// removes what it made).
TEST_F(InterruptStages, RenderReadingAndDrawing) {
    write("frames.toml", fcc_config(4 * 20 * 20 * 20, "", 40) +
                             "[output]\nprogress = false\nformats = [\"gsd\"]\n"
                             "snapshot_every = 1\n");
    ASSERT_EQ(run_pedesis("run frames.toml --out traj", dir, 120).exit_code, 0);
    for (const char* stage : {"reading the frames", "drawing the frames"}) {
        const Ended e = signal_in({"render", "traj", "--out", "movie.gif"}, stage, SIGTERM);
        EXPECT_EQ(e.signal, SIGTERM) << "exit code " << e.exit_code << ": " << e.output;
        EXPECT_LT(e.seconds, 1.0) << e.output;
        EXPECT_FALSE(fs::exists(dir / "movie.gif")) << stage;
    }
}

// pedesis view serves until a signal, which ends it at once whatever the server does.
TEST_F(InterruptStages, ViewServing) {
    write("small.toml", fcc_config(500, "", 10) + quiet_output);
    ASSERT_EQ(run_pedesis("run small.toml --out small", dir, 120).exit_code, 0);
    const Ended e = signal_in({"view", "small", "--port", "0"}, "", SIGINT, 1, "Ctrl-C to stop");
    EXPECT_EQ(e.signal, SIGINT) << "exit code " << e.exit_code << ": " << e.output;
    EXPECT_LT(e.seconds, 1.0) << e.output;
}

} // namespace
} // namespace pedesis::test
