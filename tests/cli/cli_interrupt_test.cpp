// SIGINT and SIGTERM stop a run of every engine within a second, and leave the run
// directory complete under final names (no .part file): the log, the last frame, the
// checkpoint and summary.json. The process then ends by SIGINT, as the shell expects, or
// after SIGTERM with exit code 75 (checkpointed), and the checkpoint restarts. A run that would
// never end (a stop 1e9 away) is started, signalled once its output exists, and timed from the
// signal to its end.
#include "cli/cli_support.hpp"

#include <nlohmann/json.hpp>

#include <chrono>
#include <csignal>
#include <thread>
#include <unistd.h>

namespace pedesis::test {
namespace {

namespace fs = std::filesystem;

class Interrupt : public ScratchDir {
  protected:
    struct Ended {
        int signal = 0;      // the signal that ended it, 0 if it exited
        int exit_code = -1;  // when it exited
        double seconds = -1; // from the signal to the end
        std::string output;
    };

    // Starts `pedesis run ARGS...` in dir, waits until `out` holds a file, sends `sig`
    // and waits for the end. Any wait longer than 60 s kills it and fails.
    Ended run_and_signal(const std::vector<std::string>& args, const std::string& out, int sig,
                         const std::string& command = "run") {
        const fs::path console = dir / ("console_" + std::to_string(++runs_) + ".txt");
        std::vector<std::string> argv{command};
        argv.insert(argv.end(), args.begin(), args.end());
        const pid_t pid = start_pedesis(dir, console, argv);
        Ended e;
        const auto give_up = std::chrono::steady_clock::now() + std::chrono::seconds(60);
        auto has_output = [&] {
            std::error_code ec;
            return fs::is_directory(dir / out, ec) && !fs::is_empty(dir / out, ec);
        };
        while (!has_output() && std::chrono::steady_clock::now() < give_up)
            std::this_thread::sleep_for(std::chrono::milliseconds(20));
        // well into the loop, past the frame and row of step 0
        std::this_thread::sleep_for(std::chrono::milliseconds(300));
        const auto sent = std::chrono::steady_clock::now();
        kill(pid, sig);
        int status = 0;
        while (waitpid(pid, &status, WNOHANG) == 0) {
            if (std::chrono::steady_clock::now() > give_up + std::chrono::seconds(60)) {
                kill(pid, SIGKILL);
                waitpid(pid, &status, 0);
                ADD_FAILURE() << "the run did not end after the signal";
                break;
            }
            std::this_thread::sleep_for(std::chrono::milliseconds(2));
        }
        e.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - sent).count();
        if (WIFSIGNALED(status)) e.signal = WTERMSIG(status);
        if (WIFEXITED(status)) e.exit_code = WEXITSTATUS(status);
        std::ifstream in(console);
        e.output.assign(std::istreambuf_iterator<char>(in), {});
        return e;
    }

    // The interrupted run ended by `sig` within a second, with everything in place.
    // SIGTERM (a scheduler's) ends it with exit code 75, "checkpointed, resume me"; SIGINT
    // (Ctrl-C) by the signal, as a shell expects.
    void expect_clean_stop(const Ended& e, const std::string& out, int sig) {
        if (sig == SIGTERM)
            EXPECT_EQ(e.exit_code, 75) << "signal " << e.signal << ": " << e.output;
        else
            EXPECT_EQ(e.signal, sig) << "exit code " << e.exit_code << ": " << e.output;
        EXPECT_LT(e.seconds, 1.0) << e.output;
        EXPECT_NE(e.output.find("interrupted by signal " + std::to_string(sig)), std::string::npos)
            << e.output;
        EXPECT_NE(e.output.find("--restart " + out + "/checkpoint.bin"), std::string::npos)
            << e.output;
        for (const auto& f : fs::directory_iterator(dir / out))
            EXPECT_EQ(f.path().string().find(".part"), std::string::npos) << f.path();
        for (const char* name : {"log.csv", "trajectory.gsd", "checkpoint.bin", "summary.json"})
            EXPECT_TRUE(fs::exists(dir / out / name)) << name << " missing: " << e.output;
    }

