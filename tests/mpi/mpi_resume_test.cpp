// `pedesis run --resume` under mpirun (issue 52): a soft run of 2 processes killed with
// SIGKILL at random instants, and resumed in place on 2 processes until it ends, leaves
// the directory of the run that was never killed, byte for byte.
//
// The kill takes every process of the job at once, as a dead node or a scheduler's
// cgroup does. mpirun is started in a session of its own; Open MPI puts each rank in a
// process group of its own, so the mpirun's group alone would leave the ranks running:
// the session's processes are all stopped, then all killed.
//
// summary.json may differ in its timings, and in "mpi"'s measurements of the last
// process's stepping (its seconds, seconds in MPI calls and bytes sent per step, over the
// steps that process ran); everything else, the rest of "mpi" included, must be equal.
#include "mpi/mpi_support.hpp"
#include "support/kill_and_resume.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <csignal>
#include <dirent.h>
#include <functional>
#include <unistd.h>

namespace pedesis::test {
namespace {

// The tutorial's ABP system, 2D, on a 2 x 1 grid of domains: every frame format that
// grows (GSD, XYZ) and VTP snapshots, a checkpoint every 400 steps (20 in the run).
std::string abp_config() {
    return "dimension = 2\ndynamics = \"brownian\"\nseed = 1\n[box]\nlength = 30.0\n"
           "[[species]]\nname = \"A\"\ncount = 400\nradius = 0.5\n[initial]\n"
           "positions = \"random\"\nmin_distance = 0.8\n[[force]]\nname = \"harmonic\"\n"
           "k = 50.0\n[[force]]\nname = \"self_propulsion\"\nalpha = 1.0\n[[torque]]\n"
           "name = \"polar_align\"\nJ = 0.5\na = 1.5\n[[integrator]]\nname = \"brownian\"\n"
           "T = 0.05\ngamma = 1.0\n[[integrator]]\nname = \"brownian_rotation\"\nT = 0.1\n"
           "gamma = 1.0\n[neighbor_list]\nskin = 0.4\n[run]\ndt = 0.002\nsteps = 8000\n"
           "[output]\nlog_every = 50\nsnapshot_every = 250\ncheckpoint_every = 400\n"
           "formats = [\"gsd\", \"xyz\", \"vtp\"]\nprogress = false\n";
}

// `pedesis ARGS` under mpirun on 2 processes, in a session of its own (its id is the
// returned pid), output into `console`.
pid_t start_mpi_job(const std::filesystem::path& cwd, const std::filesystem::path& console,
                    const std::vector<std::string>& args) {
    const pid_t pid = fork();
    if (pid != 0) return pid;
    setsid();
    if (chdir(cwd.c_str()) != 0) _exit(120);
    const int fd = open(console.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
    const int none = open("/dev/null", O_RDONLY);
    dup2(none, 0);
    dup2(fd, 1);
    dup2(fd, 2);
    std::vector<std::string> words{
        PEDESIS_MPIEXEC, "--allow-run-as-root", "--oversubscribe", "-np", "2", PEDESIS_BINARY};
    words.insert(words.end(), args.begin(), args.end());
    std::vector<char*> argv;
    for (auto& w : words) argv.push_back(w.data());
    argv.push_back(nullptr);
    execv(PEDESIS_MPIEXEC, argv.data());
    _exit(127);
}

// The processes of session `sid` (the session's leader included).
std::vector<pid_t> session_processes(pid_t sid) {
    std::vector<pid_t> found;
    DIR* proc = opendir("/proc");
    if (!proc) return found;
    while (const dirent* e = readdir(proc)) {
        const pid_t pid = static_cast<pid_t>(std::atoi(e->d_name));
        if (pid <= 0) continue;
        const std::string stat = file_text(std::filesystem::path("/proc") / e->d_name / "stat");
        // pid (comm) state ppid pgrp session ...: comm may hold spaces and parentheses
        const auto close = stat.rfind(')');
        if (close == std::string::npos) continue;
        std::istringstream rest(stat.substr(close + 1));
        std::string state;
        long ppid = 0, pgrp = 0, session = 0;
        rest >> state >> ppid >> pgrp >> session;
        if (session == sid && state != "Z") found.push_back(pid);
    }
    closedir(proc);
    return found;
}

// Every process of the job dies where it stands: all stopped first, so that none goes
// on (or notices another's death) while the others are killed.
void kill_job(pid_t sid) {
    for (int sweep = 0; sweep < 2; ++sweep)
        for (const pid_t p : session_processes(sid)) kill(p, SIGSTOP);
    for (int sweep = 0; sweep < 50; ++sweep) {
        const std::vector<pid_t> left = session_processes(sid);
        if (left.empty()) return;
        for (const pid_t p : left) kill(p, SIGKILL);
        std::this_thread::sleep_for(std::chrono::milliseconds(20));
    }
}

// summary.json without what depends on the process that wrote it (see the top).
nlohmann::json summary_to_compare(const std::filesystem::path& file) {
    nlohmann::json j = without_timings(nlohmann::json::parse(file_text(file)));
    if (j.contains("mpi"))
        for (const char* key : {"stepping_seconds_max", "communication_seconds_mean",
                                "communication_seconds_max", "bytes_sent_per_step"})
            j["mpi"].erase(key);
    return j;
}

using Clock = std::chrono::steady_clock;

// Waits for the job to end (its wait status), or for `until` to say so first (then -1),
// or for 120 s (then it is killed: a hang fails the test instead of stalling the suite).
int wait_job(
    pid_t job, const std::function<bool()>& until = [] { return false; }) {
    const auto limit = Clock::now() + std::chrono::seconds(120);
    int status = 0;
    while (waitpid(job, &status, WNOHANG) == 0) {
        if (until()) return -1;
        if (Clock::now() > limit) {
            kill_job(job);
            waitpid(job, &status, 0);
            ADD_FAILURE() << "a run under mpirun did not end in 120 s";
            return status;
        }
        std::this_thread::sleep_for(std::chrono::milliseconds(10));
    }
    return status;
}

bool exited_zero(int status) {
    return status >= 0 && WIFEXITED(status) && WEXITSTATUS(status) == 0;
}

class MpiResume : public ScratchDir {};

TEST_F(MpiResume, KilledAndResumedOnTwoProcessesEndsAsIfNeverKilled) {
    write("abp.toml", abp_config());
    const CliResult whole = run_mpi(2, "run abp.toml --out whole", dir, 120);
    ASSERT_EQ(whole.exit_code, 0) << whole.output;

    // PEDESIS_KILL_SEED replays the instants of a failure (its seed is in the message)
    const char* replay = std::getenv("PEDESIS_KILL_SEED");
    const unsigned seed =
        replay ? static_cast<unsigned>(std::stoul(replay)) : std::random_device{}();
    std::mt19937 random(seed);
    const std::filesystem::path run = dir / "killed";
    const auto rows = [&] {
        const std::string log = file_text(run / "log.csv.part");
        return static_cast<int>(std::count(log.begin(), log.end(), '\n'));
    };
    // The instants are drawn in steps, as rows of the log (161 in all), not in seconds: on
    // a machine shared with other work a run's pace changes from one second to the next.
    // The run is killed between rows 12 and 130, its resume at least 4 rows on and before
    // row 150, so that each kill falls between two checkpoints (every 8 rows) and before
    // the last, where a resume has a stretch to get wrong; then resumes until one ends by
    // itself.
    std::string kills;
    int killed = 0;
    bool done = false;
    for (int round = 0; round < 6 && !done; ++round) {
        std::vector<std::string> args{"run", "abp.toml", "--out", "killed"};
        if (round > 0) args.push_back("--resume");
        const pid_t job = start_mpi_job(dir, dir / "console.txt", args);
        int status = 0;
        if (round < 2) {
            // this round's set-up done (a resume has cut log.csv.part back by then)
            status = wait_job(job, [&] {
                return std::filesystem::exists(run / "log.csv.part") &&
                       file_text(dir / "console.txt").find("CPU kernels") != std::string::npos;
            });
            const int now = rows();
            const int row =
                round == 0
                    ? std::uniform_int_distribution<int>(12, 130)(random)
                    : std::uniform_int_distribution<int>(now + 4, std::max(now + 4, 150))(random);
            if (status == -1) status = wait_job(job, [&] { return rows() >= row; });
            if (status == -1) {
                // anywhere in the stretch up to the next row
                std::this_thread::sleep_for(
                    std::chrono::microseconds(std::uniform_int_distribution<int>(0, 3000)(random)));
                kill_job(job);
                waitpid(job, &status, 0);
                kills += fmt::format(" {} at row {};", kill_class(run), row);
                ++killed;
                continue;
            }
        } else {
            status = wait_job(job);
        }
        ASSERT_TRUE(exited_zero(status))
            << "seed " << seed << ", round " << round << ": " << file_text(dir / "console.txt");
        done = true;
    }
    ASSERT_TRUE(done) << "seed " << seed;
    std::cout << "killed " << killed << " times, during:" << kills << " (seed " << seed << ")\n";
    EXPECT_EQ(killed, 2) << "seed " << seed << ": a run ended before its kill";

    std::string diff = directory_differences(dir / "whole", run);
    const std::string summary = " differs:summary.json";
    if (const auto at = diff.find(summary); at != std::string::npos) {
        diff.erase(at, summary.size());
        EXPECT_EQ(summary_to_compare(run / "summary.json"),
                  summary_to_compare(dir / "whole" / "summary.json"))
            << "seed " << seed;
    }
    EXPECT_EQ(diff, "") << "seed " << seed << "; killed during:" << kills;
}

// Checkpoints on the wall clock under MPI: the processes' clocks differ, and all must
// write the checkpoint together (each deciding alone ended in MPI_ERR_TRUNCATE or a hang).
// The run ends, its trajectory that of a run without them.
TEST_F(MpiResume, CheckpointsOnTheWallClockAreTakenByAllProcessesTogether) {
    std::string config = abp_config();
    config.replace(config.find("checkpoint_every = 400"), 22, "checkpoint_seconds = 0.02");
    write("clock.toml", config);
    const CliResult r = run_mpi(2, "run clock.toml --out clock", dir, 120);
    ASSERT_EQ(r.exit_code, 0) << r.output;
    config.replace(config.find("checkpoint_seconds = 0.02"), 25, "checkpoint_seconds = 0.0");
    write("plain.toml", config);
    ASSERT_EQ(run_mpi(2, "run plain.toml --out plain", dir, 120).exit_code, 0);
    EXPECT_EQ(file_text(dir / "clock" / "trajectory.gsd"),
              file_text(dir / "plain" / "trajectory.gsd"));
}

} // namespace
} // namespace pedesis::test
