// [initial] file reads a frame of a GSD file (HOOMD-blue's conventions, written here by
// the gsd Python package as HOOMD-blue writes it) or of an extended XYZ file, and the run
// starts from the same state: positions, types, radii = diameters / 2, masses,
// velocities and directors = the x axis turned by the orientation (issue 28, item 6).
// The state is read back from the run's frame 0 in the tutorial's JSON, which keeps
// every digit, by Python: an independent reading of both files.
#include "cli/cli_support.hpp"

#include <filesystem>
#include <string>

namespace pedesis::test {
namespace {

namespace fs = std::filesystem;

const char* const python = "/usr/bin/python3"; // Debian's, which has python3-gsd and numpy

CliResult run_python(const std::string& code, const fs::path& dir) {
    std::ofstream(dir / "check.py") << code;
    return shell(std::string(python) + " check.py", dir);
}

// A HOOMD-style GSD of two frames: frame 0 and frame 1 differ in every position, types
// "A" and "B" with diameters 1.2 and 0.8 and masses 1 and 2, velocities, orientations
// (turns about z in 2D; any turn in 3D), the box centred at the origin as HOOMD-blue
// keeps it. Positions stay in [-L/2, L/2).
std::string write_hoomd_gsd(int dim) {
    return R"(import numpy as np, gsd.hoomd
Frame = getattr(gsd.hoomd, "Frame", None) or gsd.hoomd.Snapshot  # (gsd < 2.8: Snapshot)
W = "w" if hasattr(gsd.hoomd, "Frame") else "wb"
dim = )" + std::to_string(dim) +
           R"(
rng = np.random.default_rng(5)
N, L = 40, 16.0
def frame(step):
    f = Frame()
    f.configuration.step = step
    f.configuration.box = [L, L, L if dim == 3 else 0.0, 0, 0, 0]
    f.configuration.dimensions = dim
    f.particles.N = N
    f.particles.types = ["A", "B"]
    f.particles.typeid = np.array([i % 2 for i in range(N)], dtype=np.uint32)
    # a 4 x 10 grid with jitter: well inside the box, no overlaps of diameter 1.2
    g = np.array([[(-L / 2 + 2.0 + 3.0 * (i % 4)), (-L / 2 + 1.0 + 1.5 * (i // 4)), 0.0]
                  for i in range(N)])
    g[:, :2] += rng.uniform(-0.1, 0.1, (N, 2))
    if dim == 3:
        g[:, 2] = rng.uniform(-L / 2 + 1, L / 2 - 1, N)
    f.particles.position = g.astype(np.float32)
    f.particles.diameter = np.where(f.particles.typeid == 0, 1.2, 0.8).astype(np.float32)
    f.particles.mass = np.where(f.particles.typeid == 0, 1.0, 2.0).astype(np.float32)
    v = rng.normal(size=(N, 3))
    if dim == 2:
        v[:, 2] = 0
        th = rng.uniform(-np.pi, np.pi, N)
        q = np.stack([np.cos(th / 2), 0 * th, 0 * th, np.sin(th / 2)], axis=1)
    else:
        q = rng.normal(size=(N, 4))
        q /= np.linalg.norm(q, axis=1)[:, None]
    f.particles.velocity = v.astype(np.float32)
    f.particles.orientation = q.astype(np.float32)
    return f
with gsd.hoomd.open("start.gsd", W) as t:
    t.append(frame(0))
    t.append(frame(1000))
)";
}

// Compares frame `k` of start.gsd with the run's frame 0 (out/snapshots/frame_000000.json):
// what the start should be under HOOMD-blue's conventions, computed here.
std::string check_against_gsd(int k, const std::string& names = "['A', 'B']") {
    return R"(import json, numpy as np, gsd.hoomd
with gsd.hoomd.open("start.gsd", "r" if hasattr(gsd.hoomd, "Frame") else "rb") as t:
    f = t[)" +
           std::to_string(k) +
           R"(]
dim = int(f.configuration.dimensions)
doc = json.load(open("out/snapshots/frame_000000.json"))["system"]
ps = sorted(doc["particles"], key=lambda p: p["id"])
names = )" +
           names +
           R"(  # the run's species, in its order
assert [doc["box"][k] for k in ("Lx", "Ly", "Lz")[:dim]] == list(f.configuration.box[:dim])
r = np.array([p["r"] for p in ps]); v = np.array([p["v"] for p in ps])
n = np.array([p["n"] for p in ps]); radius = np.array([p["radius"] for p in ps])
mass = np.array([p["mass"] for p in ps]); types = [names[p["type"]] for p in ps]
assert len(ps) == f.particles.N
assert np.array_equal(r, f.particles.position[:, :dim].astype(float)), "positions"
assert np.array_equal(v, f.particles.velocity[:, :dim].astype(float)), "velocities"
assert types == [f.particles.types[t] for t in f.particles.typeid], "types"
# (a config's species radius is the file's to single precision)
assert np.allclose(radius, f.particles.diameter / 2.0, rtol=1e-6, atol=0), "radius = d / 2"
assert np.array_equal(mass, f.particles.mass.astype(float)), "masses"
# the director: x = (1, 0, 0) turned by q, q x q*
q = f.particles.orientation.astype(float); q /= np.linalg.norm(q, axis=1)[:, None]
w, x, y, z = q.T
ex = np.stack([1 - 2 * (y * y + z * z), 2 * (x * y + w * z), 2 * (x * z - w * y)], axis=1)
assert np.allclose(n, ex[:, :dim], atol=1e-6), np.abs(n - ex[:, :dim]).max()
print("same state")
)";
}

class InitialGsd : public ScratchDir {
  protected:
    // A soft NVE run of a few steps from start.gsd: velocities kept, frame 0 in JSON.
    CliResult run_soft(int dim, const std::string& initial, const std::string& species = "") {
        write("run.toml", "dimension = " + std::to_string(dim) +
                              "\ndynamics = \"nve\"\nseed = 3\n[initial]\nfile = \"start.gsd\"\n" +
                              initial + "\n" + species +
                              "[[force]]\nname = \"wca\"\nepsilon = 1.0\n"
                              "[[integrator]]\nname = \"nve\"\n[run]\nsteps = 5\ndt = 0.0001\n"
                              "[output]\nprogress = false\nformats = [\"json\"]\n");
        return run_pedesis("run run.toml --out out", dir, 120);
    }
};

TEST_F(InitialGsd, HoomdFrame2DStartsTheSameState) {
    const CliResult w = run_python(write_hoomd_gsd(2), dir);
    ASSERT_EQ(w.exit_code, 0) << w.output;
    // no [box], no [[species]]: both from the file, the last frame by default
    const CliResult r = run_soft(2, "");
    ASSERT_EQ(r.exit_code, 0) << r.output;
    const CliResult c = run_python(check_against_gsd(1), dir);
    EXPECT_EQ(c.exit_code, 0) << c.output;
    EXPECT_NE(c.output.find("same state"), std::string::npos) << c.output;
}

TEST_F(InitialGsd, FrameKeyChoosesTheFrame) {
    ASSERT_EQ(run_python(write_hoomd_gsd(2), dir).exit_code, 0);
    for (const std::string frame : {"0", "-2"}) {
        const CliResult r = run_soft(2, "frame = " + frame);
        ASSERT_EQ(r.exit_code, 0) << r.output;
        const CliResult c = run_python(check_against_gsd(0), dir);
        EXPECT_EQ(c.exit_code, 0) << "frame = " << frame << ": " << c.output;
    }
    // and the check tells the frames apart: frame 0 is not the last one
    ASSERT_EQ(run_soft(2, "frame = 1").exit_code, 0);
    EXPECT_NE(run_python(check_against_gsd(0), dir).exit_code, 0);
}

TEST_F(InitialGsd, HoomdFrame3DStartsTheSameState) {
    const CliResult w = run_python(write_hoomd_gsd(3), dir);
    ASSERT_EQ(w.exit_code, 0) << w.output;
    const CliResult r = run_soft(3, "");
    ASSERT_EQ(r.exit_code, 0) << r.output;
    const CliResult c = run_python(check_against_gsd(1), dir);
    EXPECT_EQ(c.exit_code, 0) << c.output;
}

TEST_F(InitialGsd, SpeciesOfTheConfigAreMatchedByName) {
    ASSERT_EQ(run_python(write_hoomd_gsd(2), dir).exit_code, 0);
    // the config lists B before A: the file's type names decide, not their order
    const CliResult r =
        run_soft(2, "",
                 "[box]\nlength = 16.0\n[[species]]\nname = \"B\"\nradius = 0.4\nmass = 2.0\n"
                 "[[species]]\nname = \"A\"\nradius = 0.6\nmass = 1.0\n");
    ASSERT_EQ(r.exit_code, 0) << r.output;
    const CliResult c = run_python(check_against_gsd(1, "['B', 'A']"), dir);
    EXPECT_EQ(c.exit_code, 0) << c.output;
}

TEST_F(InitialGsd, HardParticlesStartFromAGsdFrame) {
    ASSERT_EQ(run_python(write_hoomd_gsd(2), dir).exit_code, 0);
    write("run.toml", "dimension = 2\nseed = 3\n[box]\nlength = 16.0\n"
                      "[[species]]\nname = \"A\"\nradius = 0.6\nmass = 1.0\n"
                      "[[species]]\nname = \"B\"\nradius = 0.4\nmass = 2.0\n"
                      "[initial]\nfile = \"start.gsd\"\n[run]\ntime = 0.5\n"
                      "[output]\nprogress = false\nformats = [\"json\"]\n");
    const CliResult r = run_pedesis("run run.toml --out out", dir, 120);
    ASSERT_EQ(r.exit_code, 0) << r.output;
    // (hard particles have no directors: the check of the soft runs without them)
    const CliResult c2 = run_python(std::string(R"(import json, numpy as np, gsd.hoomd
f = gsd.hoomd.open("start.gsd", "r" if hasattr(gsd.hoomd, "Frame") else "rb")[1]
ps = sorted(json.load(open("out/snapshots/frame_000000.json"))["system"]["particles"],
            key=lambda p: p["id"])
assert np.array_equal([p["r"] for p in ps], f.particles.position[:, :2].astype(float))
assert np.array_equal([p["v"] for p in ps], f.particles.velocity[:, :2].astype(float))
assert [p["type"] for p in ps] == list(f.particles.typeid)
assert np.allclose([p["radius"] for p in ps], f.particles.diameter / 2, rtol=1e-7)
print("same state")
)"),
                                    dir);
    EXPECT_NE(c2.output.find("same state"), std::string::npos) << c2.output;
}

TEST_F(InitialGsd, PedesisOwnTrajectoryRestartsFromItsLastFrame) {
    // a soft run's trajectory.gsd as the start of another: the same positions (single
    // precision, as GSD stores them), directors, species names and radii
    write("first.toml", "dimension = 2\ndynamics = \"brownian\"\nseed = 9\n[box]\nlength = 14.0\n"
                        "[[species]]\nname = \"big\"\ncount = 20\nradius = 0.7\n"
                        "[[species]]\nname = \"small\"\ncount = 10\nradius = 0.3\n"
                        "[[force]]\nname = \"harmonic\"\nk = 10.0\n"
                        "[[force]]\nname = \"self_propulsion\"\nalpha = 1.0\n"
                        "[[integrator]]\nname = \"brownian\"\nT = 0.1\ngamma = 1.0\n"
                        "[[integrator]]\nname = \"brownian_rotation\"\nT = 0.1\ngamma = 1.0\n"
                        "[run]\nsteps = 50\ndt = 0.001\n"
                        "[output]\nprogress = false\nformats = [\"gsd\", \"json\"]\n");
    ASSERT_EQ(run_pedesis("run first.toml --out first", dir, 120).exit_code, 0);
    write("second.toml", "dimension = 2\ndynamics = \"brownian\"\nseed = 9\n"
                         "[initial]\nfile = \"first/trajectory.gsd\"\n"
                         "[[force]]\nname = \"harmonic\"\nk = 10.0\n"
                         "[[integrator]]\nname = \"brownian\"\nT = 0.1\ngamma = 1.0\n"
                         "[run]\nsteps = 5\ndt = 0.001\n"
                         "[output]\nprogress = false\nformats = [\"json\"]\n");
    const CliResult r = run_pedesis("run second.toml --out second", dir, 120);
    ASSERT_EQ(r.exit_code, 0) << r.output;
    const CliResult c = run_python(R"(import json, numpy as np
def state(path):
    s = json.load(open(path))["system"]
    return sorted(s["particles"], key=lambda p: p["id"])
a = state("first/snapshots/frame_000001.json")
b = state("second/snapshots/frame_000000.json")
assert len(a) == len(b) == 30
f32 = lambda x: np.asarray(x, dtype=np.float32).astype(float)
assert np.array_equal(f32([p["r"] for p in a]), [p["r"] for p in b])
assert np.array_equal([p["radius"] for p in b], f32([0.7] * 20 + [0.3] * 10))
assert [p["type"] for p in a] == [p["type"] for p in b]
assert np.allclose([p["n"] for p in a], [p["n"] for p in b], atol=1e-6)
print("same state")
)",
                                   dir);
    EXPECT_NE(c.output.find("same state"), std::string::npos) << c.output;
}