    // A run signalled, then its checkpoint restarted and signalled again: the restart
    // must load it (a refused checkpoint exits 2 at once) and go on from where it was.
    void check_engine(const std::string& config, const std::string& clock) {
        write("forever.toml", config);
        const Ended first = run_and_signal({"forever.toml", "--out", "first"}, "first", SIGTERM);
        expect_clean_stop(first, "first", SIGTERM);
        const auto s1 = nlohmann::json::parse(read("first/summary.json"));
        const Ended second =
            run_and_signal({"forever.toml", "--restart", "first/checkpoint.bin", "--out", "second"},
                           "second", SIGINT);
        expect_clean_stop(second, "second", SIGINT);
        const auto s2 = nlohmann::json::parse(read("second/summary.json"));
        EXPECT_GT(s2[clock].get<double>(), s1[clock].get<double>());
    }

    int runs_ = 0;
};

const std::string gsd_frames = "formats = [\"gsd\"]\n";

TEST_F(Interrupt, EventRunStopsCleanlyAndRestarts) {
    check_engine(small_config("", "length = 20.0", "time = 1e9") + gsd_frames, "time");
}

TEST_F(Interrupt, SteppedRunStopsCleanlyAndRestarts) {
    check_engine("dimension = 2\ndynamics = \"stepped\"\nseed = 2\n[box]\nlength = 20.0\n"
                 "[[species]]\nname = \"A\"\ncount = 40\nradius = 0.5\n[stepped]\ndt = 0.001\n"
                 "[run]\ntime = 1e9\n[output]\nlog_interval = 0.5\nprogress = false\n" +
                     gsd_frames,
                 "time");
}

TEST_F(Interrupt, SoftRunStopsCleanlyAndRestarts) {
    check_engine("dimension = 2\ndynamics = \"brownian\"\nseed = 1\n[box]\nlength = 20.0\n"
                 "[[species]]\nname = \"A\"\ncount = 40\nradius = 1.0\n[initial]\n"
                 "positions = \"random\"\n[[force]]\nname = \"harmonic\"\nk = 10.0\n"
                 "[[integrator]]\nname = \"brownian\"\nT = 0.1\ngamma = 1.0\n"
                 "[run]\nsteps = 1000000000\ndt = 0.001\n[output]\nprogress = false\n"
                 "log_every = 1000\nsnapshot_every = 100000\n" +
                     gsd_frames,
                 "steps");
}

// pedesis analyze runs a Python script: a signal reaches it too, and pedesis ends by
// that signal only once the script has ended (no orphan plotting on), leaving no figure.
TEST_F(Interrupt, AnalyzePassesTheSignalToItsScript) {
    write("gas.toml", small_config() + gsd_frames);
    ASSERT_EQ(run_pedesis("run gas.toml --out gas", dir, 60).exit_code, 0);
    // "gas" exists and is not empty from the start: the signal comes 0.3 s after launch,
    // while the script imports numpy and matplotlib
    const Ended e = run_and_signal({"speed", "gas"}, "gas", SIGTERM, "analyze");
    EXPECT_EQ(e.signal, SIGTERM) << "exit code " << e.exit_code << ": " << e.output;
    EXPECT_LT(e.seconds, 1.0) << e.output;
    // (the brackets keep pgrep from finding the shell that runs it)
    const std::string orphans = "pgrep -f 'speed[.]py " + (dir / "gas").string() + "' > /dev/null";
    EXPECT_NE(std::system(orphans.c_str()), 0) << "the script still runs";
    EXPECT_FALSE(fs::exists(dir / "gas" / "speed_distribution.png"));
}

} // namespace
} // namespace pedesis::test
