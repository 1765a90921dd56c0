// A corrupt checkpoint is refused, whatever the corruption: for the checkpoint of each
// engine (event, stepped, soft), every byte of the first 64 flipped one at a time, 64
// bytes spread over the rest flipped, the file cut at every 64th of its length, and one
// byte appended. Each `pedesis run --restart` must exit 2 with a message naming the file,
// within 30 s (a hang is killed and fails), and write nothing: the run directory must not
// exist afterwards. The envelope's CRC-32 catches every one of these (a CRC detects all
// single-byte errors); the length checks catch the cuts before the CRC is computed.
#include "cli_support.hpp"

#include <fstream>

using namespace pedesis::test;
namespace fs = std::filesystem;

namespace {

class CheckpointCorruption : public ScratchDir {
  protected:
    std::string bytes_of(const fs::path& p) {
        std::ifstream in(p, std::ios::binary);
        return std::string(std::istreambuf_iterator<char>(in), {});
    }

    // Runs config.toml restarted from `text` written as bad.bin; expects a clean refusal.
    void expect_refused(const std::string& text, const std::string& what) {
        {
            std::ofstream out(dir / "bad.bin", std::ios::binary);
            out << text;
        }
        fs::remove_all(dir / "o");
        const CliResult r = run_pedesis("run longer.toml --restart bad.bin --out o", dir, 30);
        ++runs;
        EXPECT_EQ(r.exit_code, 2) << what << "\n" << r.output;
        EXPECT_NE(r.output.find("bad.bin"), std::string::npos) << what << "\n" << r.output;
        EXPECT_EQ(r.output.find("internal error"), std::string::npos) << what << "\n" << r.output;
        EXPECT_FALSE(fs::exists(dir / "o")) << what;
    }

    // `config` runs to make the checkpoint; `longer` (the same system, a later stop) is
    // what every restart runs, so that the untouched checkpoint restarts with exit 0 and
    // only the corruption can make a restart fail.
    void sweep(const std::string& config, const std::string& longer) {
        write("config.toml", config);
        write("longer.toml", longer);
        const CliResult ok = run_pedesis("run config.toml --out good", dir, 60);
        ASSERT_EQ(ok.exit_code, 0) << ok.output;
        const std::string good = bytes_of(dir / "good" / "checkpoint.bin");
        ASSERT_GT(good.size(), 256u);
        const CliResult again =
            run_pedesis("run longer.toml --restart good/checkpoint.bin --out again", dir, 60);
        ASSERT_EQ(again.exit_code, 0) << again.output;
        for (std::size_t k = 0; k < 64; ++k) {
            std::string bad = good;
            bad[k] = static_cast<char>(bad[k] ^ 0xff);
            expect_refused(bad, "byte " + std::to_string(k) + " flipped");
        }
        for (std::size_t j = 0; j < 64; ++j) {
            const std::size_t k = 64 + j * (good.size() - 64) / 64;
            std::string bad = good;
            bad[k] = static_cast<char>(bad[k] ^ 0x5a);
            expect_refused(bad, "byte " + std::to_string(k) + " changed");
        }
        for (std::size_t j = 0; j < 64; ++j)
            expect_refused(good.substr(0, j * good.size() / 64),
                           "cut at " + std::to_string(j) + "/64");
        expect_refused(good + "x", "one byte appended");
    }

    int runs = 0;
};

const std::string hard_output = "[output]\nlog_interval = 0.5\nprogress = false\nformats = []\n";

std::string replaced(std::string text, const std::string& from, const std::string& to) {
    const auto at = text.find(from);
    EXPECT_NE(at, std::string::npos) << from;
    return text.replace(at, from.size(), to);
}

const std::string stepped =
    "dimension = 2\ndynamics = \"stepped\"\nseed = 2\n[box]\nlength = 20.0\n"
    "[[species]]\nname = \"A\"\ncount = 40\nradius = 0.5\n[stepped]\ndt = 0.01\n"
    "[run]\ntime = 1.0\n" +
    hard_output;

const std::string soft = "dimension = 2\ndynamics = \"brownian\"\nseed = 1\n[box]\nlength = 20.0\n"
                         "[[species]]\nname = \"A\"\ncount = 40\nradius = 1.0\n[initial]\n"
                         "positions = \"random\"\n[[force]]\nname = \"harmonic\"\nk = 10.0\n"
                         "[[integrator]]\nname = \"brownian\"\nT = 0.1\ngamma = 1.0\n"
                         "[run]\nsteps = 20\ndt = 0.01\n[output]\nprogress = false\nformats = []\n";

} // namespace

TEST_F(CheckpointCorruption, EventCheckpoint) {
    const std::string config = small_config() + "formats = []\n";
    sweep(config, replaced(config, "time = 2.0", "time = 3.0"));
    EXPECT_EQ(runs, 193);
}

TEST_F(CheckpointCorruption, SteppedCheckpoint) {
    sweep(stepped, replaced(stepped, "time = 1.0", "time = 1.5"));
    EXPECT_EQ(runs, 193);
}

TEST_F(CheckpointCorruption, SoftCheckpoint) {
    sweep(soft, replaced(soft, "steps = 20", "steps = 30"));
    EXPECT_EQ(runs, 193);
}
