// `[run] device` and `--device`: where a soft-engine run steps. On a machine without a GPU
// (or a build without CUDA) asking for one is bad input, said once, before any output.
#include "cli/cli_support.hpp"

#include "pedesis/gpu/gpu_stepper.hpp"

namespace pedesis::test {
namespace {

std::string abp(const std::string& run_extra = "") {
    return R"(dimension = 2
dynamics = "brownian"
seed = 2
[box]
length = 20
[[species]]
name = "A"
count = 40
radius = 1.0
[[force]]
name = "harmonic"
k = 10.0
[[force]]
name = "self_propulsion"
alpha = 1.0
[[integrator]]
name = "brownian"
T = 0.1
gamma = 1.0
[[integrator]]
name = "brownian_rotation"
T = 0.1
gamma = 1.0
[run]
steps = 50
dt = 0.01
)" + run_extra +
           "[output]\nlog_every = 10\n";
}

using DeviceChoice = ScratchDir;

TEST_F(DeviceChoice, AnUnknownDeviceIsRefused) {
    expect_rejected(abp("device = \"tpu\"\n"),
                    {"bad.toml", "device", "must be \"cpu\" or \"gpu\""});
    write("ok.toml", abp());
    const CliResult r = run_pedesis("run ok.toml --device tpu --out out", dir, 60);
    EXPECT_EQ(r.exit_code, 2) << r.output;
    EXPECT_NE(r.output.find("--device"), std::string::npos) << r.output;
}

TEST_F(DeviceChoice, OnlyTheSoftEnginesRunOnTheGpu) {
    write("gas.toml", R"(dimension = 2
dynamics = "event"
seed = 1
[box]
length = 20
[[species]]
name = "A"
count = 10
radius = 0.5
[run]
time = 1.0
)");
    const CliResult r = run_pedesis("run gas.toml --device gpu --out out", dir, 60);
    EXPECT_EQ(r.exit_code, 2) << r.output;
    EXPECT_NE(r.output.find("only the soft engines"), std::string::npos) << r.output;
    EXPECT_FALSE(std::filesystem::exists(dir / "out" / "log.csv"));
}

// The CPU is the default and says nothing of a GPU; device = "gpu" runs where a GPU is
// and is refused, with the reason, where none is.
TEST_F(DeviceChoice, GpuWhereThereIsOneAndAClearRefusalWhereNot) {
    write("cpu.toml", abp("device = \"cpu\"\n"));
    const CliResult cpu = run_pedesis("run cpu.toml --out c", dir, 60);
    ASSERT_EQ(cpu.exit_code, 0) << cpu.output;
    EXPECT_EQ(cpu.output.find("GPU"), std::string::npos) << cpu.output;
    EXPECT_NE(read("c/summary.json").find("\"device\": \"cpu\""), std::string::npos);

    const std::string why = gpu_unavailable_reason();
    if (why.empty()) {
        write("gpu.toml", abp("device = \"gpu\"\n"));
        const CliResult gpu = run_pedesis("run gpu.toml --out g", dir, 60);
        EXPECT_EQ(gpu.exit_code, 0) << gpu.output;
        EXPECT_NE(gpu.output.find("on the GPU"), std::string::npos) << gpu.output;
        return;
    }
    expect_rejected(abp("device = \"gpu\"\n"), {"device = \"gpu\"", why});
    write("ok.toml", abp());
    const CliResult r = run_pedesis("run ok.toml --device gpu --out out", dir, 60);
    EXPECT_EQ(r.exit_code, 2) << r.output;
    EXPECT_NE(r.output.find(why), std::string::npos) << r.output;
    EXPECT_FALSE(std::filesystem::exists(dir / "out" / "log.csv"));
}

} // namespace
} // namespace pedesis::test
