// pedesis run --resume and what surrounds it (issue 52): a finished run has nothing to do,
// another config is refused naming the key, a later end continues a finished run, one
// writer per run directory (a dead writer's lock does not block), a full disk stops the
// run naming the file and the checkpoint survives it, checkpoints on the wall clock,
// signals that come twice, and records that are not what they claim.
#include "support/kill_and_resume.hpp"

#include <chrono>
#include <csignal>
#include <thread>

namespace pedesis::test {
namespace {

namespace fs = std::filesystem;

class Resume : public ScratchDir {
  protected:
    void SetUp() override {
        ScratchDir::SetUp();
        write("run.toml", resume_config("event"));
    }

    // Starts `pedesis ARGS` and waits until its run directory `out` has a log row past the
    // header (the run is in its loop), at most 60 s.
    pid_t start_until_running(const std::vector<std::string>& args, const std::string& out) {
        const pid_t pid =
            start_pedesis(dir, dir / ("console_" + std::to_string(++runs_) + ".txt"), args);
        wait_until([&] {
            const std::string log = file_text(dir / out / "log.csv.part");
            return std::count(log.begin(), log.end(), '\n') >= 2;
        });
        return pid;
    }

    // Starts a resume of `out` and waits until it has written a checkpoint of its own (it
    // is in its loop: the rows it found were the dead run's, and its set-up, however slow
    // under a sanitizer, is over), at most 60 s.
    pid_t start_resume_until_running(const std::vector<std::string>& args, const std::string& out) {
        const std::string found = file_text(dir / out / "checkpoint.bin");
        const pid_t pid =
            start_pedesis(dir, dir / ("console_" + std::to_string(++runs_) + ".txt"), args);
        wait_until([&] {
            const std::string now = file_text(dir / out / "checkpoint.bin");
            return !now.empty() && now != found;
        });
        return pid;
    }

    template <class Done> static void wait_until(Done done) {
        const auto give_up = std::chrono::steady_clock::now() + std::chrono::seconds(60);
        while (std::chrono::steady_clock::now() < give_up && !done())
            std::this_thread::sleep_for(std::chrono::milliseconds(5));
    }

    // The exit code, or 128 + the signal that ended it.
    static int wait_for(pid_t pid) {
        int status = 0;
        waitpid(pid, &status, 0);
        return WIFEXITED(status) ? WEXITSTATUS(status) : 128 + WTERMSIG(status);
    }

    // No .part file, and the files of a complete run directory.
    void expect_complete(const std::string& out, const std::string& why) {
        for (const auto& f : fs::recursive_directory_iterator(dir / out))
            EXPECT_EQ(f.path().string().find(".part"), std::string::npos) << f.path() << why;
        for (const char* name :
             {"log.csv", "trajectory.gsd", "trajectory.xyz", "checkpoint.bin", "summary.json"})
            EXPECT_TRUE(fs::exists(dir / out / name)) << name << " missing" << why;
    }

