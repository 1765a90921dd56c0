// `pedesis sweep`: a base config and keys to vary give one run directory per point and
// one table of their summaries; a stopped sweep resumes by skipping the points done;
// shards of a job array make the same table; bad sweep files are refused before any run.
#include "cli_support.hpp"

#include <chrono>
#include <csignal>
#include <fcntl.h>
#include <thread>
#include <unistd.h>

namespace pedesis::test {
namespace {

namespace fs = std::filesystem;

const std::string base = "dimension = 2\nseed = 3\n[box]\nlength = 20.0\nboundary = \"wall\"\n"
                         "[[species]]\nname = \"A\"\ncount = 50\nradius = 0.5\n[event]\n"
                         "restitution = 1.0\n[run]\ntime = 2.0\n[output]\nlog_interval = 0.5\n"
                         "progress = false\nformats = []\n";

const std::string six_points = "base = \"base.toml\"\nout = \"out\"\n[vary]\n"
                               "\"event.restitution\" = [1.0, 0.9]\n"
                               "\"species.A.count\" = [20, 50, 80]\n";

class Sweep : public ScratchDir {
  protected:
    void SetUp() override {
        ScratchDir::SetUp();
        write("base.toml", base);
        write("sweep.toml", six_points);
    }
    static std::size_t count(const std::string& text, const std::string& what) {
        std::size_t n = 0;
        for (auto at = text.find(what); at != std::string::npos; at = text.find(what, at + 1)) ++n;
        return n;
    }
};

TEST_F(Sweep, SixPointsGiveSixRunsAndOneTable) {
    const CliResult r = run_pedesis("sweep sweep.toml", dir, 120);
    ASSERT_EQ(r.exit_code, 0) << r.output;
    EXPECT_NE(r.output.find("6 of 6 points done"), std::string::npos) << r.output;
    const CsvColumns t = csv_columns(read("out/sweep.csv"));
    ASSERT_EQ(t.cells.at("point").size(), 6u);
    // the first key varies slowest; the values are those of the sweep file
    EXPECT_EQ(t.cells.at("event.restitution"),
              (std::vector<std::string>{"1", "1", "1", "0.9", "0.9", "0.9"}));
    EXPECT_EQ(t.cells.at("species.A.count"),
              (std::vector<std::string>{"20", "50", "80", "20", "50", "80"}));
    for (std::size_t k = 0; k < 6; ++k) {
        EXPECT_EQ(t.cells.at("status")[k], "done");
        // each run is the point it claims to be: N, and energy kept only when elastic
        EXPECT_EQ(t.cells.at("particles")[k], t.cells.at("species.A.count")[k]);
        const double kept = std::stod(t.cells.at("final.energy_fraction")[k]);
        if (k < 3)
            EXPECT_NEAR(kept, 1.0, 1e-9) << k;
        else
            EXPECT_LT(kept, 0.999) << k;
        EXPECT_TRUE(fs::exists(dir / "out" / ("point_00" + std::to_string(k)) / "log.csv"));
    }
    // no wall-clock column: the table does not depend on how the points ran
    for (const auto& name : t.names) EXPECT_EQ(name.find("second"), std::string::npos) << name;
}

TEST_F(Sweep, AStoppedSweepResumesSkippingThePointsDone) {
    ASSERT_EQ(run_pedesis("sweep sweep.toml", dir, 120).exit_code, 0);
    const std::string whole = read("out/sweep.csv");
    fs::remove(dir / "out/point_004/summary.json"); // as if stopped during point 4
    const CliResult list = run_pedesis("sweep sweep.toml --list", dir, 60);
    EXPECT_EQ(count(list.output, " done\n"), 5u) << list.output;
    const CliResult r = run_pedesis("sweep sweep.toml", dir, 120);
    ASSERT_EQ(r.exit_code, 0) << r.output;
    EXPECT_EQ(count(r.output, "already done"), 5u) << r.output;
    EXPECT_NE(r.output.find("point_004 (event.restitution = 0.9, species.A.count = 50) done in"),
              std::string::npos)
        << r.output;
    EXPECT_EQ(read("out/sweep.csv"), whole);
}

TEST_F(Sweep, KeysKeepTheOrderOfTheFileTheFirstVaryingSlowest) {
    write("order.toml", "base = \"base.toml\"\n[vary]\n\"species.A.count\" = [20, 50]\n"
                        "\"event.restitution\" = [1.0, 0.9]\n");
    const CliResult r = run_pedesis("sweep order.toml --out order --list", dir, 60);
    ASSERT_EQ(r.exit_code, 0) << r.output;
    EXPECT_EQ(r.output, "point_000 (species.A.count = 20, event.restitution = 1)\n"
                        "point_001 (species.A.count = 20, event.restitution = 0.9)\n"
                        "point_002 (species.A.count = 50, event.restitution = 1)\n"
                        "point_003 (species.A.count = 50, event.restitution = 0.9)\n");
}

TEST_F(Sweep, ShardsOfAJobArrayMakeTheSameTable) {
    ASSERT_EQ(run_pedesis("sweep sweep.toml --out whole", dir, 120).exit_code, 0);
    const CliResult a = run_pedesis("sweep sweep.toml --out sharded --shard 1/2", dir, 120);
    ASSERT_EQ(a.exit_code, 0) << a.output;
    EXPECT_NE(a.output.find("3 of 6 points done"), std::string::npos) << a.output;
    EXPECT_NE(read("sharded/sweep.csv").find(",not run,"), std::string::npos);
    ASSERT_EQ(run_pedesis("sweep sweep.toml --out sharded --shard 0/2", dir, 120).exit_code, 0);
    EXPECT_EQ(read("sharded/sweep.csv"), read("whole/sweep.csv"));
}

TEST_F(Sweep, ASignalStopsTheSweepAndTheNextCallGoesOn) {
    // points of about a second each; SIGTERM once the second is in its loop (its log is
    // opened there). Sent at the first point's summary it could land in the second's
    // set-up, where the process ends at once by design (core/interrupt.hpp): a sanitizer
    // build, slow to set up, did that.
    write("base.toml", "dimension = 2\ndynamics = \"stepped\"\nseed = 2\n[box]\nlength = 20.0\n"
                       "[[species]]\nname = \"A\"\ncount = 40\nradius = 0.5\n[stepped]\n"
                       "dt = 0.0001\n[run]\ntime = 10.0\n[output]\nlog_interval = 0.5\n"
                       "progress = false\nformats = []\n");
    write("sweep.toml", "base = \"base.toml\"\nout = \"out\"\n[vary]\nseed = [1, 2, 3]\n");
    const pid_t pid = fork();
    if (pid == 0) {
        if (chdir(dir.c_str()) != 0) _exit(120);
        const int fd = open("console.txt", O_WRONLY | O_CREAT | O_TRUNC, 0644);
        dup2(fd, 1);
        dup2(fd, 2);
        execl(PEDESIS_BINARY, PEDESIS_BINARY, "sweep", "sweep.toml", "--threads", "1", nullptr);
        _exit(127);
    }
    const auto give_up = std::chrono::steady_clock::now() + std::chrono::seconds(120);
    while (!fs::exists(dir / "out/point_001/log.csv.part") &&
           std::chrono::steady_clock::now() < give_up)
        std::this_thread::sleep_for(std::chrono::milliseconds(10));
    kill(pid, SIGTERM);
    int status = 0;
    waitpid(pid, &status, 0);
    // SIGTERM, a scheduler's: exit code 75, "checkpointed, resume me"
    ASSERT_TRUE(WIFEXITED(status)) << read("console.txt");
    EXPECT_EQ(WEXITSTATUS(status), 75);
    EXPECT_NE(read("console.txt").find("run the same command with --resume"), std::string::npos);
    const CsvColumns stopped = csv_columns(read("out/sweep.csv"));
    EXPECT_EQ(stopped.cells.at("status")[0], "done");
    EXPECT_NE(stopped.cells.at("status")[1], "done");
    EXPECT_EQ(stopped.cells.at("status")[2], "not run");

    const CliResult r = run_pedesis("sweep sweep.toml --threads 1", dir, 300);
    ASSERT_EQ(r.exit_code, 0) << r.output;
    EXPECT_EQ(count(r.output, "already done"), 1u) << r.output;
    EXPECT_EQ(csv_columns(read("out/sweep.csv")).cells.at("status"),
              (std::vector<std::string>{"done", "done", "done"}));
}

// What only the run of a point finds (here a missing file) fails that point: the others
// run, the table says which failed, its message is kept, and the sweep ends with exit 3.
TEST_F(Sweep, AFailingPointIsRecordedAndTheOthersRun) {
    write("failing.toml", sweep_with_a_failing_point(dir));
    const CliResult r = run_pedesis("sweep failing.toml --out failing", dir, 120);
    EXPECT_EQ(r.exit_code, 3) << r.output;
    EXPECT_NE(r.output.find("point_001 failed: failing/configs/missing.json: cannot open"),
              std::string::npos)
        << r.output;
    EXPECT_EQ(csv_columns(read("failing/sweep.csv")).cells.at("status"),
              (std::vector<std::string>{"done", "failed"}));
    EXPECT_NE(read("failing/logs/point_001.failed").find("missing.json"), std::string::npos);
}

TEST_F(Sweep, BadSweepFilesAreRefusedBeforeAnyRun) {
    const auto refused = [&](const std::string& text, const std::string& fragment) {
        write("bad.toml", text);
        const CliResult r = run_pedesis("sweep bad.toml --out bad", dir, 60);
        EXPECT_EQ(r.exit_code, 2) << text << r.output;
        EXPECT_NE(r.output.find(fragment), std::string::npos)
            << "missing '" << fragment << "' in: " << r.output;
        EXPECT_FALSE(fs::exists(dir / "bad")) << text;
    };
    const std::string head = "base = \"base.toml\"\n[vary]\n";
    refused(head + "\"force.harmonic.k\" = [1.0]\n",
            "bad.toml:3:23: [vary] key 'force.harmonic.k': the base config base.toml has no "
            "[force]");
    refused(head + "\"species.B.radius\" = [1.0]\n",
            "has no [[species]] named 'B' (it has: A; or give an index)");
    refused(head + "\"species.A.count\" = [2.5]\n", "holds a value of type integer there, the "
                                                    "sweep gives floating-point");
    refused(head + "\"event.restitution\" = []\n", "must be a non-empty list");
    refused(head + "\"run.stop_time\" = [1.0]\n", "point_000.toml");     // not a config key
    refused(head + "\"event.restitution\" = [1.5]\n", "restitution");    // out of range
    refused(head + "\"\" = [1.0]\n", "[vary] key '' has an empty part"); // a fuzzing find
    refused(head + "\"box.\" = [1.0]\n", "[vary] key 'box.' has an empty part");
    refused("[vary]\nseed = [1]\n", "needs base = ");
    refused("base = \"none.toml\"\n[vary]\nseed = [1]\n", "no such config file");
    refused(head + "seed = [1]\nextra = 2\n", "extra");
    write("ok.toml", six_points);
    const CliResult r = run_pedesis("sweep ok.toml --shard 2/2", dir, 60);
    EXPECT_EQ(r.exit_code, 2) << r.output;
    EXPECT_NE(r.output.find("--shard 2/2: expected I/N"), std::string::npos) << r.output;
}

} // namespace
} // namespace pedesis::test