TEST_F(InitialGsd, FaultsAreNamed) {
    ASSERT_EQ(run_python(write_hoomd_gsd(2), dir).exit_code, 0);
    const auto rejected = [&](const CliResult& r, const std::string& part) {
        EXPECT_EQ(r.exit_code, 2) << r.output;
        EXPECT_NE(r.output.find(part), std::string::npos) << r.output;
    };
    rejected(run_soft(2, "frame = 2"), "[initial] frame = 2, but the file has 2 frame(s)");
    rejected(run_soft(2, "frame = -3"), "[initial] frame = -3");
    rejected(run_soft(3, ""), "the frame is 2D (configuration/dimensions = 2), but this run is 3D");
    rejected(run_soft(2, "", "[box]\nlength = 16.0\n[[species]]\nname = \"A\"\n"),
             "particle 1 is of type 'B'");
    rejected(run_soft(2, "",
                      "[box]\nlength = 15.0\n[[species]]\nname = \"A\"\nradius = "
                      "0.6\n[[species]]\nname = \"B\"\nradius = 0.4\nmass = 2.0\n"),
             "box does not match");
    write("init.json", "{\"system\": {\"box\": {\"Lx\": 5, \"Ly\": 5}, \"particles\": [{\"id\": "
                       "0, \"r\": [0, 0]}]}}");
    write("json.toml", "dimension = 2\ndynamics = \"brownian\"\n[initial]\nfile = \"init.json\"\n"
                       "frame = 0\n[[integrator]]\nname = \"brownian\"\nT = 0.1\ngamma = 1.0\n"
                       "[run]\nsteps = 5\ndt = 0.001\n");
    rejected(run_pedesis("run json.toml --out j", dir, 60), "is for GSD and XYZ files");
    write("noframe.toml", "dimension = 2\n[box]\nlength = 5.0\n[[species]]\ncount = 2\n"
                          "[initial]\nframe = 0\n[run]\ntime = 1.0\n");
    rejected(run_pedesis("run noframe.toml --out n", dir, 60), "give [initial] file");
}

