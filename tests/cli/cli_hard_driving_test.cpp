// [event] gravity, thermostat = "andersen" and driving = "white_noise" through `pedesis
// run`: the log's columns (potential_energy and total_energy with gravity, injected_energy
// with the driving), the summary's records, a restart that continues bit for bit, and
// bad configs refused with one message and exit 2.
#include "cli/cli_support.hpp"

#include <nlohmann/json.hpp>

#include <cmath>
#include <regex>
#include <sstream>

namespace pedesis::test {
namespace {

std::string falling_disks(const std::string& event, double time) {
    std::ostringstream c;
    c << "dimension = 2\ndynamics = \"event\"\nseed = 3\n[box]\nlengths = [40.0, 40.0]\n"
         "boundary = [\"periodic\", \"wall\"]\n[[species]]\nname = \"A\"\ncount = 200\nradius = "
         "0.5\n[initial]\npositions = \"random\"\nvelocities = \"maxwell_boltzmann\"\n"
         "temperature = 1.0\n[event]\n"
      << event << "\n[run]\ntime = " << time
      << "\n[output]\nlog_interval = 1.0\nformats = [\"json\"]\nsnapshot_interval = 2.0\n"
         "checkpoint_interval = 2.0\nprogress = false\n";
    return c.str();
}

const std::string gravity = "gravity = [0.0, -0.5]";
const std::string andersen = "thermostat = \"andersen\"\nthermostat_rate = 0.5\ntemperature = 2.0";
const std::string driving = "restitution = 0.9\ndriving = \"white_noise\"\ndriving_rate = 1.0\n"
                            "driving_strength = 0.05";

class HardDriving : public ScratchDir {
  protected:
    nlohmann::json summary(const std::string& run) {
        return nlohmann::json::parse(read(run + "/summary.json"));
    }
};

TEST_F(HardDriving, GravityLogsItsEnergiesAndKeepsTheTotal) {
    write("run.toml", falling_disks(gravity, 20.0));
    const CliResult r = run_pedesis("run run.toml --out out", dir, 60);
    ASSERT_EQ(r.exit_code, 0) << r.output;
    EXPECT_NE(r.output.find("gravity 0, -0.5"), std::string::npos) << r.output;
    const CsvColumns log = csv_columns(read("out/log.csv"));
    const auto u = log.numbers("potential_energy"), e = log.numbers("total_energy"),
               k = log.numbers("kinetic_energy");
    ASSERT_EQ(u.size(), 21u);
    for (std::size_t i = 0; i < u.size(); ++i) {
        // elastic: conserved (to the log's 10 digits)
        EXPECT_NEAR(e[i], e[0], 1e-9 * e[0]) << "row " << i;
        EXPECT_NEAR(u[i] + k[i], e[i], 1e-9 * e[0]);
    }
    // the gas falls: potential energy turns kinetic
    EXPECT_LT(u.back(), u.front());
    const nlohmann::json j = summary("out");
    EXPECT_NEAR(j.at("gravity").at("total_energy").get<double>(), e.back(), 1e-9 * e[0]);
}

TEST_F(HardDriving, SteppedGravityLogsItsEnergies) {
    std::string config = std::regex_replace(
        falling_disks(gravity, 10.0), std::regex("dynamics = \"event\""), "dynamics = \"stepped\"");
    config = std::regex_replace(config, std::regex("\\[event\\]"), "[stepped]\ndt = 0.01");
    write("run.toml", config);
    const CliResult r = run_pedesis("run run.toml --out good", dir, 60);
    ASSERT_EQ(r.exit_code, 0) << r.output;
    const CsvColumns log = csv_columns(read("good/log.csv"));
    const auto u = log.numbers("potential_energy"), e = log.numbers("total_energy");
    ASSERT_EQ(u.size(), 11u);
    for (std::size_t i = 0; i < u.size(); ++i) EXPECT_NEAR(e[i], e[0], 1e-9 * e[0]) << i;
    EXPECT_LT(u.back(), u.front());
    EXPECT_TRUE(nlohmann::json::parse(read("good/summary.json")).contains("gravity"));
    expect_rejected(
        std::regex_replace(config, std::regex("gravity = \\[0.0, -0.5\\]"), "gravity = [0.5, 0.0]"),
        {"stepped.gravity", "periodic"});
}

TEST_F(HardDriving, RestartsContinueBitForBit) {
    for (const std::string& event : {gravity, andersen, driving, gravity + "\n" + andersen}) {
        SCOPED_TRACE(event);
        std::filesystem::remove_all(dir / "full");
        std::filesystem::remove_all(dir / "half");
        std::filesystem::remove_all(dir / "cont");
        write("full.toml", falling_disks(event, 8.0));
        write("half.toml", falling_disks(event, 4.0));
        ASSERT_EQ(run_pedesis("run full.toml --out full", dir, 60).exit_code, 0);
        ASSERT_EQ(run_pedesis("run half.toml --out half", dir, 60).exit_code, 0);
        const CliResult cont =
            run_pedesis("run full.toml --out cont --restart half/checkpoint.bin", dir, 60);
        ASSERT_EQ(cont.exit_code, 0) << cont.output;
        const std::string a = read("full/snapshots/frame_000004.json");
        ASSERT_FALSE(a.empty());
        EXPECT_TRUE(a == read("cont/snapshots/frame_000004.json")) << "the frames at t = 8 differ";
        for (const char* record : {"gravity", "andersen", "driving"})
            EXPECT_EQ(summary("full").value(record, nlohmann::json{}),
                      summary("cont").value(record, nlohmann::json{}))
                << record;
    }
}

TEST_F(HardDriving, TheThermostatAndTheDrivingAreRecorded) {
    write("a.toml",
          std::regex_replace(falling_disks(andersen, 10.0),
                             std::regex("boundary = \\[\"periodic\", \"wall\"\\]\n"), ""));
    const CliResult a = run_pedesis("run a.toml --out a", dir, 60);
    ASSERT_EQ(a.exit_code, 0) << a.output;
    const nlohmann::json ja = summary("a");
    // ~ N rate t = 1000 redraws
    EXPECT_NEAR(ja.at("andersen").at("events").get<double>(), 1000.0, 150.0);
    write("d.toml",
          std::regex_replace(falling_disks(driving, 10.0),
                             std::regex("boundary = \\[\"periodic\", \"wall\"\\]\n"), ""));
    const CliResult d = run_pedesis("run d.toml --out d", dir, 60);
    ASSERT_EQ(d.exit_code, 0) << d.output;
    const CsvColumns log = csv_columns(read("d/log.csv"));
    const auto injected = log.numbers("injected_energy");
    ASSERT_EQ(injected.size(), 11u);
    EXPECT_EQ(injected.front(), 0.0);
    // (D/2) m s nu N t = 0.05 * 200 * 10 = 100; each of the ~1000 pair kicks scatters by
    // sqrt(2 s T D) ~ 0.45 (the cross term dp.(v_i - v_j)), the sum by ~14
    EXPECT_NEAR(injected.back(), 100.0, 40.0);
    EXPECT_NEAR(injected.back(), summary("d").at("driving").at("injected_energy").get<double>(),
                1e-9 * injected.back());
}

TEST_F(HardDriving, BadConfigsAreRefusedWithOneMessage) {
    const std::string good = falling_disks(gravity, 2.0);
    auto with = [&](const std::string& from, const std::string& to) {
        return std::regex_replace(good, std::regex(from), to);
    };
    expect_rejected(with("gravity = \\[0.0, -0.5\\]", "gravity = [-0.5, 0.0]"),
                    {"event.gravity", "periodic", "fall for ever"});
    expect_rejected(with("gravity = \\[0.0, -0.5\\]", "gravity = [0.0, -0.5, 1.0]"),
                    {"event.gravity", "list of 2 numbers"});
    expect_rejected(with("gravity = \\[0.0, -0.5\\]", "gravity = [0.0, \"down\"]"),
                    {"event.gravity", "numbers"});
    expect_rejected(with("\\[run\\]\ntime = 2", "[run]\ntime = 2\nenergy_fraction = 0.5"),
                    {"energy_fraction", "gravity"});
    expect_rejected(with("gravity = \\[0.0, -0.5\\]", "thermostat = \"andersen\"\ntemperature = 1"),
                    {"event.thermostat", "thermostat_rate"});
    expect_rejected(with("gravity = \\[0.0, -0.5\\]",
                         "thermostat = \"andersen\"\nthermostat_rate = -1\ntemperature = 1"),
                    {"event.thermostat_rate", "positive"});
    expect_rejected(with("gravity = \\[0.0, -0.5\\]",
                         "thermostat = \"andersen\"\nthermostat_rate = 1\nthermostat_interval = 1"
                         "\ntemperature = 1"),
                    {"event.thermostat_interval", "rescale"});
    expect_rejected(with("gravity = \\[0.0, -0.5\\]", "thermostat_rate = 1"),
                    {"event.thermostat_rate", "needs event.thermostat = \"andersen\""});
    expect_rejected(with("gravity = \\[0.0, -0.5\\]", "driving = \"shaking\""),
                    {"event.driving", "unknown driving 'shaking'"});
    expect_rejected(
        with("gravity = \\[0.0, -0.5\\]", "driving = \"white_noise\"\ndriving_rate = 1"),
        {"event.driving", "driving_strength"});
    expect_rejected(with("gravity = \\[0.0, -0.5\\]", "driving_strength = 1"),
                    {"event.driving_strength", "needs event.driving"});
    expect_rejected(with("gravity = \\[0.0, -0.5\\]", "thermostat = \"andersen\"\nthermostat_rate "
                                                      "= 1\ntemperature = 1\ngrowth_rate = 0.1"),
                    {"event.thermostat", "growth"});
    // (with gravity, [transport] meets the walls' refusal first)
    expect_rejected(std::regex_replace(falling_disks(andersen, 400.0),
                                       std::regex("boundary = \\[\"periodic\", \"wall\"\\]\n"),
                                       "") +
                        "[transport]\ninterval = 0.1\ndiffusion_interval = 0.1\n",
                    {"transport", "andersen"});
}

} // namespace
} // namespace pedesis::test