    int runs_ = 0;
};

TEST_F(Resume, AFinishedRunHasNothingToDoAndStaysAsItWas) {
    ASSERT_EQ(run_pedesis("run run.toml --out done", dir, 120).exit_code, 0);
    const std::string log = read("done/log.csv");
    const CliResult r = run_pedesis("run run.toml --out done --resume", dir, 120);
    EXPECT_EQ(r.exit_code, 0) << r.output;
    EXPECT_NE(r.output.find("holds a finished run of this config (stopped by time): nothing to do"),
              std::string::npos)
        << r.output;
    EXPECT_EQ(read("done/log.csv"), log);
    EXPECT_FALSE(fs::exists(dir / "done" / "pedesis.lock"));
    // how a run reports is not where it ends: still nothing to do (it went on before)
    const CliResult quiet =
        run_pedesis("run run.toml --out done --resume --set output.progress=true", dir, 120);
    EXPECT_EQ(quiet.exit_code, 0) << quiet.output;
    EXPECT_NE(quiet.output.find("nothing to do"), std::string::npos) << quiet.output;
    EXPECT_EQ(read("done/log.csv"), log);
}

TEST_F(Resume, AnEmptyOrAbsentDirectoryStartsTheRun) {
    fs::create_directories(dir / "empty");
    for (const char* out : {"empty", "absent"}) {
        const CliResult r =
            run_pedesis(std::string("run run.toml --out ") + out + " --resume", dir, 120);
        EXPECT_EQ(r.exit_code, 0) << r.output;
        EXPECT_NE(r.output.find("holds no run yet: starting it"), std::string::npos) << r.output;
    }
    ASSERT_EQ(run_pedesis("run run.toml --out ref", dir, 120).exit_code, 0);
    EXPECT_EQ(directory_differences(dir / "ref", dir / "empty"), "");
    EXPECT_EQ(directory_differences(dir / "ref", dir / "absent"), "");
}

TEST_F(Resume, AnotherConfigIsRefusedNamingTheKeyThatDiffers) {
    ASSERT_EQ(run_pedesis("run run.toml --out done", dir, 120).exit_code, 0);
    const CliResult box =
        run_pedesis("run run.toml --out done --resume --set box.length=60.0", dir, 120);
    EXPECT_EQ(box.exit_code, 2) << box.output;
    EXPECT_NE(box.output.find("holds a run of another config: box.length (was 50.0, now 60.0)"),
              std::string::npos)
        << box.output;
    const CliResult species =
        run_pedesis("run run.toml --out done --resume --set species.B.mass=4.0", dir, 120);
    EXPECT_EQ(species.exit_code, 2) << species.output;
    EXPECT_NE(species.output.find("species[1].mass (was 3.0, now 4.0)"), std::string::npos)
        << species.output;
    EXPECT_TRUE(fs::exists(dir / "done" / "summary.json"));
}

// The first half ends at t = 60, a point of every grid (rows, frames, checkpoints): its
// continuation to t = 120 is the run that went there at once, byte for byte.
TEST_F(Resume, ALaterEndContinuesAFinishedRun) {
    ASSERT_EQ(run_pedesis("run run.toml --out ref", dir, 120).exit_code, 0);
    ASSERT_EQ(run_pedesis("run run.toml --out half --set run.time=60.0", dir, 120).exit_code, 0);
    const CliResult r = run_pedesis("run run.toml --out half --resume", dir, 120);
    ASSERT_EQ(r.exit_code, 0) << r.output;
    EXPECT_NE(r.output.find("resuming half from half/checkpoint.bin"), std::string::npos)
        << r.output;
    EXPECT_EQ(directory_differences(dir / "ref", dir / "half"), "");
}

// A second run on a directory in use is refused at once, naming the first; the first
// goes on. Killed, the first leaves its lock file, which does not block the resume; and
// SIGTERM ends that resume with exit 75, every file complete.
TEST_F(Resume, OneWriterPerRunDirectoryAndADeadOneDoesNotBlock) {
    const pid_t first =
        start_until_running({"run", "run.toml", "--out", "busy", "--set", "run.time=1e9"}, "busy");
    const CliResult second = run_pedesis("run run.toml --out busy --set run.time=1e9", dir, 60);
    EXPECT_EQ(second.exit_code, 2) << second.output;
    EXPECT_NE(second.output.find("busy: in use by pedesis process " + std::to_string(first)),
              std::string::npos)
        << second.output;
    const CliResult resumer =
        run_pedesis("run run.toml --out busy --resume --set run.time=1e9", dir, 60);
    EXPECT_EQ(resumer.exit_code, 2) << resumer.output;
    EXPECT_EQ(waitpid(first, nullptr, WNOHANG), 0) << "the first run stopped";
    std::this_thread::sleep_for(std::chrono::milliseconds(400)); // past a checkpoint (t = 3)
    kill(first, SIGKILL);
    waitpid(first, nullptr, 0);
    EXPECT_TRUE(fs::exists(dir / "busy" / "pedesis.lock"));
    const pid_t again = start_resume_until_running(
        {"run", "run.toml", "--out", "busy", "--resume", "--set", "run.time=1e9"}, "busy");
    std::this_thread::sleep_for(std::chrono::milliseconds(200));
    kill(again, SIGTERM);
    EXPECT_EQ(wait_for(again), 75)
        << file_text(dir / ("console_" + std::to_string(runs_) + ".txt"));
    expect_complete("busy", " after SIGTERM");
    EXPECT_FALSE(fs::exists(dir / "busy" / "pedesis.lock"));
}

// A file-size limit (ulimit -f) stops the run where a write fails: exit 2, the file and
// the reason named; its last checkpoint stays whole, and the resume without the limit
// ends as the run that never met it.
TEST_F(Resume, AFullDiskStopsTheRunNamingTheFileAndTheCheckpointSurvives) {
    ASSERT_EQ(run_pedesis("run run.toml --out ref", dir, 120).exit_code, 0);
    const std::uintmax_t largest = fs::file_size(dir / "ref" / "trajectory.xyz");
    const std::string limit = std::to_string(largest / 1024 / 2); // kiB: half-way through
    const CliResult r = shell("bash -c 'ulimit -f " + limit + "; exec \"" + PEDESIS_BINARY +
                                  "\" run run.toml --out full'",
                              dir);
    EXPECT_EQ(r.exit_code, 2) << r.output;
    EXPECT_NE(r.output.find("full/trajectory.xyz.part: write error: File too large"),
              std::string::npos)
        << r.output;
    ASSERT_TRUE(fs::exists(dir / "full" / "checkpoint.bin"));
    EXPECT_FALSE(fs::exists(dir / "full" / "summary.json"));
    const CliResult resumed = run_pedesis("run run.toml --out full --resume", dir, 120);
    ASSERT_EQ(resumed.exit_code, 0) << resumed.output;
    EXPECT_NE(resumed.output.find("resuming full from full/checkpoint.bin"), std::string::npos)
        << resumed.output;
    EXPECT_EQ(directory_differences(dir / "ref", dir / "full"), "");
}

// A disk that fills: a tmpfs of half the run's size, mounted in a mount namespace of the
// test's own (unshare), so the writes fail with ENOSPC. The run stops with exit 2 naming
// the file; once there is room (the tmpfs remounted larger) the resume ends as the run
// that never met a full disk.
TEST_F(Resume, ADiskThatFillsLosesNoCheckpoint) {
    if (shell("unshare -rm true", dir).exit_code != 0)
        GTEST_SKIP() << "no user and mount namespaces here (unshare -rm): the ulimit test "
                        "above covers the write failure";
    ASSERT_EQ(run_pedesis("run run.toml --out ref", dir, 120).exit_code, 0);
    std::uintmax_t total = 0;
    for (const auto& f : fs::recursive_directory_iterator(dir / "ref"))
        if (f.is_regular_file()) total += f.file_size();
    fs::create_directories(dir / "small");
    const std::string pedesis = std::string("'") + PEDESIS_BINARY + "'";
    const CliResult r = shell(
        "unshare -rm sh -c 'mount -t tmpfs -o size=" + std::to_string(total / 2 / 1024) +
            "k tmpfs small && " + pedesis + " run run.toml --out small/run; echo \"first=$?\"; " +
            "ls small/run; mount -o remount,size=64m small && " + pedesis +
            " run run.toml --out small/run --resume; echo \"second=$?\"; cp -a small/run grown'",
        dir);
    EXPECT_NE(r.output.find("first=2"), std::string::npos) << r.output;
    EXPECT_NE(r.output.find("No space left on device"), std::string::npos) << r.output;
    EXPECT_NE(r.output.find("resuming small/run from small/run/checkpoint.bin"), std::string::npos)
        << r.output;
    EXPECT_NE(r.output.find("second=0"), std::string::npos) << r.output;
    EXPECT_EQ(directory_differences(dir / "ref", dir / "grown"), "");
}

// [output] checkpoint_seconds alone: a run killed after a few intervals has a checkpoint,
// and goes on from it.
TEST_F(Resume, CheckpointsComeOnTheWallClock) {
    std::string config = resume_config("event");
    config.replace(config.find("checkpoint_interval = 3.0"), 25, "checkpoint_seconds = 0.1");
    config.replace(config.find("time = 120.0"), 12, "time = 600.0"); // well past the kill
    write("clock.toml", config);
    ASSERT_EQ(run_pedesis("run clock.toml --out ref", dir, 120).exit_code, 0);
    const pid_t pid = start_until_running({"run", "clock.toml", "--out", "clock"}, "clock");
    std::this_thread::sleep_for(std::chrono::milliseconds(300));
    kill(pid, SIGKILL);
    waitpid(pid, nullptr, 0);
    ASSERT_TRUE(fs::exists(dir / "clock" / "checkpoint.bin")) << "no checkpoint on the clock";
    const CliResult r = run_pedesis("run clock.toml --out clock --resume", dir, 120);
    ASSERT_EQ(r.exit_code, 0) << r.output;
    EXPECT_NE(r.output.find("resuming clock from clock/checkpoint.bin"), std::string::npos)
        << r.output;
    EXPECT_EQ(directory_differences(dir / "ref", dir / "clock"), "");
    config.replace(config.find("checkpoint_seconds = 0.1"), 24, "checkpoint_seconds = -1.0");
    write("bad.toml", config);
    const CliResult bad = run_pedesis("run bad.toml --out bad", dir, 60);
    EXPECT_EQ(bad.exit_code, 2) << bad.output;
    EXPECT_NE(bad.output.find("checkpoint_seconds': must be >= 0"), std::string::npos)
        << bad.output;
}

// timeout, Slurm and mpirun signal a whole process group, often twice within
// milliseconds: the second signal must not cut the clean stop short. Each try sends
// SIGTERM (or SIGUSR1 then SIGTERM) twice, 1 ms apart, at a random instant: the run ends
// with exit 75 and every file complete, or (in set-up) by the signal with no file
// looking complete.
TEST_F(Resume, SignalsThatComeTwiceDoNotCutTheStopShort) {
    std::mt19937 random(std::random_device{}());
    std::uniform_int_distribution<int> delay_ms(0, 300);
    int clean = 0;
    for (int k = 0; k < 12; ++k) {
        const std::string out = "twice" + std::to_string(k);
        const std::vector<std::string> args{"run", "run.toml", "--out",
                                            out,   "--set",    "run.time=1e9"};
        // every other try from the launch (set-up included), the others once in the loop
        const bool in_loop = k % 4 >= 2;
        const pid_t pid = in_loop ? start_until_running(args, out)
                                  : start_pedesis(dir, dir / "console.txt", args);
        std::this_thread::sleep_for(std::chrono::milliseconds(delay_ms(random)));
        const int first = k % 2 ? SIGUSR1 : SIGTERM;
        kill(pid, first);
        std::this_thread::sleep_for(std::chrono::milliseconds(1));
        kill(pid, SIGTERM);
        const int code = wait_for(pid);
        const std::string why =
            " (try " + std::to_string(k) + ", exit " + std::to_string(code) + ")";
        if (code == 128 + first && !in_loop) { // in set-up: nothing may look complete
            EXPECT_FALSE(fs::exists(dir / out / "summary.json")) << why;
            EXPECT_FALSE(fs::exists(dir / out / "log.csv")) << why;
            continue;
        }
        EXPECT_EQ(code, 75) << why;
        expect_complete(out, why);
        ++clean;
    }
    EXPECT_GE(clean, 6) << "too few signals reached the loop to test the clean stop";
}

// Under `timeout -s TERM`, which signals the run (and, under a shell, its group), every
// run ends with its files complete.
TEST_F(Resume, UnderTimeoutEveryRunEndsComplete) {
    for (int k = 0; k < 6; ++k) {
        const std::string out = "timed" + std::to_string(k);
        const CliResult r =
            shell("timeout -s TERM 0." + std::to_string(3 + k) + " '" + PEDESIS_BINARY +
                      "' run run.toml --out " + out + " --set run.time=1e9",
                  dir);
        EXPECT_EQ(r.exit_code, 124) << r.output;
        EXPECT_NE(r.output.find("exit code 75: checkpointed"), std::string::npos) << r.output;
        expect_complete(out, ": " + r.output);
    }
}

// A record that is not what it claims (corrupt, or lengths the files do not have) is
// refused with exit 2 naming the file; nothing is cut.
TEST_F(Resume, ARecordThatDoesNotFitIsRefused) {
    const pid_t pid =
        start_until_running({"run", "run.toml", "--out", "r", "--set", "run.time=1e9"}, "r");
    std::this_thread::sleep_for(std::chrono::milliseconds(300));
    kill(pid, SIGKILL);
    waitpid(pid, nullptr, 0);
    ASSERT_TRUE(fs::exists(dir / "r" / "checkpoint.outputs.json"));
    const std::string record = read("r/checkpoint.outputs.json");
    write("r/checkpoint.outputs.json", "{\"pedesis_checkpoint_record\": 1, \"checkpoints\": 7}");
    const CliResult garbage = run_pedesis("run run.toml --out r --resume", dir, 60);
    EXPECT_EQ(garbage.exit_code, 2) << garbage.output;
    EXPECT_NE(garbage.output.find("r/checkpoint.outputs.json: no \"checkpoints\" list"),
              std::string::npos)
        << garbage.output;
    nlohmann::json j = nlohmann::json::parse(record);
    for (auto& c : j["checkpoints"]) c["log_bytes"] = 1u << 30;
    write("r/checkpoint.outputs.json", j.dump());
    const std::string log = read("r/log.csv.part");
    const CliResult longer = run_pedesis("run run.toml --out r --resume", dir, 60);
    EXPECT_EQ(longer.exit_code, 2) << longer.output;
    EXPECT_NE(longer.output.find("the checkpoint recorded: not the file the checkpoint knew"),
              std::string::npos)
        << longer.output;
    EXPECT_EQ(read("r/log.csv.part"), log);
}

// A sweep killed in a point, then `pedesis sweep --resume`: the done points are skipped,
// the killed one continues from its checkpoint, and every point's directory and the
// table end as those of a sweep never killed.
TEST_F(Resume, ASweepResumesItsInterruptedPointInPlace) {
    write("sweep.toml", "base = \"run.toml\"\n[vary]\n\"species.B.mass\" = [2.0, 3.0]\n");
    ASSERT_EQ(run_pedesis("sweep sweep.toml --out ref", dir, 120).exit_code, 0);
    const pid_t pid =
        start_pedesis(dir, dir / "console.txt", {"sweep", "sweep.toml", "--out", "sw"});
    const auto give_up = std::chrono::steady_clock::now() + std::chrono::seconds(60);
    while (!fs::exists(dir / "sw" / "point_001" / "checkpoint.bin") &&
           std::chrono::steady_clock::now() < give_up)
        std::this_thread::sleep_for(std::chrono::milliseconds(2));
    kill(pid, SIGKILL);
    waitpid(pid, nullptr, 0);
    ASSERT_TRUE(fs::exists(dir / "sw" / "point_000" / "summary.json"));
    ASSERT_FALSE(fs::exists(dir / "sw" / "point_001" / "summary.json"));
    const CliResult r = run_pedesis("sweep sweep.toml --out sw --resume", dir, 120);
    ASSERT_EQ(r.exit_code, 0) << r.output;
    EXPECT_NE(r.output.find("point_000"), std::string::npos) << r.output;
    EXPECT_NE(read("sw/logs/point_001.txt").find("resuming sw/point_001 from"), std::string::npos)
        << read("sw/logs/point_001.txt");
    for (const char* point : {"point_000", "point_001"})
        EXPECT_EQ(directory_differences(dir / "ref" / point, dir / "sw" / point), "") << point;
    EXPECT_EQ(read("sw/sweep.csv"), read("ref/sweep.csv"));
}

TEST_F(Resume, SteeringAndRestartDoNotMixWithResume) {
    const CliResult view = run_pedesis("run run.toml --out v --resume --view", dir, 60);
    EXPECT_EQ(view.exit_code, 2) << view.output;
    EXPECT_NE(view.output.find("--view and --steering cannot be given with it"), std::string::npos)
        << view.output;
    const CliResult restart =
        run_pedesis("run run.toml --out v --resume --restart x/checkpoint.bin", dir, 60);
    EXPECT_EQ(restart.exit_code, 2) << restart.output;
    EXPECT_NE(restart.output.find("excludes"), std::string::npos) << restart.output;
}

} // namespace
} // namespace pedesis::test