class InitialXyz : public ScratchDir {};

TEST_F(InitialXyz, CornerOriginCellIsCentredAndEveryColumnKept) {
    // ASE/OVITO style: the cell's corner at the origin (no Origin key), positions in
    // [0, L), species by name, velocities and radii as columns; ids absent (row order)
    const CliResult w = run_python(R"(import numpy as np
rng = np.random.default_rng(2)
N, L = 24, 12.0
rows = []
for i in range(N):
    s = "Ar" if i % 3 else "He"
    x, y = 1.0 + 2.0 * (i % 6) + rng.uniform(-0.2, 0.2), 1.0 + 2.5 * (i // 6)
    vx, vy = rng.normal(size=2)
    rows.append(f"{s} {x!r} {y!r} 0.0 {vx!r} {vy!r} 0.0 {0.45 if s == 'Ar' else 0.3}")
with open("start.xyz", "w") as out:
    for frame in range(2):
        out.write(f"{N}\nLattice=\"{L} 0 0 0 {L} 0 0 0 1.0\" Properties=species:S:1:pos:R:3:"
                  f"velo:R:3:radius:R:1 pbc=\"T T F\"\n")
        out.write("\n".join(rows) + "\n")
)",
                                   dir);
    ASSERT_EQ(w.exit_code, 0) << w.output;
    write("run.toml", "dimension = 2\ndynamics = \"nve\"\nseed = 1\n[initial]\nfile = "
                      "\"start.xyz\"\n[[force]]\nname = \"wca\"\nepsilon = 1.0\n"
                      "[[integrator]]\nname = \"nve\"\n[run]\nsteps = 3\ndt = 0.0001\n"
                      "[output]\nprogress = false\nformats = [\"json\"]\n");
    const CliResult r = run_pedesis("run run.toml --out out", dir, 120);
    ASSERT_EQ(r.exit_code, 0) << r.output;
    const CliResult c = run_python(R"(import json, numpy as np
lines = open("start.xyz").read().splitlines()[2:26]
rows = [l.split() for l in lines]
s = json.load(open("out/snapshots/frame_000000.json"))["system"]
ps = sorted(s["particles"], key=lambda p: p["id"])
assert s["box"] == {"Lx": 12.0, "Ly": 12.0}
# species named after the file's, in order of first appearance: He (row 0), then Ar
names = ["He", "Ar"]
assert [names[p["type"]] for p in ps] == [r[0] for r in rows]
want = np.array([[float(r[1]) - 6.0, float(r[2]) - 6.0] for r in rows])
assert np.allclose([p["r"] for p in ps], want, rtol=0, atol=1e-12)
assert [p["v"] for p in ps] == [[float(r[4]), float(r[5])] for r in rows]
assert [p["radius"] for p in ps] == [float(r[7]) for r in rows]
print("same state")
)",
                                   dir);
    EXPECT_NE(c.output.find("same state"), std::string::npos) << c.output;
}

