// From the start LAMMPS wrote for in.lj at 4000 atoms (tests/data/inlj), the means of T,
// U/N and P over steps 1000-6000 against LAMMPS' own run of the same start (label
// validation: 6000 steps, about 20 s each in a release build, too long for the sanitizer
// job).
#include "cli/cli_support.hpp"
#include "support/inlj_config.hpp"

#include <nlohmann/json.hpp>

#include <cmath>
#include <fstream>

namespace pedesis::test {
namespace {

// The same start in both codes: the trajectories part (chaos), the statistics do not.
// Means over steps 1000-6000 (501 rows, every 10 steps), standard errors from 10 block
// means of 500 steps each (2.5 time units, several decorrelation times of T and P);
// tolerance 4 standard errors of the difference. In double and in mixed precision (float
// pair rows, issue 54), each against LAMMPS's double run.
class InLjPrecision : public ScratchDir, public ::testing::WithParamInterface<const char*> {};

TEST_P(InLjPrecision, AgreesWithLammpsFromTheSameStart) {
    write("lammps.toml",
          inlj("[initial]\nfile = \"" + inlj_data_dir + "/start.json\"\n", 0.3, 6000, 10));
    const CliResult r =
        run_pedesis(std::string("run lammps.toml --out out --precision ") + GetParam(), dir, 300);
    ASSERT_EQ(r.exit_code, 0) << r.output;
    const auto log = csv_columns(read("out/log.csv"));
    const auto step = log.numbers("step");
    std::ifstream in(inlj_data_dir + "/reference.json");
    const auto reference = nlohmann::json::parse(in);
    struct Quantity {
        const char* column;
        const char* reference;
        double scale;
    };
    for (const Quantity q :
         {Quantity{"temperature", "temperature", 1.0},
          Quantity{"potential_energy", "potential_energy_per_particle", 1.0 / 4000.0},
          Quantity{"pressure", "pressure", 1.0}}) {
        const auto values = log.numbers(q.column);
        std::vector<double> kept;
        for (std::size_t i = 0; i < values.size(); ++i)
            if (step[i] >= 1000) kept.push_back(values[i] * q.scale);
        ASSERT_EQ(kept.size(), 501u);
        const std::size_t blocks = 10, size = kept.size() / blocks;
        double mean = 0.0;
        for (double v : kept) mean += v;
        mean /= static_cast<double>(kept.size());
        std::vector<double> block_means(blocks, 0.0);
        for (std::size_t b = 0; b < blocks; ++b) {
            for (std::size_t i = b * size; i < (b + 1) * size; ++i) block_means[b] += kept[i];
            block_means[b] /= static_cast<double>(size);
        }
        double var = 0.0, block_mean = 0.0;
        for (double m : block_means) block_mean += m / blocks;
        for (double m : block_means) var += (m - block_mean) * (m - block_mean) / (blocks - 1);
        const double se = std::sqrt(var / blocks);
        const double ref = reference[q.reference]["mean"].get<double>();
        const double ref_se = reference[q.reference]["standard_error"].get<double>();
        EXPECT_NEAR(mean, ref, 4.0 * std::hypot(se, ref_se))
            << q.column << ": pedesis " << mean << " +- " << se << ", LAMMPS " << ref << " +- "
            << ref_se;
    }
}

INSTANTIATE_TEST_SUITE_P(Precisions, InLjPrecision, ::testing::Values("double", "mixed"));

} // namespace
} // namespace pedesis::test
