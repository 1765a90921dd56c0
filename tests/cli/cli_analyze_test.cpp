// `pedesis analyze` end to end: the real binary runs small event and soft simulations,
// then draws each plot; the PNGs are checked by their header, and the Kolmogorov-Smirnov
// distances `analyze speed` prints are recomputed here from the same snapshot with
// pedesis::theory, independently of the Python that printed them. Bad input exits with 2
// and a single line naming the file.
#include "cli_support.hpp"

#include "pedesis/observe/theory.hpp"

#include <nlohmann/json.hpp>

#include <cstdint>
#include <cstdlib>
#include <map>
#include <optional>
#include <regex>

using namespace pedesis::test;
namespace fs = std::filesystem;

namespace {

// Two species of different mass in a walled box, started at equal speeds: after 20
// collisions per particle each species is near its own Rayleigh distribution.
std::string event_config(int dim) {
    const std::string L = dim == 2 ? "30.0" : "12.0";
    return "dimension = " + std::to_string(dim) + "\nseed = 3\n[box]\nlength = " + L +
           "\nboundary = \"wall\"\n"
           "[[species]]\nname = \"A\"\ncount = 200\nradius = 0.5\n"
           "[[species]]\nname = \"B\"\ncount = 100\nradius = 0.7\nmass = 3.0\n"
           "[initial]\nvelocities = \"equal_speed\"\n"
           "[run]\ntime = 20.0\n"
           "[output]\nlog_interval = 0.5\nsnapshot_interval = 5.0\nformats = [\"json\"]\n"
           "progress = false\n";
}

// A short version of the ABP tutorial: repulsion, propulsion, alignment, both noises.
std::string soft_config(const std::string& formats = "[\"json\"]") {
    return "dimension = 2\ndynamics = \"brownian\"\nseed = 4\n[box]\nlength = 30.0\n"
           "[[species]]\nname = \"A\"\ncount = 150\nradius = 1.0\n"
           "[[force]]\nname = \"harmonic\"\nk = 10.0\n"
           "[[force]]\nname = \"self_propulsion\"\nalpha = 1.0\n"
           "[[torque]]\nname = \"polar_align\"\nJ = 1.0\na = 2.0\n"
           "[[integrator]]\nname = \"brownian\"\nT = 0.05\ngamma = 1.0\n"
           "[[integrator]]\nname = \"brownian_rotation\"\nT = 0.1\ngamma = 1.0\n"
           "[run]\nsteps = 1000\ndt = 0.01\n"
           "[output]\nlog_every = 10\nformats = " +
           formats + "\nprogress = false\n";
}

struct PngInfo {
    std::uint32_t width = 0, height = 0;
    std::uintmax_t bytes = 0;
};

std::uint32_t big_endian(const unsigned char* p) {
    return (std::uint32_t(p[0]) << 24) | (std::uint32_t(p[1]) << 16) | (std::uint32_t(p[2]) << 8) |
           std::uint32_t(p[3]);
}

// The 8-byte PNG signature, then the IHDR chunk first: length 13, "IHDR", width, height.
std::optional<PngInfo> read_png(const fs::path& file) {
    std::ifstream in(file, std::ios::binary);
    unsigned char h[24] = {};
    if (!in.read(reinterpret_cast<char*>(h), sizeof h)) return std::nullopt;
    const unsigned char signature[8] = {0x89, 'P', 'N', 'G', '\r', '\n', 0x1a, '\n'};
    if (!std::equal(signature, signature + 8, h)) return std::nullopt;
    if (big_endian(h + 8) != 13 || std::string(reinterpret_cast<char*>(h + 12), 4) != "IHDR")
        return std::nullopt;
    return PngInfo{big_endian(h + 16), big_endian(h + 20), fs::file_size(file)};
}

// A plot that is really there: a PNG of a readable size with something drawn on it.
void expect_plot(const fs::path& file, std::uint32_t min_width, std::uint32_t min_height) {
    const auto png = read_png(file);
    ASSERT_TRUE(png) << file << " is missing or not a PNG";
    EXPECT_GE(png->width, min_width) << file;
    EXPECT_GE(png->height, min_height) << file;
    EXPECT_GT(png->bytes, 20000u) << file << ": too small to hold a drawn plot";
}

struct KsLine {
    double distance;
    std::size_t n;
};

// `ks_distance NAME: D (N = n, ...)`, the line docs/analyze.md promises scripts can parse.
std::map<std::string, KsLine> parse_ks(const std::string& output) {
    std::map<std::string, KsLine> out;
    const std::regex line(R"(ks_distance (\S+): ([0-9.eE+-]+) \(N = (\d+))");
    for (std::sregex_iterator it(output.begin(), output.end(), line), end; it != end; ++it)
        out[(*it)[1]] = {std::stod((*it)[2]), std::stoul((*it)[3])};
    return out;
}

// The KS distance of each species of a snapshot against the equilibrium speed law at
// its measured temperature T = sum m v^2 / (d N), computed with pedesis::theory.
std::map<int, KsLine> ks_of_snapshot(const fs::path& file) {
    std::ifstream in(file);
    const auto snap = nlohmann::json::parse(in);
    std::map<int, std::vector<double>> speeds;
    std::map<int, double> mass;
    int dim = 0;
    for (const auto& p : snap["system"]["particles"]) {
        const int type = p.value("type", 0);
        if (p["mass"].is_string()) continue; // "inf": a fixed obstacle
        double v2 = 0.0;
        dim = static_cast<int>(p["v"].size());
        for (const auto& c : p["v"]) v2 += c.get<double>() * c.get<double>();
        speeds[type].push_back(std::sqrt(v2));
        mass[type] = p["mass"].get<double>();
    }
    std::map<int, KsLine> out;
    for (auto& [type, v] : speeds) {
        double sum_v2 = 0.0;
        for (double s : v) sum_v2 += s * s;
        const double m = mass[type];
        const double T = m * sum_v2 / (dim * static_cast<double>(v.size()));
        const double d = pedesis::theory::ks_distance(
            v, [&](double s) { return pedesis::theory::speed_cdf(dim, s, T, m); });
        out[type] = {d, v.size()};
    }
    return out;
}

// Only the one line of the project's error format, nothing else (no traceback).
void expect_one_error_line(const CliResult& r, const std::string& names) {
    EXPECT_EQ(r.exit_code, 2) << r.output;
    EXPECT_EQ(r.output.rfind("pedesis: error: ", 0), 0u) << r.output;
    EXPECT_EQ(std::count(r.output.begin(), r.output.end(), '\n'), 1) << r.output;
    EXPECT_NE(r.output.find(names), std::string::npos) << "should name " << names << ":\n"
                                                       << r.output;
}

// Sets an environment variable for one test; the child pedesis inherits it.
class ScopedEnv {
  public:
    ScopedEnv(const char* name, const std::string& value) : name_(name) {
        ::setenv(name, value.c_str(), 1);
    }
    ~ScopedEnv() { ::unsetenv(name_); }
    ScopedEnv(const ScopedEnv&) = delete;
    ScopedEnv& operator=(const ScopedEnv&) = delete;