TEST_F(InitialXyz, PedesisOwnXyzTrajectoryStartsAHardRun) {
    write("first.toml",
          small_config("", "length = 20.0", "time = 1.0") + "formats = [\"xyz\", \"json\"]\n");
    ASSERT_EQ(run_pedesis("run first.toml --out first", dir, 120).exit_code, 0);
    write("second.toml", small_config("", "length = 20.0", "time = 1.0") +
                             "formats = [\"json\"]\n[initial]\nfile = \"first/trajectory.xyz\"\n");
    const CliResult r = run_pedesis("run second.toml --out second", dir, 120);
    ASSERT_EQ(r.exit_code, 0) << r.output;
    // the last frame of the first run is the first of the second, digit for digit
    const CliResult c = run_python(R"(import json, glob
last = sorted(glob.glob("first/snapshots/frame_*.json"))[-1]
a = json.load(open(last))["system"]["particles"]
b = json.load(open("second/snapshots/frame_000000.json"))["system"]["particles"]
key = lambda p: p["id"]
for p, q in zip(sorted(a, key=key), sorted(b, key=key)):
    assert p["r"] == q["r"] and p["v"] == q["v"] and p["type"] == q["type"], (p, q)
print("same state", len(a))
)",
                                   dir);
    EXPECT_NE(c.output.find("same state 50"), std::string::npos) << c.output;
}

} // namespace
} // namespace pedesis::test
