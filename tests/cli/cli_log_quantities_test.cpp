// The log's quantities by name: `[log] quantities` chooses the columns of log.csv for any
// engine, `pedesis run --list-quantities` prints the catalogue, every quantity of the
// catalogue is documented in docs/formats.md, and bad names are refused before any
// file is written.
#include "cli_support.hpp"

#include "pedesis/observe/quantities.hpp"

#include <nlohmann/json.hpp>

#include <cmath>
#include <fstream>

using namespace pedesis::test;

namespace {

class LogQuantities : public ScratchDir {};

const std::string soft_nve = R"(dimension = 2
dynamics = "nve"
seed = 2
[box]
length = 12.0
[[species]]
name = "A"
count = 40
radius = 0.5
[initial]
positions = "square"
velocities = "maxwell_boltzmann"
temperature = 0.5
[[force]]
name = "wca"
epsilon = 1.0
[[integrator]]
name = "nve"
[run]
steps = 200
dt = 0.002
[output]
log_every = 50
formats = []
progress = false
)";

} // namespace

TEST_F(LogQuantities, EveryQuantityIsListedAndDocumented) {
    const CliResult r = run_pedesis("run --list-quantities", dir);
    ASSERT_EQ(r.exit_code, 0) << r.output;
    std::ifstream in(std::string(PEDESIS_SOURCE_DIR) + "/docs/formats.md");
    const std::string docs(std::istreambuf_iterator<char>(in), {});
    ASSERT_GT(pedesis::quantity_catalogue().size(), 20u);
    for (const pedesis::QuantityInfo& q : pedesis::quantity_catalogue()) {
        const std::string name = q.name;
        EXPECT_NE(r.output.find(name + " "), std::string::npos) << name << "\n" << r.output;
        EXPECT_NE(r.output.find(q.meaning), std::string::npos) << name;
        // per-species columns are documented by an example species name
        const std::string documented = name.substr(0, name.find("<species>"));
        EXPECT_NE(docs.find("`" + documented), std::string::npos)
            << "docs/formats.md does not document " << name;
    }
}

TEST_F(LogQuantities, ChosenColumnsComeInTheGivenOrderWithTheSameValues) {
    const std::string base = small_config("", "length = 20.0", "time = 2.0");
    write("all.toml", base);
    write("some.toml", base + "[log]\nquantities = [\"temperature\", \"time\", \"collisions\"]\n");
    ASSERT_EQ(run_pedesis("run all.toml --out all", dir).exit_code, 0);
    const CliResult r = run_pedesis("run some.toml --out some", dir);
    ASSERT_EQ(r.exit_code, 0) << r.output;
    const CsvColumns all = csv_columns(read("all/log.csv"));
    const CsvColumns some = csv_columns(read("some/log.csv"));
    EXPECT_EQ(some.names, (std::vector<std::string>{"temperature", "time", "collisions"}));
    EXPECT_GT(all.names.size(), 10u);
    for (const auto& name : some.names) EXPECT_EQ(some.cells.at(name), all.cells.at(name)) << name;
    EXPECT_EQ(some.cells.at("time").size(), 5u); // t = 0, 0.5, ..., 2
}

TEST_F(LogQuantities, TotalEnergyIsPotentialPlusKinetic) {
    write("nve.toml", soft_nve);
    const CliResult r = run_pedesis("run nve.toml --out out", dir);
    ASSERT_EQ(r.exit_code, 0) << r.output;
    const CsvColumns c = csv_columns(read("out/log.csv"));
    const auto u_col = c.numbers("potential_energy"), k_col = c.numbers("kinetic_energy");
    const auto e_col = c.numbers("total_energy");
    ASSERT_EQ(e_col.size(), 5u);
    for (std::size_t k = 0; k < 5; ++k) {
        const double u = u_col[k], kin = k_col[k], e = e_col[k];
        EXPECT_NEAR(e, u + kin, 1e-9 * (std::abs(u) + kin)); // 10 digits each
    }
}

TEST_F(LogQuantities, UnknownOrUnmeasuredNamesAreRefusedBeforeAnyOutput) {
    const std::string base = small_config();
    expect_rejected(base + "[log]\nquantities = [\"time\", \"temprature\"]\n",
                    {"bad.toml", "quantities", "unknown quantity 'temprature'", "temperature"});
    expect_rejected(base + "[log]\nquantities = [\"time\", \"polar_order\"]\n",
                    {"bad.toml", "'polar_order' is not measured by this run", "collisions"});
    expect_rejected(base + "[log]\nquantities = [\"time\", \"time\"]\n", {"listed twice"});
    expect_rejected(base + "[log]\nquantities = []\n", {"non-empty list"});
    expect_rejected(base + "[log]\nquantities = [\"time\"]\nevery = 3\n", {"every"});
}

// summary.json's "final" holds every quantity the engine measures, by the same names, with
// the values of the last row of the default log (the same instant), whatever
// [log] quantities showed; so a script reads the end of any run without knowing the engine.
TEST_F(LogQuantities, SummaryFinalIsTheLastRowOfEveryMeasuredQuantity) {
    const std::string chosen = "[log]\nquantities = [\"time\"]\n";
    const std::map<std::string, std::string> configs = {
        {"event", small_config("", "length = 20.0", "time = 2.0")},
        {"stepped", "dimension = 2\ndynamics = \"stepped\"\nseed = 2\n[box]\nlength = 20.0\n"
                    "[[species]]\nname = \"A\"\ncount = 40\nradius = 0.5\n[stepped]\n"
                    "dt = 0.01\n[run]\ntime = 1.0\n[output]\nlog_interval = 0.5\n"
                    "progress = false\n"},
        {"nve", soft_nve}};
    for (const auto& [name, config] : configs) {
        write(name + ".toml", config);
        write(name + "_time.toml", config + chosen);
        ASSERT_EQ(run_pedesis("run " + name + ".toml --out " + name, dir).exit_code, 0) << name;
        ASSERT_EQ(run_pedesis("run " + name + "_time.toml --out " + name + "_time", dir).exit_code,
                  0)
            << name;
        const CsvColumns log = csv_columns(read(name + "/log.csv"));
        for (const std::string& run : {name, name + "_time"}) {
            const auto final_row = nlohmann::json::parse(read(run + "/summary.json")).at("final");
            EXPECT_EQ(final_row.size(), log.names.size()) << run << ": " << final_row.dump();
            for (const auto& column : log.names) {
                ASSERT_TRUE(final_row.contains(column)) << run << " lacks " << column;
                const std::string last = log.cells.at(column).back();
                if (final_row[column].is_null()) {
                    EXPECT_EQ(last, "inf") << run << ": " << column;
                    continue;
                }
                const double v = final_row[column].get<double>(), shown = std::stod(last);
                EXPECT_NEAR(v, shown, 1e-9 * std::abs(shown)) << run << ": " << column;
            }
        }
    }
}