  private:
    const char* name_;
};

class CliAnalyze : public ScratchDir {
  protected:
    void simulate(const std::string& name, const std::string& config) {
        write(name + ".toml", config);
        const CliResult r = run_pedesis("run " + name + ".toml --out " + name, dir);
        ASSERT_EQ(r.exit_code, 0) << r.output;
    }
};

void check_speed_against_theory(const CliResult& r, const fs::path& run_dir) {
    ASSERT_EQ(r.exit_code, 0) << r.output;
    // the final frame: t = 20 with a frame every 5 is frame 4
    ASSERT_NE(r.output.find("velocities of snapshots/frame_000004.json"), std::string::npos)
        << r.output;
    const auto printed = parse_ks(r.output);
    const auto expected = ks_of_snapshot(run_dir / "snapshots" / "frame_000004.json");
    ASSERT_EQ(printed.size(), 2u) << r.output;
    const std::map<int, std::string> names{{0, "A"}, {1, "B"}};
    for (const auto& [type, ks] : expected) {
        const auto it = printed.find(names.at(type));
        ASSERT_NE(it, printed.end()) << "no ks_distance line for " << names.at(type);
        EXPECT_EQ(it->second.n, ks.n);
        EXPECT_NEAR(it->second.distance, ks.distance, 1e-6) << names.at(type);
        // 20 collisions per particle relax equal speeds to the equilibrium law; a KS
        // distance this far below 0.1 % significance says the curve is the right one
        EXPECT_LT(ks.distance, pedesis::theory::ks_critical(ks.n, 0.001)) << names.at(type);
    }
    expect_plot(run_dir / "speed_distribution.png", 1200, 500);
}

} // namespace

