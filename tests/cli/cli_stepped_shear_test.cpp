// Lees-Edwards shear of hard disks with the stepped engine through `pedesis run`
// ([box] shear_rate with dynamics = "stepped"):
// - a sheared gas flows linearly (the profile's slope is the rate), its P_xy is negative,
//   and with no thermostat it heats by exactly the viscous heating -rate V ∫ P_xy dt: the
//   log's P_xy integrates the kinetic stress exactly, so the balance holds to rounding;
// - a restart continues bit for bit, with the shear record (profile, P_xy series), and a
//   restart at another rate is refused;
// - a rate whose flow alone would move touching disks more than max_move a step is
//   refused, naming [box] shear_rate and [stepped] dt.
#include "cli/cli_support.hpp"

#include <nlohmann/json.hpp>

#include <cstddef>
#include <regex>
#include <sstream>
#include <string>

namespace pedesis::test {
namespace {

std::string sheared_disks(double rate, double time, const std::string& extra = "") {
    std::ostringstream c;
    c << "dimension = 2\ndynamics = \"stepped\"\nseed = 5\n[box]\nlength = 20.0\nshear_rate = "
      << rate
      << "\n[[species]]\nname = \"A\"\ncount = 200\nradius = 0.5\n[initial]\nvelocities = "
         "\"maxwell_boltzmann\"\ntemperature = 1.0\n[stepped]\ndt = 0.01\n[run]\ntime = "
      << time << "\n[output]\nlog_interval = 0.5\nformats = []\nprogress = false\n"
      << extra;
    return c.str();
}

class SteppedShear : public ScratchDir {
  protected:
    nlohmann::json summary(const std::string& run) {
        return nlohmann::json::parse(read(run + "/summary.json"));
    }
};

TEST_F(SteppedShear, AShearedGasFlowsLinearlyAndHeatsByTheViscousHeating) {
    const double rate = 0.2, time = 20.0, V = 400.0;
    write("run.toml", sheared_disks(rate, time));
    const CliResult r = run_pedesis("run run.toml --out out", dir, 120);
    ASSERT_EQ(r.exit_code, 0) << r.output;
    EXPECT_NE(r.output.find("Lees–Edwards shear at rate 0.2"), std::string::npos) << r.output;
    EXPECT_NE(r.output.find("shear viscosity -<P_xy>/rate"), std::string::npos) << r.output;
    const nlohmann::json j = summary("out");
    EXPECT_LT(j.at("shear").at("shear_stress").at("value").get<double>(), 0.0);
    EXPECT_GT(j.at("shear").at("viscosity").at("value").get<double>(), 0.0);
    // the heating: the peculiar kinetic energy (N - 1) T (no total peculiar momentum)
    // grows by -rate V Σ P_xy Δt over the log's rows
    const CsvColumns log = csv_columns(read("out/log.csv"));
    const auto t = log.numbers("time"), T = log.numbers("temperature"),
               pxy = log.numbers("pressure_xy");
    ASSERT_EQ(t.size(), 41u);
    double heating = 0.0;
    for (std::size_t k = 1; k < t.size(); ++k) heating += -rate * V * pxy[k] * (t[k] - t[k - 1]);
    const double dK = 199.0 * (T.back() - T.front());
    EXPECT_GT(heating, 0.1 * 199.0 * T.front());
    EXPECT_NEAR(dK, heating, 1e-6 * heating) << T.front() << " -> " << T.back();
    // the laboratory velocity profile: a straight line of slope `rate`
    const CsvColumns profile = csv_columns(read("out/velocity_profile.csv"));
    const auto y = profile.numbers("y"), v = profile.numbers("velocity_x");
    ASSERT_EQ(y.size(), 20u);
    double sy = 0, sv = 0, syy = 0, syv = 0;
    for (std::size_t k = 0; k < y.size(); ++k) {
        sy += y[k];
        sv += v[k];
        syy += y[k] * y[k];
        syv += y[k] * v[k];
    }
    const double n = static_cast<double>(y.size());
    EXPECT_NEAR((n * syv - sy * sv) / (n * syy - sy * sy), rate, 0.1 * rate);
}

TEST_F(SteppedShear, ARestartContinuesBitForBitAndKeepsItsRate) {
    const std::string out = "snapshot_interval = 2.0\ncheckpoint_interval = 2.0\n";
    std::string full = sheared_disks(0.5, 4.0);
    full = std::regex_replace(full, std::regex("formats = \\[\\]"), "formats = [\"json\"]\n" + out);
    write("full.toml", full);
    write("half.toml", std::regex_replace(full, std::regex("time = 4\n"), "time = 2\n"));
    ASSERT_EQ(run_pedesis("run full.toml --out full", dir, 60).exit_code, 0);
    const CliResult half = run_pedesis("run half.toml --out half", dir, 60);
    ASSERT_EQ(half.exit_code, 0) << half.output;
    const CliResult cont =
        run_pedesis("run full.toml --out cont --restart half/checkpoint.bin", dir, 60);
    ASSERT_EQ(cont.exit_code, 0) << cont.output;
    const std::string a = read("full/snapshots/frame_000002.json");
    ASSERT_FALSE(a.empty());
    EXPECT_TRUE(a == read("cont/snapshots/frame_000002.json")) << "the frames at t = 4 differ";
    EXPECT_EQ(read("full/velocity_profile.csv"), read("cont/velocity_profile.csv"));
    EXPECT_EQ(summary("full").at("shear"), summary("cont").at("shear"));
    write("other.toml",
          std::regex_replace(full, std::regex("shear_rate = 0.5"), "shear_rate = 0.25"));
    const CliResult other =
        run_pedesis("run other.toml --out other --restart half/checkpoint.bin", dir, 60);
    EXPECT_EQ(other.exit_code, 2) << other.output;
    EXPECT_NE(other.output.find("does not match the checkpoint's"), std::string::npos)
        << other.output;
}

TEST_F(SteppedShear, AFlowTooFastForTheStepIsRefused) {
    // 100 x 1 x 0.01 = 1 a step between touching disks, 2 radii: more than max_move = 0.5
    expect_rejected(sheared_disks(100.0, 1.0), {"[box] shear_rate = 100", "[stepped] dt = 0.01"});
}

} // namespace
} // namespace pedesis::test
