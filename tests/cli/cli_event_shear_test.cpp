// Lees-Edwards shear of hard particles through `pedesis run` ([box] shear_rate with the
// event engine, [event] thermostat = "rescale"):
// - a sheared hard-sphere fluid flows linearly (the profile's slope is the rate), its
//   P_xy is negative, and the thermostat removes exactly the viscous heating
//   -rate <P_xy> V t (less the change of the kinetic energy): the log's P_xy integrates
//   the kinetic stress exactly, so the balance holds to rounding;
// - a restart continues bit for bit, with the shear record (profile, P_xy series);
// - bad shear and thermostat configs are refused with one message.
#include "cli/cli_support.hpp"

#include <nlohmann/json.hpp>

#include <cmath>
#include <fstream>
#include <regex>
#include <sstream>

namespace pedesis::test {
namespace {

std::string sheared_spheres(double rate, double time, const std::string& extra = "") {
    std::ostringstream c;
    c << "dimension = 3\ndynamics = \"event\"\nseed = 5\n[box]\nlength = 8.0\nshear_rate = " << rate
      << "\n[[species]]\nname = \"A\"\ncount = 256\nradius = 0.5\n[initial]\npositions = "
         "\"fcc\"\nvelocities = \"maxwell_boltzmann\"\ntemperature = 1.0\n[event]\nthermostat = "
         "\"rescale\"\ntemperature = 1.0\nthermostat_interval = 0.5\n[run]\ntime = "
      << time << "\n[output]\nlog_interval = 0.5\nformats = []\nprogress = false\n"
      << extra;
    return c.str();
}

class EventShear : public ScratchDir {
  protected:
    nlohmann::json summary(const std::string& run) {
        return nlohmann::json::parse(read(run + "/summary.json"));
    }
};

TEST_F(EventShear, AShearedFluidFlowsLinearlyAndTheThermostatTakesTheViscousHeating) {
    const double rate = 0.5, time = 40.0, V = 512.0;
    write("run.toml", sheared_spheres(rate, time));
    const CliResult r = run_pedesis("run run.toml --out out", dir, 120);
    ASSERT_EQ(r.exit_code, 0) << r.output;
    EXPECT_NE(r.output.find("shear viscosity -<P_xy>/rate"), std::string::npos) << r.output;
    const nlohmann::json j = summary("out");
    const double stress = j.at("shear").at("shear_stress").at("value").get<double>();
    EXPECT_LT(stress, 0.0);
    const double eta = j.at("shear").at("viscosity").at("value").get<double>();
    EXPECT_GT(eta, 0.0);
    // the heating over the run against what the thermostat took out; the peculiar kinetic
    // energy at the end is 3/2 (N - 1) T_end, within one interval's heating of the start
    const double removed = j.at("thermostat").at("energy_removed").get<double>();
    const double heating = -rate * stress * V * time;
    const double dK = 1.5 * 255 * (j.at("temperature").get<double>() - 1.0);
    EXPECT_NEAR(removed + dK, heating, 1e-6 * heating) << removed << " + " << dK;
    EXPECT_EQ(j.at("thermostat").at("rescales").get<int>(), 80);
    // the laboratory velocity profile: a straight line of slope `rate`
    const CsvColumns profile = csv_columns(read("out/velocity_profile.csv"));
    const auto y = profile.numbers("y"), v = profile.numbers("velocity_x");
    ASSERT_EQ(y.size(), 8u);
    double sy = 0, sv = 0, syy = 0, syv = 0;
    for (std::size_t k = 0; k < y.size(); ++k) {
        sy += y[k];
        sv += v[k];
        syy += y[k] * y[k];
        syv += y[k] * v[k];
    }
    const double n = static_cast<double>(y.size());
    const double slope = (n * syv - sy * sv) / (n * syy - sy * sy);
    EXPECT_NEAR(slope, rate, 0.1 * rate);
    for (std::size_t k = 0; k < y.size(); ++k) EXPECT_NEAR(v[k], rate * y[k], 0.15) << y[k];
    // the log has P_xy and the co-moving temperature
    const CsvColumns log = csv_columns(read("out/log.csv"));
    EXPECT_EQ(log.numbers("pressure_xy").size(), 81u);
    EXPECT_NEAR(log.numbers("temperature").back(), 1.0, 1e-9); // the last row is a rescaling
}

TEST_F(EventShear, ARestartContinuesBitForBit) {
    const std::string out = "snapshot_interval = 4.0\ncheckpoint_interval = 4.0\n";
    std::string full = sheared_spheres(1.0, 8.0, "");
    full = std::regex_replace(full, std::regex("formats = \\[\\]"), "formats = [\"json\"]\n" + out);
    write("full.toml", full);
    write("half.toml", std::regex_replace(full, std::regex("time = 8\n"), "time = 4\n"));
    ASSERT_EQ(run_pedesis("run full.toml --out full", dir, 60).exit_code, 0);
    const CliResult half = run_pedesis("run half.toml --out half", dir, 60);
    ASSERT_EQ(half.exit_code, 0) << half.output;
    const CliResult cont =
        run_pedesis("run full.toml --out cont --restart half/checkpoint.bin", dir, 60);
    ASSERT_EQ(cont.exit_code, 0) << cont.output;
    const std::string a = read("full/snapshots/frame_000002.json");
    ASSERT_FALSE(a.empty());
    EXPECT_TRUE(a == read("cont/snapshots/frame_000002.json")) << "the frames at t = 8 differ";
    EXPECT_EQ(read("full/velocity_profile.csv"), read("cont/velocity_profile.csv"));
    EXPECT_EQ(summary("full").at("shear"), summary("cont").at("shear"));
    EXPECT_EQ(summary("full").at("thermostat"), summary("cont").at("thermostat"));
    write("other.toml", std::regex_replace(full, std::regex("shear_rate = 1"), "shear_rate = 0.5"));
    const CliResult other =
        run_pedesis("run other.toml --out other --restart half/checkpoint.bin", dir, 60);
    EXPECT_EQ(other.exit_code, 2) << other.output;
    EXPECT_NE(other.output.find("does not match the checkpoint's"), std::string::npos)
        << other.output;
}

TEST_F(EventShear, BadShearAndThermostatConfigsAreRefusedWithOneMessage) {
    const std::string good = sheared_spheres(0.5, 2.0);
    auto with = [&](const std::string& from, const std::string& to) {
        return std::regex_replace(good, std::regex(from), to);
    };
    expect_rejected(with("thermostat = \"rescale\"", "thermostat = \"berendsen\""),
                    {"event.thermostat", "unknown thermostat 'berendsen'"});
    expect_rejected(with("thermostat = \"rescale\"\n", ""),
                    {"event.temperature", "needs event.thermostat = \"rescale\""});
    expect_rejected(with("temperature = 1.0\nthermostat_interval", "thermostat_interval"),
                    {"event.thermostat", "needs event.temperature"});
    expect_rejected(with("thermostat_interval = 0.5", "thermostat_interval = 0"),
                    {"event.thermostat_interval", "positive"});
    expect_rejected(with("temperature = 1.0\nthermostat_interval", "temperature = -1\nthermostat_"
                                                                   "interval"),
                    {"event.temperature", "positive"});
    expect_rejected(with("\\[run\\]\ntime = 2", "[run]\ntime = 2\nenergy_fraction = 0.5"),
                    {"energy_fraction", "viscous heating"});
    expect_rejected(with("thermostat = \"rescale\"\ntemperature = 1.0\nthermostat_interval = 0.5",
                         "growth_rate = 0.01"),
                    {"shear_rate", "growth"});
    expect_rejected(good + "[transport]\n", {"transport", "not under shear"});
}

} // namespace
} // namespace pedesis::test
