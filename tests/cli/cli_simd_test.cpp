// PEDESIS_SIMD and what pedesis says about its CPU kernels: --version and a soft or event
// run's console and summary name the set in use; an unknown set or one the CPU lacks is bad
// input (exit 2, one message).
#include "cli/cli_support.hpp"

#include "pedesis/core/simd_level.hpp"

#include <nlohmann/json.hpp>

#include <fstream>

namespace pedesis::test {
namespace {

using CpuKernels = ScratchDir;

CliResult with_simd(const std::string& set, const std::string& args,
                    const std::filesystem::path& dir) {
    return shell("PEDESIS_SIMD=" + set + " timeout -s KILL 60 '" + std::string(PEDESIS_BINARY) +
                     "' " + args,
                 dir);
}

// Runs `config` under `level` into `out`: the run succeeds, its console and summary.json
// name the set; returns the summary.
nlohmann::json run_saying_the_set(SimdLevel level, const std::string& config,
                                  const std::string& out, const std::filesystem::path& dir) {
    const CliResult r = with_simd(simd_name(level), "run " + config + " --out " + out, dir);
    EXPECT_EQ(r.exit_code, 0) << r.output;
    EXPECT_NE(r.output.find(std::string("CPU kernels: ") + simd_name(level)), std::string::npos)
        << r.output;
    std::ifstream in(dir / out / "summary.json");
    const auto summary = nlohmann::json::parse(in, nullptr, false);
    EXPECT_FALSE(summary.is_discarded()) << "no readable summary.json in " << out;
    if (!summary.is_discarded()) {
        EXPECT_EQ(summary.value("cpu_kernels", ""), simd_name(level));
    }
    return summary;
}

TEST_F(CpuKernels, VersionNamesTheSetInUse) {
    for (const SimdLevel level : available_simd_levels()) {
        const CliResult r = with_simd(simd_name(level), "--version", dir);
        EXPECT_EQ(r.exit_code, 0) << r.output;
        EXPECT_NE(r.output.find(std::string("CPU kernels: ") + simd_name(level) + " "),
                  std::string::npos)
            << r.output;
    }
    // without PEDESIS_SIMD: the best this CPU runs
    const CliResult r = with_simd("", "--version", dir);
    EXPECT_NE(
        r.output.find(std::string("CPU kernels: ") + simd_name(available_simd_levels().back())),
        std::string::npos)
        << r.output;
}

TEST_F(CpuKernels, AnUnknownSetOrOneTheCpuLacksIsRefused) {
    const CliResult unknown = with_simd("avx3", "--version", dir);
    EXPECT_EQ(unknown.exit_code, 2) << unknown.output;
    EXPECT_NE(unknown.output.find("PEDESIS_SIMD = \"avx3\": not a kernel set"), std::string::npos)
        << unknown.output;
    if (available_simd_levels().back() != SimdLevel::avx512) {
        const CliResult lacking = with_simd("avx512", "--version", dir);
        EXPECT_EQ(lacking.exit_code, 2) << lacking.output;
        EXPECT_NE(lacking.output.find("this CPU or build runs only"), std::string::npos)
            << lacking.output;
    }
}

TEST_F(CpuKernels, ASoftRunSaysWhichSetRan) {
    write("soft.toml", R"(dimension = 3
dynamics = "langevin"
seed = 3
[box]
length = 8
[[species]]
name = "A"
count = 200
radius = 0.5
[[force]]
name = "harmonic"
k = 10.0
[[integrator]]
name = "langevin"
T = 1.0
gamma = 1.0
[run]
steps = 20
dt = 0.002
[output]
log_every = 10
)");
    for (const SimdLevel level : available_simd_levels())
        run_saying_the_set(level, "soft.toml", std::string("out_") + simd_name(level), dir);
}

// The event engine's predictions run in the kernel set too (four pairs per instruction
// with AVX2), and must not change a bit of the run: the log and the checkpoint of every
// set are the sse2 run's, byte for byte.
TEST_F(CpuKernels, AnEventRunSaysWhichSetRanAndEverySetRunsItTheSame) {
    write("gas.toml", R"(dimension = 3
seed = 5
[box]
length = 12.0
[[species]]
name = "big"
count = 300
radius = 0.5
[[species]]
name = "small"
count = 200
radius = 0.3
mass = 0.4
[initial]
positions = "random"
velocities = "maxwell_boltzmann"
temperature = 1.0
[run]
collisions_per_particle = 30
[output]
log_interval = 0.5
)");
    std::string log_sse2, checkpoint_sse2;
    for (const SimdLevel level : available_simd_levels()) {
        const std::string out = std::string("event_") + simd_name(level);
        const nlohmann::json summary = run_saying_the_set(level, "gas.toml", out, dir);
        EXPECT_GE(summary.value("pair_collisions", 0.0), 30.0 * 500);
        const std::string log = read(out + "/log.csv");
        const std::string checkpoint = read(out + "/checkpoint.bin");
        ASSERT_GT(log.size(), 1000u);
        ASSERT_GT(checkpoint.size(), 1000u);
        if (level == SimdLevel::sse2) {
            log_sse2 = log;
            checkpoint_sse2 = checkpoint;
        } else {
            EXPECT_TRUE(log == log_sse2) << "log.csv differs from the sse2 run's";
            EXPECT_TRUE(checkpoint == checkpoint_sse2)
                << "checkpoint.bin differs from the sse2 run's";
        }
    }
}

} // namespace
} // namespace pedesis::test
