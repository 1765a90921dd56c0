// The soft/active engine through the command line: the ABP tutorial's example, its
// outputs read back by real readers (Python's XML parser, nlohmann-json, python3-gsd),
// restart against a continuous run, per-species parameters, and blow-ups.
#include "cli/cli_support.hpp"

#include <nlohmann/json.hpp>

#include <cmath>
#include <fstream>
#include <regex>
#include <sstream>

namespace pedesis::test {
namespace {

namespace fs = std::filesystem;

#ifdef PEDESIS_PYTHON
const char* const python = PEDESIS_PYTHON;
#else
const char* const python = "/usr/bin/python3"; // Debian's, which has python3-gsd
#endif

std::string slurp(const fs::path& p) {
    std::ifstream in(p);
    return std::string(std::istreambuf_iterator<char>(in), {});
}

nlohmann::json read_json(const fs::path& p) {
    return nlohmann::json::parse(slurp(p));
}

// Runs a Python snippet with Debian's interpreter; its stdout and exit status.
CliResult run_python(const std::string& code, const fs::path& dir) {
    std::ofstream(dir / "check.py") << code;
    const std::string cmd = std::string(python) + " '" + (dir / "check.py").string() + "' 2>&1";
    CliResult r;
    FILE* pipe = popen(cmd.c_str(), "r");
    std::array<char, 4096> buf;
    while (pipe && fgets(buf.data(), buf.size(), pipe)) r.output += buf.data();
    const int status = pipe ? pclose(pipe) : -1;
    r.exit_code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
    return r;
}

const fs::path examples = fs::path(PEDESIS_SOURCE_DIR) / "examples";

// The tutorial's example with another [run] and [output]: the same physics, shorter.
std::string tutorial_config(const std::string& run, const std::string& output,
                            const std::string& extra = "") {
    std::string text = slurp(examples / "abp_tutorial.toml");
    text = text.substr(0, text.find("[run]"));
    text = std::regex_replace(text, std::regex("abp_tutorial_init.json"),
                              (examples / "abp_tutorial_init.json").string());
    return text + extra + "[run]\n" + run + "\n[output]\nprogress = false\n" + output + "\n";
}

class SoftRun : public ScratchDir {};

TEST_F(SoftRun, TutorialExampleRunsAndWritesParaViewFiles) {
    const auto r =
        run_pedesis("run '" + (examples / "abp_tutorial.toml").string() + "' --out out", dir);
    ASSERT_EQ(r.exit_code, 0) << r.output;
    // a snapshot every 10 of 1000 steps, the first included
    std::size_t vtp = 0;
    for (const auto& e : fs::directory_iterator(dir / "out" / "snapshots"))
        vtp += e.path().extension() == ".vtp";
    EXPECT_EQ(vtp, 101u);
    // a real XML parser reads the last one, with the arrays ParaView needs
    const auto py = run_python("import xml.etree.ElementTree as ET\n"
                               "root = ET.parse('" +
                                   (dir / "out/snapshots/frame_000100.vtp").string() +
                                   "').getroot()\n"
                                   "piece = root.find('PolyData/Piece')\n"
                                   "print('points', piece.get('NumberOfPoints'))\n"
                                   "for a in piece.find('PointData'):\n"
                                   "    vals = a.text.split()\n"
                                   "    ncomp = int(a.get('NumberOfComponents', '1'))\n"
                                   "    print(a.get('Name'), len(vals) // ncomp)\n",
                               dir);
    ASSERT_EQ(py.exit_code, 0) << py.output;
    EXPECT_NE(py.output.find("points 1000"), std::string::npos) << py.output;
    for (const char* name : {"id", "director", "velocity", "force", "radius"})
        EXPECT_NE(py.output.find(std::string(name) + " 1000"), std::string::npos) << name << "\n"
                                                                                  << py.output;
    const auto summary = read_json(dir / "out" / "summary.json");
    EXPECT_EQ(summary["steps"], 1000);
    EXPECT_DOUBLE_EQ(summary["time"].get<double>(), 10.0);
}

TEST_F(SoftRun, JsonAndGsdAgreeAndPythonGsdReadsTheTrajectory) {
    write("abp.toml", tutorial_config("steps = 40\ndt = 0.01",
                                      "snapshot_every = 20\nformats = [\"json\", \"gsd\", "
                                      "\"table\", \"xyz\"]"));
    const auto r = run_pedesis("run abp.toml --out out", dir);
    ASSERT_EQ(r.exit_code, 0) << r.output;
    const auto last = read_json(dir / "out/snapshots/frame_000002.json");
    const auto& particles = last["system"]["particles"];
    ASSERT_EQ(particles.size(), 1000u);
    for (std::size_t k = 0; k < particles.size(); ++k) {
        ASSERT_EQ(particles[k]["id"], k); // tag order
        const auto n = particles[k]["n"];
        EXPECT_NEAR(std::hypot(n[0].get<double>(), n[1].get<double>()), 1.0, 1e-12);
    }
    // python3-gsd: 3 frames, N, the 2D box, and positions equal to the JSON's to float32
    std::ostringstream expect;
    expect.precision(17);
    for (std::size_t k = 0; k < 1000; k += 97)
        expect << "(" << k << ", " << particles[k]["r"][0].get<double>() << ", "
               << particles[k]["r"][1].get<double>() << "),";
    const auto py = run_python(
        "import gsd.hoomd\n"
        "t = gsd.hoomd.open('" +
            (dir / "out/trajectory.gsd").string() +
            "')\n"
            "f = t[len(t) - 1]\n"
            "assert len(t) == 3, len(t)\n"
            "assert f.particles.N == 1000, f.particles.N\n"
            "assert list(f.configuration.box) == [50, 50, 0, 0, 0, 0], f.configuration.box\n"
            "assert f.configuration.dimensions == 2\n"
            "assert f.configuration.step == 40, f.configuration.step\n"
            "for k, x, y in [" +
            expect.str() +
            "]:\n"
            "    p = f.particles.position[k]\n"
            "    assert abs(p[0] - x) < 1e-5 and abs(p[1] - y) < 1e-5 and p[2] == 0, (k, p, x, y)\n"
            "print('ok')\n",
        dir);
    ASSERT_EQ(py.exit_code, 0) << py.output;
    EXPECT_NE(py.output.find("ok"), std::string::npos) << py.output;
    // the text table and the XYZ trajectory hold the same particles
    const std::string table = slurp(dir / "out/snapshots/frame_000002.txt");
    EXPECT_NE(table.find("# id x y nx ny vx vy fx fy"), std::string::npos);
    EXPECT_EQ(std::count(table.begin(), table.end(), '\n'), 1002);
    const std::string xyz = slurp(dir / "out/trajectory.xyz");
    EXPECT_EQ(xyz.rfind("1000\n", 0), 0u);
}

// Restart: 100 steps, then a restart to 200, must equal 200 steps in one go bit for bit,
// with noise, alignment, list rebuilds and space-filling-curve sorts on both sides of
// the checkpoint.
void expect_restart_exact(const fs::path& dir, const std::string& extra) {
    const std::string out = "log_every = 25\nformats = [\"json\"]";
    std::ofstream(dir / "full.toml") << tutorial_config("steps = 200\ndt = 0.01", out, extra);
    std::ofstream(dir / "half.toml") << tutorial_config("steps = 100\ndt = 0.01", out, extra);
    ASSERT_EQ(run_pedesis("run full.toml --out full", dir).exit_code, 0);
    const auto half = run_pedesis("run half.toml --out half", dir);
    ASSERT_EQ(half.exit_code, 0) << half.output;
    const auto cont = run_pedesis("run full.toml --out cont --restart half/checkpoint.bin", dir);
    ASSERT_EQ(cont.exit_code, 0) << cont.output;
    const std::string a = slurp(dir / "full/snapshots/frame_000001.json");
    // frames are numbered on from the checkpoint: the half run wrote frames 0 and 1
    const std::string b = slurp(dir / "cont/snapshots/frame_000002.json");
    ASSERT_FALSE(a.empty());
    EXPECT_TRUE(a == b) << "the restarted run differs from the continuous one";
    // the log rows after the checkpoint agree too
    const std::string la = slurp(dir / "full/log.csv"), lb = slurp(dir / "cont/log.csv");
    EXPECT_NE(la.find(lb.substr(lb.find('\n') + 1)), std::string::npos) << lb;
}

TEST_F(SoftRun, RestartEqualsContinuousRunBrownian) {
    expect_restart_exact(dir, "");
}

TEST_F(SoftRun, RestartEqualsContinuousRunWithSortingAndNoise) {
    // the [neighbor_list] of the example, sorting often, and thermal noise on positions
    std::string text = tutorial_config("steps = 200\ndt = 0.01", "");
    ASSERT_NE(text.find("\npad = 0.5\n"), std::string::npos);
    std::string full =
        std::regex_replace(text, std::regex("\npad = 0.5\n"), "\npad = 0.5\nsort_every = 30\n");
    full = std::regex_replace(full, std::regex("T = 0.0\n"), "T = 0.05\n");
    std::string half = std::regex_replace(full, std::regex("steps = 200"), "steps = 100");
    full += "formats = [\"json\"]\nlog_every = 25\n";
    half += "formats = [\"json\"]\nlog_every = 25\n";
    write("full.toml", full);
    write("half.toml", half);
    ASSERT_EQ(run_pedesis("run full.toml --out full", dir).exit_code, 0);
    ASSERT_EQ(run_pedesis("run half.toml --out half", dir).exit_code, 0);
    const auto cont = run_pedesis("run full.toml --out cont --restart half/checkpoint.bin", dir);
    ASSERT_EQ(cont.exit_code, 0) << cont.output;
    EXPECT_TRUE(slurp(dir / "full/snapshots/frame_000001.json") ==
                slurp(dir / "cont/snapshots/frame_000002.json"));
}

TEST_F(SoftRun, RestartEqualsContinuousRunLangevin) {
    // velocity Verlet half-kicks read the forces saved in the checkpoint
    std::string text = tutorial_config("steps = 200\ndt = 0.005", "");
    text =
        std::regex_replace(text, std::regex("dynamics = \"brownian\""), "dynamics = \"langevin\"");
    text = std::regex_replace(text, std::regex("name = \"brownian\"\nT = 0.0"),
                              "name = \"langevin\"\nT = 0.2");
    std::string half = std::regex_replace(text, std::regex("steps = 200"), "steps = 100");
    text += "formats = [\"json\"]\nlog_every = 25\n";
    half += "formats = [\"json\"]\nlog_every = 25\n";
    write("full.toml", text);
    write("half.toml", half);
    const auto full = run_pedesis("run full.toml --out full", dir);
    ASSERT_EQ(full.exit_code, 0) << full.output;
    ASSERT_EQ(run_pedesis("run half.toml --out half", dir).exit_code, 0);
    const auto cont = run_pedesis("run full.toml --out cont --restart half/checkpoint.bin", dir);
    ASSERT_EQ(cont.exit_code, 0) << cont.output;
    EXPECT_TRUE(slurp(dir / "full/snapshots/frame_000001.json") ==
                slurp(dir / "cont/snapshots/frame_000002.json"));
}

TEST_F(SoftRun, RestartThatAsksForNoMoreStepsIsAnError) {
    write("run.toml", tutorial_config("steps = 20\ndt = 0.01", "formats = [\"json\"]"));
    ASSERT_EQ(run_pedesis("run run.toml --out a", dir).exit_code, 0);
    const auto r = run_pedesis("run run.toml --out b --restart a/checkpoint.bin", dir);
    EXPECT_EQ(r.exit_code, 2) << r.output;
    EXPECT_NE(r.output.find("is at step 20, and run.steps = 20"), std::string::npos) << r.output;
}

TEST_F(SoftRun, PerSpeciesSelfPropulsion) {
    // Two species placed at random, no pair forces, no noise: species A moves at
    // alpha / gamma = 2 along its director, B (alpha = 0) never moves. Exact to rounding.
    write("mix.toml", R"(dimension = 2
dynamics = "brownian"
seed = 4
[box]
length = 30
[[species]]
name = "A"
count = 20
radius = 1.0
[[species]]
name = "B"
count = 30
radius = 1.0
[[force]]
name = "self_propulsion"
alpha = { A = 2.0, B = 0.0 }
[[integrator]]
name = "brownian"
T = 0.0
gamma = 1.0
[run]
steps = 10
dt = 0.01
[output]
formats = ["json"]
progress = false
)");
    const auto r = run_pedesis("run mix.toml --out out", dir);
    ASSERT_EQ(r.exit_code, 0) << r.output;
    const auto a = read_json(dir / "out/snapshots/frame_000000.json")["system"]["particles"];
    const auto b = read_json(dir / "out/snapshots/frame_000001.json")["system"]["particles"];
    ASSERT_EQ(a.size(), 50u);
    for (std::size_t k = 0; k < 50; ++k) {
        const double v = std::hypot(b[k]["v"][0].get<double>(), b[k]["v"][1].get<double>());
        EXPECT_NEAR(v, b[k]["type"] == 0 ? 2.0 : 0.0, 1e-12) << k;
        if (b[k]["type"] == 1) {
            EXPECT_EQ(a[k]["r"], b[k]["r"]) << k;
        }
    }
}

TEST_F(SoftRun, ThreeDimensionalRunThroughTheSamePlugins) {
    // 3D: positions from [[species]], directors on the sphere, alignment and rotational
    // noise; directors stay unit vectors and python3-gsd sees a 3D box.
    write("abp3d.toml", R"(dimension = 3
dynamics = "brownian"
seed = 9
[box]
length = 12
[[species]]
name = "A"
count = 300
radius = 0.5
[[force]]
name = "harmonic"
k = 10.0
[[force]]
name = "self_propulsion"
alpha = 1.0
[[torque]]
name = "polar_align"
J = 1.0
a = 1.5
[[integrator]]
name = "brownian"
T = 0.1
gamma = 1.0
[[integrator]]
name = "brownian_rotation"
T = 0.1
gamma = 1.0
[run]
steps = 100
dt = 0.005
[output]
formats = ["json", "gsd"]
progress = false
)");
    const auto r = run_pedesis("run abp3d.toml --out out", dir);
    ASSERT_EQ(r.exit_code, 0) << r.output;
    const auto p = read_json(dir / "out/snapshots/frame_000001.json")["system"]["particles"];
    ASSERT_EQ(p.size(), 300u);
    for (const auto& q : p) {
        ASSERT_EQ(q["r"].size(), 3u);
        const double n = std::sqrt(q["n"][0].get<double>() * q["n"][0].get<double>() +
                                   q["n"][1].get<double>() * q["n"][1].get<double>() +
                                   q["n"][2].get<double>() * q["n"][2].get<double>());
        EXPECT_NEAR(n, 1.0, 1e-12);
    }
    const auto py = run_python("import gsd.hoomd\n"
                               "f = gsd.hoomd.open('" +
                                   (dir / "out/trajectory.gsd").string() +
                                   "')[1]\n"
                                   "assert f.configuration.dimensions == 3\n"
                                   "assert list(f.configuration.box) == [12, 12, 12, 0, 0, 0]\n"
                                   "assert f.particles.N == 300\n"
                                   "print('ok')\n",
                               dir);
    EXPECT_EQ(py.exit_code, 0) << py.output;
}

TEST_F(SoftRun, BlowUpStopsNamingStepAndParticleAndKeepsTheLastGoodSnapshot) {
    // alpha = 1000 moves a particle 10 per step, far more than the skin of 0.5
    std::string text =
        tutorial_config("steps = 50\ndt = 0.01", "snapshot_every = 1\nformats = [\"json\"]");
    text = std::regex_replace(text, std::regex("alpha = 1.0"), "alpha = 1000.0");
    write("boom.toml", text);
    const auto r = run_pedesis("run boom.toml --out out", dir);
    EXPECT_EQ(r.exit_code, 3) << r.output;
    EXPECT_NE(r.output.find("at step 0 particle"), std::string::npos) << r.output;
    EXPECT_NE(r.output.find("last good snapshot is frame 0"), std::string::npos) << r.output;
    EXPECT_EQ(read_json(dir / "out/snapshots/frame_000000.json")["system"]["particles"].size(),
              1000u);
    EXPECT_FALSE(fs::exists(dir / "out/snapshots/frame_000001.json"));
    EXPECT_TRUE(fs::exists(dir / "out/log.csv")); // committed, not left as .part
    EXPECT_FALSE(fs::exists(dir / "out/summary.json"));
}

} // namespace
} // namespace pedesis::test