TEST_F(CliAnalyze, SpeedKsDistanceMatchesAnIndependentRayleighComputation) {
    simulate("ev", event_config(2));
    const CliResult r = run_pedesis("analyze speed ev", dir);
    check_speed_against_theory(r, dir / "ev");
    EXPECT_NE(r.output.find("wrote ev/speed_distribution.png"), std::string::npos) << r.output;
}

TEST_F(CliAnalyze, SpeedKsDistanceMatchesAnIndependentMaxwellComputationIn3D) {
    simulate("ev3", event_config(3));
    check_speed_against_theory(run_pedesis("analyze speed ev3", dir), dir / "ev3");
}

// A longer earlier run in the same directory leaves later-numbered frames behind
// (docs/formats.md); the final frame is the one at the log's last time.
TEST_F(CliAnalyze, SpeedIgnoresAStaleLaterFrame) {
    simulate("ev", event_config(2));
    auto stale = nlohmann::json::parse(read("ev/snapshots/frame_000004.json"));
    stale["system"]["time"] = 99.0;
    for (auto& p : stale["system"]["particles"]) p["v"] = {2.0, 0.0};
    write("ev/snapshots/frame_000009.json", stale.dump());
    check_speed_against_theory(run_pedesis("analyze speed ev", dir), dir / "ev");
}

TEST_F(CliAnalyze, ThermoOfAnEventRunHasARowAgainstCollisions) {
    simulate("ev", event_config(2));
    simulate("abp", soft_config());
    const CliResult event = run_pedesis("analyze thermo ev", dir);
    ASSERT_EQ(event.exit_code, 0) << event.output;
    const CliResult soft = run_pedesis("analyze thermo abp", dir);
    ASSERT_EQ(soft.exit_code, 0) << soft.output;
    expect_plot(dir / "ev" / "thermo.png", 1200, 800);
    expect_plot(dir / "abp" / "thermo.png", 900, 450);
    // against time and against collisions per particle: twice the panels' height
    const auto two_rows = read_png(dir / "ev" / "thermo.png");
    const auto one_row = read_png(dir / "abp" / "thermo.png");
    ASSERT_TRUE(two_rows && one_row);
    EXPECT_GT(two_rows->height, 3 * one_row->height / 2);
}

TEST_F(CliAnalyze, MsdAndOrderOfASoftRun) {
    simulate("abp", soft_config());
    for (const char* kind : {"msd", "order"}) {
        const CliResult r = run_pedesis(std::string("analyze ") + kind + " abp", dir);
        ASSERT_EQ(r.exit_code, 0) << r.output;
        expect_plot(dir / "abp" / (std::string(kind) + ".png"), 900, 600);
    }
}

TEST_F(CliAnalyze, OutPutsThePlotWhereAskedAndLeavesNoTemporary) {
    simulate("abp", soft_config());
    fs::create_directories(dir / "plots");
    const CliResult r = run_pedesis("analyze order abp --out plots/p.png", dir);
    ASSERT_EQ(r.exit_code, 0) << r.output;
    EXPECT_NE(r.output.find("wrote plots/p.png"), std::string::npos) << r.output;
    expect_plot(dir / "plots" / "p.png", 900, 600);
    EXPECT_FALSE(fs::exists(dir / "plots" / "p.tmp.png"));
    EXPECT_FALSE(fs::exists(dir / "abp" / "order.png"));
}

TEST_F(CliAnalyze, MissingRunDirectory) {
    expect_one_error_line(run_pedesis("analyze thermo nowhere", dir), "nowhere: no such run");
}

TEST_F(CliAnalyze, RunDirectoryWithoutLog) {
    simulate("ev", event_config(2));
    fs::remove(dir / "ev" / "log.csv");
    expect_one_error_line(run_pedesis("analyze thermo ev", dir), "ev/log.csv: missing");
}

