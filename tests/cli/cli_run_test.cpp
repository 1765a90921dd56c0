// End-to-end runs through the command line: outputs exist and parse, and a run
// continued from its checkpoint equals the uninterrupted run bit for bit.
#include "cli_support.hpp"

#include <nlohmann/json.hpp>

#include <atomic>
#include <chrono>
#include <thread>
#include <vector>

using namespace pedesis::test;

namespace {

class CliRun : public ScratchDir {};

std::string config_with_time(double t) {
    return "dimension = 2\nseed = 5\n[box]\nlength = 30.0\nboundary = [\"wall\", \"periodic\"]\n"
           "[[species]]\nname = \"A\"\ncount = 200\nradius = 0.5\n"
           "[[species]]\nname = \"B\"\ncount = 100\nradius = 0.7\nmass = 3.0\n"
           "[event]\nrestitution = 0.95\ntc = 1e-6\n"
           "[run]\ntime = " +
           std::to_string(t) +
           "\n[output]\nlog_interval = 0.5\nprogress = false\nformats = [\"gsd\", \"xyz\", "
           "\"json\"]\n";
}

TEST_F(CliRun, RestartContinuesBitForBit) {
    write("full.toml", config_with_time(6.0));
    write("half.toml", config_with_time(3.0));
    ASSERT_EQ(run_pedesis("run full.toml --out full", dir).exit_code, 0);
    ASSERT_EQ(run_pedesis("run half.toml --out half", dir).exit_code, 0);
    const CliResult r = run_pedesis("run full.toml --restart half/checkpoint.bin --out cont", dir);
    ASSERT_EQ(r.exit_code, 0) << r.output;
    const auto full = nlohmann::json::parse(read("full/summary.json"));
    const auto cont = nlohmann::json::parse(read("cont/summary.json"));
    EXPECT_EQ(full["pair_collisions"], cont["pair_collisions"]);
    EXPECT_EQ(full["wall_collisions"], cont["wall_collisions"]);
    // the final frames are written with round-trip precision: equal text means equal bits
    const std::string last_full = read("full/snapshots/frame_000001.json");
    // frame numbers continue across a restart: the half run wrote frames 0 and 1
    const std::string last_cont = read("cont/snapshots/frame_000002.json");
    ASSERT_FALSE(last_full.empty());
    EXPECT_EQ(last_full, last_cont);
    EXPECT_EQ(read("full/speed_histogram.csv"), read("cont/speed_histogram.csv"));
}

// (the commit itself is not compared: a binary built before the last commit names the one
// before it, with local changes)
TEST_F(CliRun, VersionNamesVersionAndCommit) {
    const CliResult r = run_pedesis("--version", dir);
    EXPECT_EQ(r.exit_code, 0) << r.output;
    EXPECT_EQ(r.output.rfind("pedesis 0.1.0 (commit ", 0), 0u) << r.output;
    EXPECT_NE(r.output.find(")"), std::string::npos) << r.output;
}

// With another process keeping cores busy, a run takes the idle ones and says so (OpenMP's
// spinning threads on a shared core made runs several times slower); --threads chooses.
// The results are the same for any thread count (the engines' promise, tested elsewhere).
TEST_F(CliRun, BusyCoresAreLeftAloneUnlessThreadsAreChosen) {
    write("run.toml", config_with_time(0.5));
    const unsigned cores = std::thread::hardware_concurrency();
    std::atomic<bool> stop{false};
    std::vector<std::thread> hogs;
    for (unsigned k = 0; k + 1 < cores; ++k)
        hogs.emplace_back([&stop] {
            volatile double x = 0.0;
            while (!stop.load(std::memory_order_relaxed)) x = x + 1.0;
        });
    std::this_thread::sleep_for(std::chrono::milliseconds(200));
    const CliResult busy = run_pedesis("run run.toml --out busy", dir);
    const CliResult chosen = run_pedesis("run run.toml --out chosen --threads 2", dir);
    stop = true;
    for (auto& h : hogs) h.join();
    ASSERT_EQ(busy.exit_code, 0) << busy.output;
    ASSERT_EQ(chosen.exit_code, 0) << chosen.output;
    if (cores >= 2)
        EXPECT_NE(busy.output.find("cores are busy with other work: running on"), std::string::npos)
            << busy.output;
    else
        EXPECT_EQ(busy.output.find("cores are busy"), std::string::npos) << busy.output;
    EXPECT_EQ(chosen.output.find("cores are busy"), std::string::npos) << chosen.output;
    EXPECT_EQ(read("busy/checkpoint.bin"), read("chosen/checkpoint.bin"));
    EXPECT_EQ(run_pedesis("run run.toml --out zero --threads 0", dir).exit_code, 2);
}

TEST_F(CliRun, FrozenSystemStopsInsteadOfLooping) {
    write("frozen.toml",
          "dimension = 2\n[box]\nlength = 10.0\n[[species]]\ncount = 4\nvelocities = \"zero\"\n"
          "[run]\ncollisions_per_particle = 5\n[output]\nprogress = false\n");
    const CliResult r = run_pedesis("run frozen.toml --out out", dir);
    ASSERT_EQ(r.exit_code, 0) << r.output;
    EXPECT_NE(r.output.find("no more events"), std::string::npos) << r.output;
}

TEST_F(CliRun, OutputsParse) {
    write("run.toml", config_with_time(2.0));
    const CliResult r = run_pedesis("run run.toml --out out", dir);
    ASSERT_EQ(r.exit_code, 0) << r.output;
    for (const char* f :
         {"config.toml", "log.csv", "trajectory.gsd", "trajectory.xyz", "speed_histogram.csv",
          "checkpoint.bin", "summary.json", "snapshots/frame_000000.json"})
        EXPECT_TRUE(std::filesystem::exists(dir / "out" / f)) << f;
    EXPECT_FALSE(std::filesystem::exists(dir / "out" / "log.csv.part"));
    const auto snap = nlohmann::json::parse(read("out/snapshots/frame_000000.json"));
    EXPECT_EQ(snap["system"]["particles"].size(), 300u);
    EXPECT_DOUBLE_EQ(snap["system"]["box"]["Lx"].get<double>(), 30.0);
    // log: header plus one row per 0.5 time units, t = 0 .. 2
    const std::string log = read("out/log.csv");
    EXPECT_EQ(std::count(log.begin(), log.end(), '\n'), 1 + 5);
    EXPECT_NE(log.find("temperature_B"), std::string::npos);
    // trajectory: two frames of 300 particles, each "300\n<comment>\n" + 300 lines
    const std::string xyz = read("out/trajectory.xyz");
    EXPECT_EQ(std::count(xyz.begin(), xyz.end(), '\n'), 2 * (2 + 300));
}

// A dense, strongly inelastic gas without the TC model collapses: the run stops with
// exit code 3 and a message, and keeps the frames and log written before the collapse
// (committed under their final names, not left as .part files). With tc it runs on.
TEST_F(CliRun, CollapseStopsCleanlyAndKeepsGoodOutput) {
    const std::string base =
        "dimension = 2\nseed = 4\n[box]\nlength = 20.0\nboundary = \"wall\"\n"
        "[[species]]\ncount = 200\nradius = 0.5\npositions = \"square\"\n"
        "[run]\ntime = 5.0\n[output]\nlog_interval = 0.05\nsnapshot_interval = 0.05\n"
        "progress = false\nformats = [\"gsd\", \"xyz\"]\n"
        "[event]\nrestitution = 0.1\nwall_restitution = 0.1\n";
    write("collapse.toml", base);
    const CliResult r = run_pedesis("run collapse.toml --out out", dir);
    ASSERT_EQ(r.exit_code, 3) << r.output;
    EXPECT_NE(r.output.find("inelastic collapse"), std::string::npos) << r.output;
    EXPECT_TRUE(std::filesystem::exists(dir / "out" / "trajectory.xyz"));
    EXPECT_TRUE(std::filesystem::exists(dir / "out" / "log.csv"));
    EXPECT_FALSE(std::filesystem::exists(dir / "out" / "trajectory.xyz.part"));
    EXPECT_TRUE(std::filesystem::exists(dir / "out" / "trajectory.gsd"));
    EXPECT_FALSE(std::filesystem::exists(dir / "out" / "trajectory.gsd.part"));
    EXPECT_FALSE(std::filesystem::exists(dir / "out" / "summary.json"));
    const std::string xyz = read("out/trajectory.xyz");
    EXPECT_GE(std::count(xyz.begin(), xyz.end(), '\n'), 2 * (2 + 200)); // whole frames only
    EXPECT_EQ(std::count(xyz.begin(), xyz.end(), '\n') % (2 + 200), 0);

    write("tc.toml", base + "tc = 1e-3\n");
    const CliResult ok = run_pedesis("run tc.toml --out tc", dir);
    EXPECT_EQ(ok.exit_code, 0) << ok.output;
}

TEST_F(CliRun, BenchPrintsItsFigures) {
    const CliResult r =
        run_pedesis("bench event --dim 3 --n 500 --eta 0.3 --time 0.5 --warmup 0.1", dir);
    ASSERT_EQ(r.exit_code, 0) << r.output;
    EXPECT_NE(r.output.find("collisions_per_second: "), std::string::npos);
    EXPECT_NE(r.output.find("bytes_per_particle: "), std::string::npos);
    EXPECT_NE(r.output.find("max_rss_bytes_per_particle: "), std::string::npos);
}

TEST_F(CliRun, BenchRunsAMixtureAndRefusesImpossibleOnes) {
    // 8 x 4^3 particles: 256 large and 256 small in the rock-salt arrangement
    const CliResult r =
        run_pedesis("bench event --n 512 --eta 0.3 --size-ratio 0.5 --time 0.3 --warmup 0.1", dir);
    ASSERT_EQ(r.exit_code, 0) << r.output;
    EXPECT_NE(r.output.find("size ratio 0.5"), std::string::npos) << r.output;
    EXPECT_NE(r.output.find("collisions_per_second: "), std::string::npos);
    for (const char* bad : {"--n 500 --size-ratio 0.5", "--n 512 --size-ratio 1.5",
                            "--n 512 --size-ratio 0.9 --eta 0.6", "--dim 2 --size-ratio 0.5"}) {
        const CliResult b = run_pedesis(std::string("bench event --time 0.1 ") + bad, dir);
        EXPECT_EQ(b.exit_code, 2) << bad << ": " << b.output;
        EXPECT_NE(b.output.find("--size-ratio"), std::string::npos) << bad << ": " << b.output;
    }
}

} // namespace
