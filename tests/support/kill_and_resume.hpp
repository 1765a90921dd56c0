#pragma once
// Kills real runs with SIGKILL (or stops them with SIGTERM) at random instants and
// resumes them in place (--resume),
// again and again, until they finish; then every file of the run directory must be the
// one a run that was never killed wrote, byte for byte. summary.json may differ only in
// its timings. Each kill is classed by what the directory shows it interrupted.
#include "cli/cli_support.hpp"

#include <nlohmann/json.hpp>

#include <chrono>
#include <csignal>
#include <cstdlib>
#include <map>
#include <random>
#include <thread>

namespace pedesis::test {

// A config of each engine that runs for about a second here, writing every frame format
// that grows (GSD, XYZ) and VTP snapshots, with a checkpoint every few log rows.
inline std::string resume_config(const std::string& engine) {
    const std::string frames = "formats = [\"gsd\", \"xyz\", \"vtp\"]\nprogress = false\n";
    if (engine == "event")
        return "dimension = 2\nseed = 3\n[box]\nlength = 50.0\n[[species]]\nname = \"A\"\n"
               "count = 800\nradius = 0.5\n[[species]]\nname = \"B\"\ncount = 100\nradius = "
               "0.8\nmass = 3.0\n[run]\ntime = 120.0\n[output]\nlog_interval = 0.5\n"
               "snapshot_interval = 2.0\ncheckpoint_interval = 3.0\n" +
               frames;
    if (engine == "stepped")
        return "dimension = 2\ndynamics = \"stepped\"\nseed = 2\n[box]\nlength = 50.0\n"
               "[[species]]\nname = \"A\"\ncount = 800\nradius = 0.5\n[stepped]\ndt = 0.002\n"
               "[run]\ntime = 8.0\n[output]\nlog_interval = 0.05\nsnapshot_interval = 0.25\n"
               "checkpoint_interval = 0.4\n" +
               frames;
    return "dimension = 2\ndynamics = \"brownian\"\nseed = 1\n[box]\nlength = 50.0\n"
           "[[species]]\nname = \"A\"\ncount = 1000\nradius = 1.0\n[initial]\n"
           "positions = \"random\"\n[[force]]\nname = \"harmonic\"\nk = 10.0\n[[force]]\n"
           "name = \"self_propulsion\"\nalpha = 1.0\n[[torque]]\nname = \"polar_align\"\n"
           "J = 0.5\na = 2.0\n[[integrator]]\nname = \"brownian\"\nT = 0.1\ngamma = 1.0\n"
           "[[integrator]]\nname = \"brownian_rotation\"\nT = 0.1\ngamma = 1.0\n[run]\n"
           "steps = 12000\ndt = 0.005\n[output]\nlog_every = 100\nsnapshot_every = 500\n"
           "checkpoint_every = 1500\n" +
           frames;
}

// The timings of summary.json, the one difference a resumed run may show.
inline nlohmann::json without_timings(nlohmann::json j) {
    for (const char* key : {"wall_seconds", "stepping_seconds", "particle_steps_per_second",
                            "collisions_per_second", "cpu_seconds"})
        j.erase(key);
    return j;
}

inline std::string file_text(const std::filesystem::path& p) {
    std::ifstream in(p, std::ios::binary);
    return {std::istreambuf_iterator<char>(in), {}};
}

// The files of `got` that differ from `want`'s, are missing or are extra ("" if none).
inline std::string directory_differences(const std::filesystem::path& want,
                                         const std::filesystem::path& got) {
    namespace fs = std::filesystem;
    std::string diff;
    std::map<std::string, bool> seen;
    for (const auto& e : fs::recursive_directory_iterator(want)) {
        if (!e.is_regular_file()) continue;
        const std::string rel = fs::relative(e.path(), want).string();
        seen[rel] = true;
        if (!fs::exists(got / rel)) {
            diff += " missing:" + rel;
            continue;
        }
        const std::string a = file_text(e.path()), b = file_text(got / rel);
        if (rel == "summary.json") {
            if (without_timings(nlohmann::json::parse(a)) !=
                without_timings(nlohmann::json::parse(b)))
                diff += " differs:" + rel;
        } else if (a != b) {
            diff += " differs:" + rel;
        }
    }
    for (const auto& e : fs::recursive_directory_iterator(got))
        if (e.is_regular_file() && !seen.count(fs::relative(e.path(), got).string()))
            diff += " extra:" + fs::relative(e.path(), got).string();
    return diff;
}

// What the directory shows the kill interrupted.
inline std::string kill_class(const std::filesystem::path& run) {
    namespace fs = std::filesystem;
    if (!fs::exists(run / "config.toml")) return "set-up";
    for (const fs::path& d : {run, run / "snapshots"}) {
        if (!fs::is_directory(d)) continue;
        for (const auto& e : fs::directory_iterator(d)) {
            const std::string name = e.path().filename().string();
            if (name.find(".tmp.") == std::string::npos) continue;
            if (name.rfind("checkpoint", 0) == 0) return "a checkpoint write";
            if (d == run / "snapshots") return "a snapshot write";
            return "another atomic write";
        }
    }
    if (fs::exists(run / "log.csv.part")) {
        const std::string log = file_text(run / "log.csv.part");
        if (!log.empty() && log.back() != '\n') return "a log row";
    }
    if (fs::exists(run / "summary.json") || fs::exists(run / "checkpoint.previous.bin"))
        return "the close";
    if (!fs::exists(run / "checkpoint.bin")) return "steps before the first checkpoint";
    return "steps";
}

struct KillTally {
    int kills = 0, resumes = 0;
    std::map<std::string, int> by_class;
};

// Runs `engine`'s config once through, then `kills` times: a fresh run killed at a random
// instant, resumed (and, half the time, killed again, up to three times) until a resume
// ends by itself; each finished directory is compared with the first.
inline KillTally kill_and_resume(const std::filesystem::path& dir, const std::string& engine,
                                 int kills) {
    namespace fs = std::filesystem;
    KillTally tally;
    std::ofstream(dir / "run.toml") << resume_config(engine);
    const auto t0 = std::chrono::steady_clock::now();
    const CliResult ref = run_pedesis("run run.toml --out ref --threads 1", dir, 120);
    EXPECT_EQ(ref.exit_code, 0) << ref.output;
    if (ref.exit_code != 0) return tally;
    const double seconds =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    std::random_device device;
    const unsigned seed = std::getenv("PEDESIS_KILL_SEED")
                              ? static_cast<unsigned>(std::atoi(std::getenv("PEDESIS_KILL_SEED")))
                              : device();
    std::mt19937 random(seed);
    std::uniform_real_distribution<double> uniform(0.0, 1.0);
    // (a run may end before its kill: then another, until `kills` kills or thrice as many runs)
    for (int k = 0; tally.kills < kills && k < 3 * kills; ++k) {
        const fs::path run = dir / "killed";
        fs::remove_all(run);
        // one thread: each run as fast as it goes beside the other tests of `make test`
        std::vector<std::string> args{"run", "run.toml", "--out", "killed", "--threads", "1"};
        bool ended_by_itself = false;
        for (int round = 0; round < 5 && !ended_by_itself; ++round) {
            const pid_t pid = start_pedesis(dir, dir / "console.txt", args);
            // the last round is never killed; the others at a random instant of the run
            const bool kill_it = round == 0 || (round < 4 && uniform(random) < 0.5);
            if (kill_it)
                std::this_thread::sleep_for(
                    std::chrono::duration<double>(seconds * uniform(random)));
            int status = 0;
            if (kill_it && waitpid(pid, &status, WNOHANG) == 0) {
                // one stop in four is a scheduler's SIGTERM: a clean stop at whatever step
                // it lands on, whose checkpoint then lies off every grid
                const bool term = uniform(random) < 0.25;
                kill(pid, term ? SIGTERM : SIGKILL);
                waitpid(pid, &status, 0);
                ++tally.kills;
                const bool clean = WIFEXITED(status) && WEXITSTATUS(status) == 75;
                ++tally.by_class[term ? (clean ? "SIGTERM, a clean stop" : "SIGTERM in set-up")
                                      : kill_class(run)];
            } else {
                if (!kill_it) waitpid(pid, &status, 0);
                ended_by_itself = true;
                const bool ok = WIFEXITED(status) && WEXITSTATUS(status) == 0;
                EXPECT_TRUE(ok) << engine << " (seed " << seed << ", kill " << k
                                << "): the resumed run did not finish: "
                                << file_text(dir / "console.txt");
                if (!ok) return tally;
            }
            args = {"run", "run.toml", "--out", "killed", "--resume", "--threads", "1"};
            if (!ended_by_itself) ++tally.resumes;
        }
        const std::string diff = directory_differences(dir / "ref", run);
        EXPECT_EQ(diff, "") << engine << " (seed " << seed << ", kill " << k << ")";
        if (!diff.empty()) return tally;
    }
    std::cout << engine << ": " << tally.kills << " kills, " << tally.resumes << " resumes (seed "
              << seed << "); killed during:";
    for (const auto& [what, n] : tally.by_class) std::cout << " " << what << " " << n << ";";
    std::cout << "\n";
    return tally;
}

} // namespace pedesis::test
