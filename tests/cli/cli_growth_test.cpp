// Lubachevsky-Stillinger growth from the command line: `[event] growth_rate` with a target
// packing fraction and `[run] grown = true`, the log's growth columns and the summary's
// growth record; impossible growth settings exit 2 naming the key.
#include "cli_support.hpp"

#include "pedesis/io/gsd_reader.hpp"

#include <nlohmann/json.hpp>

#include <cmath>
#include <numbers>
#include <sstream>

using namespace pedesis::test;

namespace {

class CliGrowth : public ScratchDir {
  protected:
    std::string config(const std::string& event, const std::string& run = "grown = true") {
        return small_config("", "length = 20.0", run) + "[event]\n" + event + "\n";
    }
};

} // namespace

// 50 disks of radius 0.5 in a 20 x 20 walled box (packing fraction 0.098) grown to 0.5:
// the radius must end at 0.5 sqrt(0.5 / 0.098175) = 1.1284.
TEST_F(CliGrowth, GrowsToTheTargetAndStops) {
    write("grow.toml", config("growth_rate = 0.2\ngrowth_packing_fraction = 0.5"));
    const CliResult r = run_pedesis("run grow.toml --out out", dir);
    ASSERT_EQ(r.exit_code, 0) << r.output;
    EXPECT_NE(r.output.find("growth ended"), std::string::npos) << r.output;
    const auto summary = nlohmann::json::parse(read("out/summary.json"));
    EXPECT_EQ(summary["stopped_by"], "grown");
    EXPECT_EQ(summary["growth"]["ended_by"], "packing_fraction");
    EXPECT_NEAR(summary["packing_fraction"].get<double>(), 0.5, 1e-9);
    EXPECT_NEAR(summary["energy_fraction"].get<double>(), 1.0, 1e-9); // the thermostat's hold

    std::istringstream log(read("out/log.csv"));
    std::string header, line, last;
    std::getline(log, header);
    EXPECT_NE(header.find(",packing_fraction,growth_pressure"), std::string::npos) << header;
    while (std::getline(log, line)) last = line;
    const auto comma = last.rfind(',');
    const auto before = last.rfind(',', comma - 1);
    EXPECT_NEAR(std::stod(last.substr(before + 1, comma - before - 1)), 0.5, 1e-8) << last;

    // the last frame of the trajectory (GSD, the default) carries the grown radius
    const pedesis::GsdReader gsd(dir / "out" / "trajectory.gsd");
    ASSERT_GE(gsd.frames(), 2u);
    const pedesis::GsdFrame last_frame = gsd.frame(gsd.frames() - 1);
    ASSERT_EQ(last_frame.diameter.size(), 50u);
    // 50 disks of radius r fill half of 20 x 20 when r = sqrt(4 / pi); float32 in the file
    EXPECT_NEAR(last_frame.diameter[0], 2.0 * std::sqrt(4.0 / std::numbers::pi), 1e-6);
}

TEST_F(CliGrowth, ImpossibleSettingsExit2NamingTheKey) {
    expect_rejected(config("growth_rate = -1.0"), {"bad.toml", "growth_rate"});
    expect_rejected(config("growth_packing_fraction = 0.5"),
                    {"bad.toml", "growth_packing_fraction", "growth_rate > 0"});
    expect_rejected(config("growth_rate = 0.1\ngrowth_packing_fraction = 1.2"),
                    {"bad.toml", "growth_packing_fraction", "(0, 1)"});
    expect_rejected(config("growth_rate = 0.1\ngrowth_max_pressure = 0.5"),
                    {"bad.toml", "growth_max_pressure"});
    expect_rejected(config("restitution = 1.0"), {"bad.toml", "run.grown", "growth_rate > 0"});
    expect_rejected(config("growth_rate = 0.1\ngrowth_packing_fraction = 0.05"),
                    {"growth_packing_fraction", "starting packing fraction"});
}
