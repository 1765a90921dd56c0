// precision = "mixed" through the real binary (issue 54): the run says which precision
// its pair math ran in (console and summary.json), `--precision mixed` is the key set and
// recorded as one, bad values and engines or devices without it are refused with exit 2,
// the forces are bit-identical on 1 and 2 threads, and in.lj (4000 atoms, the start
// LAMMPS wrote, LJ shifted so that the energy is continuous) keeps its energy in float
// pair math about as well as in double.
#include "cli/cli_support.hpp"
#include "support/inlj_config.hpp"

#include "pedesis/core/simd_level.hpp"

#include <nlohmann/json.hpp>

#include <algorithm>
#include <cmath>

namespace pedesis::test {
namespace {

class MixedPrecision : public ScratchDir {
  protected:
    void SetUp() override {
        ScratchDir::SetUp();
        std::string config =
            inlj("[initial]\nfile = \"" + inlj_data_dir + "/start.json\"\n", 0.3, 2000, 100);
        const std::string cut = "cutoff = 2.5\n";
        config.replace(config.find(cut), cut.size(), cut + "shift = true\n");
        write("inlj.toml", config);
    }

    // The largest |E/N - E/N at step 200| over the log (after the lattice has melted).
    static double energy_drift(const CsvColumns& log) {
        const auto step = log.numbers("step");
        const auto energy = log.numbers("total_energy");
        double reference = 0.0, worst = 0.0;
        for (std::size_t i = 0; i < step.size(); ++i) {
            if (step[i] == 200) reference = energy[i] / 4000.0;
            if (step[i] >= 200) worst = std::max(worst, std::abs(energy[i] / 4000.0 - reference));
        }
        return worst;
    }
};

// The mixed rows exist with the avx2 and avx512 sets; under sse2 the run says it stayed
// in double.
TEST_F(MixedPrecision, TheRunSaysWhichPrecisionItsPairMathRanIn) {
    const bool has_mixed_rows = simd_level() != SimdLevel::sse2;
    const CliResult r = run_pedesis("run inlj.toml --out mixed --precision mixed", dir, 120);
    ASSERT_EQ(r.exit_code, 0) << r.output;
    const std::string expected = has_mixed_rows ? "pair math in mixed\n"
                                                : "pair math in double (precision = \"mixed\" "
                                                  "needs one radius";
    EXPECT_NE(r.output.find(expected), std::string::npos) << r.output;
    const auto summary = nlohmann::json::parse(read("mixed/summary.json"));
    EXPECT_EQ(summary.value("precision", ""), has_mixed_rows ? "mixed" : "double");
    // the flag is the key, and the run directory's config records it
    EXPECT_NE(read("mixed/config.toml").find("precision = \"mixed\""), std::string::npos);
    ASSERT_EQ(
        run_pedesis("run inlj.toml --out set --set 'precision=\"mixed\"'", dir, 120).exit_code, 0);
    EXPECT_EQ(read("set/log.csv"), read("mixed/log.csv"));
    // the default is double, and says so
    const CliResult d = run_pedesis("run inlj.toml --out double", dir, 120);
    ASSERT_EQ(d.exit_code, 0) << d.output;
    EXPECT_NE(d.output.find("pair math in double\n"), std::string::npos) << d.output;
    EXPECT_EQ(nlohmann::json::parse(read("double/summary.json")).value("precision", ""), "double");
    if (has_mixed_rows) {
        EXPECT_NE(read("double/log.csv"), read("mixed/log.csv"));
    }

    // NVE energy: the shifted potential's force still jumps at the cutoff, so neither run
    // conserves it exactly; over 1800 steps both stay within 2e-4 eps per particle of
    // step 200 (measured on an Intel Xeon with avx512: 1.4e-4 and 1.2e-4 over 20,000
    // steps), and float pair math adds no drift of its own (within 1e-4 of double's)
    const double drift_double = energy_drift(csv_columns(read("double/log.csv")));
    const double drift_mixed = energy_drift(csv_columns(read("mixed/log.csv")));
    EXPECT_LT(drift_double, 2e-4);
    EXPECT_LT(drift_mixed, 2e-4);
    EXPECT_LT(drift_mixed, drift_double + 1e-4);
}

TEST_F(MixedPrecision, MixedRunsAreTheSameOnAnyNumberOfThreads) {
    std::string config = read("inlj.toml");
    config.replace(config.find("steps = 2000"), 12, "steps = 300");
    write("short.toml", config);
    for (const char* threads : {"1", "2"}) {
        const CliResult r = run_pedesis(std::string("run short.toml --precision mixed --threads ") +
                                            threads + " --out t" + threads,
                                        dir, 120);
        ASSERT_EQ(r.exit_code, 0) << r.output;
    }
    EXPECT_EQ(read("t1/log.csv"), read("t2/log.csv"));
}

TEST_F(MixedPrecision, BadValuesAndEnginesWithoutItAreRefused) {
    const CliResult half = run_pedesis("run inlj.toml --out h --set 'precision=\"half\"'", dir, 60);
    EXPECT_EQ(half.exit_code, 2) << half.output;
    EXPECT_NE(half.output.find("precision': must be \"double\" or \"mixed\", not \"half\""),
              std::string::npos)
        << half.output;
    const CliResult flag = run_pedesis("run inlj.toml --out f --precision single", dir, 60);
    EXPECT_EQ(flag.exit_code, 2) << flag.output;
    EXPECT_NE(flag.output.find("--precision"), std::string::npos) << flag.output;
    const CliResult gpu =
        run_pedesis("run inlj.toml --out g --precision mixed --device gpu", dir, 60);
    EXPECT_EQ(gpu.exit_code, 2) << gpu.output;
    EXPECT_NE(gpu.output.find("runs on the CPU (the GPU path computes in double only)"),
              std::string::npos)
        << gpu.output;
    const CliResult event =
        run_pedesis("run '" + std::string(PEDESIS_SOURCE_DIR) +
                        "/examples/course_1_relaxation.toml' --out e --precision mixed",
                    dir, 60);
    EXPECT_EQ(event.exit_code, 2) << event.output;
    EXPECT_NE(event.output.find("the hard engines compute in double, exactly"), std::string::npos)
        << event.output;
    const CliResult bench = run_pedesis("bench abp --precision quad", dir, 60);
    EXPECT_EQ(bench.exit_code, 2) << bench.output;
}

TEST_F(MixedPrecision, BenchSaysWhichPrecisionRan) {
    for (const char* model : {"lj", "abp"}) {
        const CliResult r = run_pedesis(std::string("bench abp --model ") + model +
                                            " --n 4000 --steps 20 --warmup 2 --precision mixed",
                                        dir, 120);
        ASSERT_EQ(r.exit_code, 0) << r.output;
        EXPECT_NE(r.output.find(simd_level() == SimdLevel::sse2 ? "precision: double\n"
                                                                : "precision: mixed\n"),
                  std::string::npos)
            << r.output;
    }
}

} // namespace
} // namespace pedesis::test
