// [event.moving_wall] through `pedesis run`: the log's wall_work and wall_position columns
// (the position is the face's, A (1 - cos 2 pi f t) in from it), the summary's record, the
// balance of an elastic run (total energy gained = the wall's work), and bad configs
// refused with one message and exit 2.
#include "cli/cli_support.hpp"

#include <nlohmann/json.hpp>

#include <cmath>
#include <numbers>
#include <sstream>

namespace pedesis::test {
namespace {

std::string shaken_bed(const std::string& wall, const std::string& boundary = "\"wall\"") {
    std::ostringstream c;
    c << "dimension = 2\ndynamics = \"event\"\nseed = 3\n[box]\nlengths = [20.0, 40.0]\n"
         "boundary = [\"periodic\", "
      << boundary
      << "]\n[[species]]\nname = \"A\"\ncount = 60\nradius = 0.5\n[initial]\npositions = "
         "\"random\"\nvelocities = \"maxwell_boltzmann\"\ntemperature = 1.0\n[event]\n"
         "gravity = [0.0, -1.0]\n[event.moving_wall]\n"
      << wall
      << "\n[run]\ntime = 10.0\n[output]\nlog_interval = 0.25\nformats = []\nprogress = "
         "false\n";
    return c.str();
}

class MovingWall : public ScratchDir {};

TEST_F(MovingWall, LogsTheWallsWorkAndPosition) {
    write("run.toml", shaken_bed("axis = \"y\"\namplitude = 0.3\nfrequency = 0.8"));
    const CliResult r = run_pedesis("run run.toml --out out", dir, 60);
    ASSERT_EQ(r.exit_code, 0) << r.output;
    EXPECT_NE(r.output.find("moving wall: the lower wall of y vibrates, amplitude 0.3, "
                            "frequency 0.8"),
              std::string::npos)
        << r.output;
    const CsvColumns log = csv_columns(read("out/log.csv"));
    const auto t = log.numbers("time"), w = log.numbers("wall_work"),
               y = log.numbers("wall_position"), e = log.numbers("total_energy");
    ASSERT_EQ(t.size(), 41u);
    for (std::size_t i = 0; i < t.size(); ++i) {
        const double face = -20.0 + 0.3 * (1.0 - std::cos(2.0 * std::numbers::pi * 0.8 * t[i]));
        EXPECT_NEAR(y[i], face, 1e-7) << "row " << i; // (the log has 10 digits)
        // elastic: what the gas gained is what the wall did (to the log's 10 digits)
        EXPECT_NEAR(e[i] - e[0], w[i], 1e-8 * e[0]) << "row " << i;
    }
    EXPECT_GT(w.back(), 1.0);
    const auto j = nlohmann::json::parse(read("out/summary.json"));
    const auto& m = j.at("moving_wall");
    EXPECT_EQ(m.at("axis"), "y");
    EXPECT_EQ(m.at("side"), "lower");
    EXPECT_NEAR(m.at("work").get<double>(), w.back(), 1e-8 * std::abs(w.back()));
}

TEST_F(MovingWall, RefusesBadTablesWithOneMessage) {
    const std::pair<std::string, std::string> cases[] = {
        {"amplitude = 0.3\nfrequency = 1.0", "needs axis"},
        {"axis = \"q\"\namplitude = 0.3\nfrequency = 1.0", "must be one of"},
        {"axis = \"x\"\namplitude = 0.3\nfrequency = 1.0", "is periodic"},
        {"axis = \"y\"\nside = \"top\"\namplitude = 0.3\nfrequency = 1.0", "\"lower\" or"},
        {"axis = \"y\"\namplitude = 0.3", "frequency"},
        {"axis = \"y\"\namplitude = -0.3\nfrequency = 1.0", "must be positive"},
        {"axis = \"y\"\nspeed = 0.1\namplitude = 0.3\nfrequency = 1.0", "not both"},
        {"axis = \"y\"", "not both nor neither"},
        {"axis = \"y\"\nspeed = -1.0", "moves into the box"},
        {"axis = \"y\"\nspeed = 1.0\nphase = 2.0", "phase"},
    };
    for (const auto& [table, message] : cases) {
        write("bad.toml", shaken_bed(table));
        const CliResult r = run_pedesis("run bad.toml --out bad", dir, 30);
        EXPECT_EQ(r.exit_code, 2) << table << "\n" << r.output;
        EXPECT_NE(r.output.find(message), std::string::npos) << table << "\n" << r.output;
    }
}

} // namespace
} // namespace pedesis::test