TEST_F(CliAnalyze, CorruptLog) {
    simulate("ev", event_config(2));
    std::string log = read("ev/log.csv");
    log.insert(log.find('\n') + 1, "0,1,2,oops\n");
    write("ev/log.csv", log);
    expect_one_error_line(run_pedesis("analyze thermo ev", dir), "ev/log.csv: line 2");
}

TEST_F(CliAnalyze, MsdOfAnEventRun) {
    // the event engine counts box crossings (issue 51): its log has the msd column
    simulate("ev", event_config(2));
    const CliResult r = run_pedesis("analyze msd ev", dir);
    EXPECT_EQ(r.exit_code, 0) << r.output;
    EXPECT_TRUE(fs::exists(dir / "ev" / "msd.png")) << r.output;
    // a log written before it had none: the message says why and what to do
    std::string log = read("ev/log.csv");
    std::string header = log.substr(0, log.find('\n'));
    ASSERT_NE(header.find(",msd,"), std::string::npos) << header;
    header.replace(header.find(",msd,"), 5, ",dsm,");
    write("ev/log.csv", header + log.substr(log.find('\n')));
    const CliResult old = run_pedesis("analyze msd ev", dir);
    expect_one_error_line(old, "ev/log.csv: no column 'msd'");
    EXPECT_NE(old.output.find("made before event and stepped runs logged the MSD"),
              std::string::npos)
        << old.output;
}

TEST_F(CliAnalyze, SpeedOfARunWithoutFrames) {
    simulate("abp", soft_config("[]"));
    expect_one_error_line(run_pedesis("analyze speed abp", dir), "abp: no frames");
}

TEST_F(CliAnalyze, CorruptSnapshot) {
    simulate("ev", event_config(2));
    write("ev/snapshots/frame_000004.json", "{\"system\": {\"particles\": [{\"v\": [1");
    expect_one_error_line(run_pedesis("analyze speed ev", dir), "ev/snapshots/frame_000004.json");
}

TEST_F(CliAnalyze, MissingPythonIsNamed) {
    simulate("ev", event_config(2));
    const ScopedEnv env("PEDESIS_PYTHON", (dir / "no_python3").string());
    expect_one_error_line(run_pedesis("analyze thermo ev", dir), "no_python3");
}

TEST_F(CliAnalyze, AMissingPackageIsNamed) {
    simulate("ev", event_config(2));
    const ScopedEnv env("PEDESIS_PYTHONPATH", (dir / "no_package").string());
    expect_one_error_line(run_pedesis("analyze thermo ev", dir), "no_package");
}

// A module named matplotlib that cannot be imported stands in for a machine without
// python3-matplotlib.
TEST_F(CliAnalyze, MissingMatplotlibIsNamed) {
    simulate("ev", event_config(2));
    fs::create_directories(dir / "shadow" / "matplotlib");
    write("shadow/matplotlib/__init__.py", "raise ImportError('No module named matplotlib')\n");
    const ScopedEnv env("PYTHONPATH", (dir / "shadow").string());
    expect_one_error_line(run_pedesis("analyze thermo ev", dir), "python3-matplotlib");
    EXPECT_FALSE(fs::exists(dir / "ev" / "thermo.png"));
}

// A plot that fails for another reason than bad input is a bug, not exit 2 (a package
// whose pedesis.analyze raises stands in for one).
TEST_F(CliAnalyze, AScriptCrashIsAnInternalError) {
    simulate("ev", event_config(2));
    fs::create_directories(dir / "package" / "pedesis" / "analyze");
    write("package/pedesis/__init__.py", "");
    write("package/pedesis/analyze/__init__.py", "");
    write("package/pedesis/analyze/__main__.py", "raise RuntimeError('boom')\n");
    const ScopedEnv env("PEDESIS_PYTHONPATH", (dir / "package").string());
    const CliResult r = run_pedesis("analyze thermo ev", dir);
    EXPECT_EQ(r.exit_code, 1) << r.output;
    EXPECT_NE(r.output.find("internal error: analyze thermo"), std::string::npos) << r.output;
}
