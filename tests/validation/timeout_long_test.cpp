// 100 runs under `timeout -s TERM` at random limits (issue 52): each ends with its run
// directory complete (no .part file; log, trajectories, checkpoint and summary there),
// or, when the limit fell in set-up, with no file that looks complete.
#include "support/kill_and_resume.hpp"

#include <fmt/format.h>

namespace pedesis::test {
namespace {

namespace fs = std::filesystem;

class TimeoutLong : public ScratchDir {};

// `timeout -s TERM S pedesis run run.toml --out OUT` with a run that would never end
std::string timed_run(double seconds, const std::string& out) {
    std::ostringstream command;
    command << "timeout -s TERM " << seconds << " '" << PEDESIS_BINARY << "' run run.toml --out "
            << out << " --set run.steps=100000000";
    return command.str();
}

TEST_F(TimeoutLong, EveryRunEndsWithItsFilesComplete) {
    write("run.toml", resume_config("soft"));
    std::mt19937 random(std::random_device{}());
    std::uniform_real_distribution<double> limit(0.02, 1.5);
    int complete = 0;
    for (int k = 0; k < 100; ++k) {
        const std::string out = fmt::format("t{}", k);
        const CliResult r = shell(timed_run(limit(random), out), dir);
        EXPECT_EQ(r.exit_code, 124) << r.output;
        bool has_part = false;
        if (fs::exists(dir / out))
            for (const auto& f : fs::recursive_directory_iterator(dir / out))
                has_part = has_part || f.path().string().find(".part") != std::string::npos;
        EXPECT_FALSE(has_part) << "try " << k << ": " << r.output;
        if (fs::exists(dir / out / "summary.json")) {
            ++complete;
            for (const char* name :
                 {"log.csv", "trajectory.gsd", "trajectory.xyz", "checkpoint.bin"})
                EXPECT_TRUE(fs::exists(dir / out / name))
                    << name << ", try " << k << ": " << r.output;
        } else {
            EXPECT_FALSE(fs::exists(dir / out / "log.csv")) << "try " << k << ": " << r.output;
        }
        fs::remove_all(dir / out);
    }
    std::cout << complete << " of 100 runs were stopped in their loop, the others in set-up\n";
    EXPECT_GE(complete, 50);
}

} // namespace
} // namespace pedesis::test
