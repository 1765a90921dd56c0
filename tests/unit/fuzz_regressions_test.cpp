// Every input that once crashed a reader under the fuzzer (fuzz/regressions/<target>/)
// and every seed of the fuzz corpus (fuzz/corpus/<target>/), replayed through the fuzz
// targets' own code (fuzz/fuzz_inputs.hpp) in every build: each must be read or refused
// with an InputError. Under `make sanitize` a memory or UB error here fails the run.
#include "fuzz/fuzz_inputs.hpp"
#include "fuzz/fuzz_resume_input.hpp"
#include "fuzz/fuzz_run_input.hpp"

#include <gtest/gtest.h>

#include <fstream>
#include <iterator>
#include <vector>

namespace fs = std::filesystem;

namespace {

using Input = void (*)(const std::uint8_t*, std::size_t);

// Returns how many files were replayed.
int replay(const std::string& target, Input input) {
    int files = 0;
    for (const char* kind : {"corpus", "regressions"}) {
        const fs::path dir = fs::path(PEDESIS_SOURCE_DIR) / "fuzz" / kind / target;
        if (!fs::is_directory(dir)) continue;
        for (const auto& entry : fs::directory_iterator(dir)) {
            std::ifstream in(entry.path(), std::ios::binary);
            const std::vector<char> bytes(std::istreambuf_iterator<char>(in), {});
            SCOPED_TRACE(entry.path().string());
            try {
                input(reinterpret_cast<const std::uint8_t*>(bytes.data()), bytes.size());
            } catch (const pedesis::InputError&) {
                // a refusal with a message is the good outcome for a bad file
            }
            ++files;
        }
    }
    return files;
}

} // namespace

TEST(FuzzRegressions, ResumeRecordAndRunDirectory) {
    // a record of a real run (cut back to each entry) and a config.toml of another config
    EXPECT_GE(replay("fuzz_resume", pedesis::fuzz::resume_input), 2);
}
TEST(FuzzRegressions, ConfigReader) {
    EXPECT_GE(replay("fuzz_config", pedesis::fuzz::config_input), 3);
}
TEST(FuzzRegressions, TutorialJsonReader) {
    EXPECT_GE(replay("fuzz_tutorial_json", pedesis::fuzz::tutorial_json_input), 2);
}
TEST(FuzzRegressions, XyzReader) {
    EXPECT_GE(replay("fuzz_xyz", pedesis::fuzz::xyz_input), 1);
}
TEST(FuzzRegressions, GsdReader) {
    EXPECT_GE(replay("fuzz_gsd", pedesis::fuzz::gsd_input), 1);
}
TEST(FuzzRegressions, CheckpointLoaders) {
    // the seeds (one valid checkpoint per engine), the position of 1e236 and the radius of
    // 1e-121 that made the stepped engine's cell list compute an int out of range
    EXPECT_GE(replay("fuzz_checkpoint", pedesis::fuzz::checkpoint_input), 5);
}

// The seeds are valid: each engine's checkpoint seed restarts (no refusal at all).
TEST(FuzzRegressions, CheckpointSeedsAreValidCheckpoints) {
    for (int k = 0; k < 3; ++k) {
        const fs::path p = fs::path(PEDESIS_SOURCE_DIR) / "fuzz" / "corpus" / "fuzz_checkpoint" /
                           ("engine" + std::to_string(k) + ".bin");
        std::ifstream in(p, std::ios::binary);
        const std::vector<char> bytes(std::istreambuf_iterator<char>(in), {});
        ASSERT_FALSE(bytes.empty()) << p;
        EXPECT_NO_THROW(pedesis::fuzz::checkpoint_input(
            reinterpret_cast<const std::uint8_t*>(bytes.data()), bytes.size()))
            << p;
    }
}
TEST(FuzzRegressions, SweepReader) {
    EXPECT_GE(replay("fuzz_sweep", pedesis::fuzz::sweep_input), 3);
}

// The running target (fuzz_run): its seeds, a small config of every engine in 2D and 3D,
// and every input that once made a run crash, hang or fail other than by a documented stop.
TEST(FuzzRegressions, Runs) {
    // the 12 seeds and its first findings: a growth run that never ended (the box half a
    // contact too small), growing particles jammed against walls (an exit-3 stop that
    // must name the jam, and soon: one took 15 s under the sanitizers), coinciding soft
    // particles (refused, no NaN)
    EXPECT_GE(replay("fuzz_run", pedesis::fuzz::run_input), 19);
}

// The seeds are configs the engines accept: each is set up and run, not refused, so a change
// of the mapping from bytes to configs that made them refusals would show here.
TEST(FuzzRegressions, RunSeedsRun) {
    const fs::path dir = fs::path(PEDESIS_SOURCE_DIR) / "fuzz" / "corpus" / "fuzz_run";
    int seeds = 0;
    for (const auto& entry : fs::directory_iterator(dir)) {
        std::ifstream in(entry.path(), std::ios::binary);
        const std::vector<char> bytes(std::istreambuf_iterator<char>(in), {});
        const auto* data = reinterpret_cast<const std::uint8_t*>(bytes.data());
        EXPECT_NO_THROW(pedesis::fuzz::run_input(data, bytes.size()))
            << entry.path() << "\n"
            << pedesis::fuzz::run_config_text(data, bytes.size());
        ++seeds;
    }
    EXPECT_GE(seeds, 12);
}
