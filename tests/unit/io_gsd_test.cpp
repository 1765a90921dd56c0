// GSD trajectories are read back with the real gsd Python package (its C reader
// through gsd.hoomd, and its pure-Python reader gsd.pygsd), never with code of ours:
// frame count, header, box, types, and per-particle values in tag order.
#include "pedesis/core/error.hpp"
#include "pedesis/io/gsd_writer.hpp"

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <limits>
#include <numeric>
#include <random>
#include <string>
#include <sys/wait.h>
#include <unistd.h>
#include <vector>

#include "support/soft_builder.hpp"

using namespace pedesis;
namespace fs = std::filesystem;
using nlohmann::json;

namespace {

#ifdef PEDESIS_PYTHON
const char* const python = PEDESIS_PYTHON;
#else
const char* const python = "/usr/bin/python3"; // Debian's, which has python3-gsd
#endif

// Prints everything the checks need as JSON; non-finite numbers as strings, since
// JSON has none. The director is x rotated by the stored quaternion.
constexpr const char* reader_script = R"PY(
import json, math, sys
import numpy as np
import gsd, gsd.fl, gsd.hoomd, gsd.pygsd

def num(x):
    x = float(x)
    return x if math.isfinite(x) else repr(x)

def rotate_x(q):
    s, u = float(q[0]), np.array(q[1:], dtype=np.float64)
    v = np.array([1.0, 0.0, 0.0])
    return (v + 2.0 * s * np.cross(u, v) + 2.0 * np.cross(u, np.cross(u, v))).tolist()

def frame(snap):
    p = snap.particles
    return {
        "step": int(snap.configuration.step),
        "time": float(np.asarray(snap.log["time"]).reshape(-1)[0]),
        "dimensions": int(snap.configuration.dimensions),
        "box": [float(x) for x in snap.configuration.box],
        "N": int(p.N),
        "types": list(p.types),
        "typeid": [int(x) for x in p.typeid],
        "mass": [num(x) for x in p.mass],
        "diameter": [float(x) for x in p.diameter],
        "position": p.position.astype(np.float64).tolist(),
        "velocity": p.velocity.astype(np.float64).tolist(),
        "image": p.image.astype(np.int64).tolist(),
        "orientation": p.orientation.astype(np.float64).tolist(),
        "director": [rotate_x(q) for q in p.orientation],
        "periodic": np.asarray(snap.log["pedesis/periodic"]).tolist(),
    }

path = sys.argv[1]
out = {}
with gsd.fl.open(name=path, mode="rb") as f:
    out["application"] = f.application
    out["schema"] = f.schema
    out["schema_version"] = list(f.schema_version)
    out["gsd_version"] = list(f.gsd_version)
    out["nframes"] = int(f.nframes)
with gsd.hoomd.open(name=path, mode="rb") as t:
    out["frames"] = [frame(s) for s in t]
with open(path, "rb") as raw:
    t = gsd.hoomd.HOOMDTrajectory(gsd.pygsd.GSDFile(raw))
    out["pygsd_frames"] = [frame(s) for s in t]
print(json.dumps(out))
)PY";

struct ReaderRun {
    int status;
    std::string output;
};

ReaderRun run_reader(const fs::path& script, const fs::path& gsd) {
    const std::string cmd =
        std::string(python) + " '" + script.string() + "' '" + gsd.string() + "' 2>&1";
    FILE* pipe = ::popen(cmd.c_str(), "r");
    if (pipe == nullptr) return {-1, "popen failed"};
    std::string out;
    char buf[4096];
    std::size_t got;
    while ((got = std::fread(buf, 1, sizeof buf, pipe)) > 0) out.append(buf, got);
    const int status = ::pclose(pipe);
    return {WIFEXITED(status) ? WEXITSTATUS(status) : -1, out};
}

class io_gsd : public ::testing::Test {
  protected:
    void SetUp() override {
        const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
        dir = fs::temp_directory_path() /
              ("pedesis_io_gsd_" + std::string(info->name()) + "_" + std::to_string(::getpid()));
        fs::remove_all(dir);
        fs::create_directories(dir);
        script = dir / "read_gsd.py";
        std::ofstream(script) << reader_script;
    }
    void TearDown() override { fs::remove_all(dir); }

    // The file as the gsd package sees it; fails the test if it cannot read it.
    json read(const fs::path& file) {
        const ReaderRun r = run_reader(script, file);
        EXPECT_EQ(r.status, 0) << r.output;
        if (r.status != 0) return json::object();
        try {
            return json::parse(r.output);
        } catch (const json::exception& e) {
            ADD_FAILURE() << e.what() << "\n" << r.output;
            return json::object();
        }
    }

    fs::path dir, script;
};

constexpr double inf = std::numeric_limits<double>::infinity();

template <int D> SoftState<D> shuffled_state(std::size_t n, unsigned seed) {
    SoftState<D> s;
    std::array<bool, D> periodic{};
    periodic.fill(true);
    Vec<D> L;
    for (int a = 0; a < D; ++a) L[a] = 8.0 + 2.0 * a;
    s.box = Box<D>(L, periodic);
    s.p.species_table = {Species{"A", 0.5, 1.0}, Species{"Bigger", 1.25, 3.0 / 7.0},
                         Species{"wall", 2.0, inf}};
    s.resize(n);
    std::mt19937_64 gen(seed);
    std::uniform_real_distribution<double> u(-0.5, 0.5);
    std::uniform_int_distribution<int> img(-3, 3);
    std::vector<std::uint32_t> tags(n);
    std::iota(tags.begin(), tags.end(), 0u);
    std::shuffle(tags.begin(), tags.end(), gen);
    for (std::size_t i = 0; i < n; ++i) {
        for (int a = 0; a < D; ++a) {
            s.p.position[i][a] = u(gen) * L[a];
            s.p.velocity[i][a] = 3.0 * u(gen);
            s.director[i][a] = u(gen);
            s.image[i][a] = img(gen);
        }
        const double len = norm(s.director[i]);
        s.director[i] *= 1.0 / len;
        s.p.tag[i] = tags[i];
        s.p.species[i] = static_cast<std::uint16_t>(tags[i] % 3);
    }
    // The two directors where the quaternion is least well conditioned.
    s.director[0] = Vec<D>{};
    s.director[0][0] = -1.0;
    s.director[1] = Vec<D>{};
    s.director[1][0] = 1.0;
    return s;
}

// Moves every particle and reorders storage, as an engine between two frames would.
template <int D> void advance(SoftState<D>& s, unsigned seed) {
    std::mt19937_64 gen(seed);
    std::uniform_real_distribution<double> u(-0.3, 0.3);
    for (std::size_t i = 0; i < s.size(); ++i) {
        for (int a = 0; a < D; ++a) s.p.position[i][a] += u(gen);
        const Vec<D> shift = s.box.wrap(s.p.position[i]);
        for (int a = 0; a < D; ++a) s.image[i][a] += static_cast<std::int32_t>(shift[a]);
    }
    s = test::permuted_storage(s, gen);
    s.step += 1000;
    s.time += 0.5;
}

double f32(double x) {
    return static_cast<double>(static_cast<float>(x));
}

template <int D> void check_frame(const json& f, const SoftState<D>& s) {
    const std::size_t n = s.size();
    ASSERT_EQ(f.at("N").get<std::size_t>(), n);
    EXPECT_EQ(f.at("step").get<std::uint64_t>(), s.step);
    EXPECT_EQ(f.at("time").get<double>(), s.time); // float64: exact
    EXPECT_EQ(f.at("dimensions").get<int>(), D);
    // 2D: Lz = 0, the HOOMD-blue 3 convention for a 2D box.
    std::vector<double> box{f32(s.box.length(0)),
                            f32(s.box.length(1)),
                            D == 3 ? f32(s.box.length(D - 1)) : 0.0,
                            0.0,
                            0.0,
                            0.0};
    EXPECT_EQ(f.at("box").get<std::vector<double>>(), box);
    EXPECT_EQ(f.at("types").get<std::vector<std::string>>(),
              (std::vector<std::string>{"A", "Bigger", "wall"}));
    std::vector<int> periodic;
    for (int a = 0; a < D; ++a) periodic.push_back(s.box.periodic(a) ? 1 : 0);
    EXPECT_EQ(f.at("periodic").get<std::vector<int>>(), periodic);

    std::vector<std::size_t> storage(n);
    for (std::size_t i = 0; i < n; ++i) storage[s.p.tag[i]] = i;
    for (std::size_t tag = 0; tag < n; ++tag) {
        SCOPED_TRACE("tag " + std::to_string(tag));
        const std::size_t i = storage[tag];
        const Species& sp = s.p.species_table[s.p.species[i]];
        EXPECT_EQ(f.at("typeid")[tag].get<int>(), s.p.species[i]);
        EXPECT_EQ(f.at("diameter")[tag].get<double>(), f32(2.0 * sp.radius));
        if (std::isinf(sp.mass))
            EXPECT_EQ(f.at("mass")[tag].get<std::string>(), "inf");
        else
            EXPECT_EQ(f.at("mass")[tag].get<double>(), f32(sp.mass));
        for (int a = 0; a < 3; ++a) {
            const double r = a < D ? s.p.position[i][a] : 0.0;
            const double v = a < D ? s.p.velocity[i][a] : 0.0;
            const int image = a < D ? s.image[i][a] : 0;
            EXPECT_EQ(f.at("position")[tag][a].get<double>(), f32(r)) << "axis " << a;
            EXPECT_EQ(f.at("velocity")[tag][a].get<double>(), f32(v)) << "axis " << a;
            EXPECT_EQ(f.at("image")[tag][a].get<int>(), image) << "axis " << a;
            const double n_a = a < D ? s.director[i][a] : 0.0;
            EXPECT_NEAR(f.at("director")[tag][a].get<double>(), n_a, 1e-6) << "axis " << a;
        }
        if (D == 2) { // a rotation about z only
            EXPECT_EQ(f.at("orientation")[tag][1].get<double>(), 0.0);
            EXPECT_EQ(f.at("orientation")[tag][2].get<double>(), 0.0);
        }
    }
}

template <int D> void check_file(const json& j, const std::vector<SoftState<D>>& frames) {
    EXPECT_EQ(j.at("application"), "pedesis");
    EXPECT_EQ(j.at("schema"), "hoomd");
    EXPECT_EQ(j.at("schema_version"), json::array({1, 4}));
    EXPECT_EQ(j.at("gsd_version").at(0), 2);
    ASSERT_EQ(j.at("nframes").get<std::size_t>(), frames.size());
    for (const char* reader : {"frames", "pygsd_frames"}) {
        ASSERT_EQ(j.at(reader).size(), frames.size()) << reader;
        for (std::size_t k = 0; k < frames.size(); ++k) {
            SCOPED_TRACE(std::string(reader) + " frame " + std::to_string(k));
            check_frame(j.at(reader)[k], frames[k]);
        }
    }
}

} // namespace

TEST_F(io_gsd, ThreeFrames2DReadBackByGsd) {
    std::vector<SoftState<2>> frames{shuffled_state<2>(29, 1)};
    frames[0].step = 7;
    for (unsigned k = 1; k < 3; ++k) {
        frames.push_back(frames.back());
        advance(frames.back(), k);
    }
    const fs::path file = dir / "traj.gsd";
    {
        GsdWriter<2> w(file);
        for (const auto& s : frames) w.append(s.frame());
        w.commit();
    }
    EXPECT_TRUE(fs::exists(file));
    EXPECT_FALSE(fs::exists(dir / "traj.gsd.part"));
    check_file(read(file), frames);
}

TEST_F(io_gsd, ThreeFrames3DReadBackByGsd) {
    std::vector<SoftState<3>> frames{shuffled_state<3>(31, 2)};
    for (unsigned k = 1; k < 3; ++k) {
        frames.push_back(frames.back());
        advance(frames.back(), 10 + k);
    }
    const fs::path file = dir / "traj.gsd";
    {
        GsdWriter<3> w(file);
        for (const auto& s : frames) w.append(s.frame());
        w.commit();
    }
    check_file(read(file), frames);
}

TEST_F(io_gsd, WalledAxesReadBackByGsdAsTheLogChunk) {
    // the schema's box cannot say walls: frame.log["pedesis/periodic"] does, in every frame
    std::vector<SoftState<2>> frames{shuffled_state<2>(17, 4)};
    frames[0].box = Box<2>(frames[0].box.lengths(), {false, true});
    frames.push_back(frames.back());
    advance(frames.back(), 5);
    const fs::path file = dir / "walled.gsd";
    {
        GsdWriter<2> w(file);
        for (const auto& s : frames) w.append(s.frame());
        w.commit();
    }
    check_file(read(file), frames);
}

TEST_F(io_gsd, UncommittedPartFileIsReadableAfterEachStage) {
    const fs::path file = dir / "run.gsd";
    std::ofstream(file) << "stale output of an earlier run";
    std::vector<SoftState<2>> frames{shuffled_state<2>(11, 3)};
    GsdWriter<2> w(file);
    EXPECT_FALSE(fs::exists(file)) << "a stale file must not pass for this run's output";
    const fs::path part = dir / "run.gsd.part";
    ASSERT_TRUE(fs::exists(part));
    check_file(read(part), std::vector<SoftState<2>>{}); // a valid file with no frames

    w.append(frames[0].frame());
    check_file(read(part), frames);

    // Enough frames to outgrow the initial index twice (128 entries, about 11 per frame).
    for (unsigned k = 1; k < 30; ++k) {
        frames.push_back(frames.back());
        advance(frames.back(), 100 + k);
        w.append(frames.back().frame());
        if (k == 12) check_file(read(part), frames); // just after the first move of the index
    }
    check_file(read(part), frames);
    EXPECT_FALSE(fs::exists(file));
    w.commit();
    w.commit(); // a second commit does nothing
    EXPECT_FALSE(fs::exists(part));
    check_file(read(file), frames);
    EXPECT_THROW(w.append(frames[0].frame()), std::logic_error);
}

TEST_F(io_gsd, DestroyedWriterLeavesTheFramesInThePartFile) {
    const fs::path file = dir / "killed.gsd";
    std::vector<SoftState<3>> frames{shuffled_state<3>(5, 4)};
    frames.push_back(frames.back());
    advance(frames.back(), 5);
    {
        GsdWriter<3> w(file);
        for (const auto& s : frames) w.append(s.frame());
    }
    EXPECT_FALSE(fs::exists(file));
    check_file(read(dir / "killed.gsd.part"), frames);
}

TEST_F(io_gsd, PositionRoundingOntoTheUpperEdgeIsWrapped) {
    // x = L/2 - 1e-12 is inside the box in double but rounds to L/2 in float32, which
    // HOOMD rejects; the same point of the torus is -L/2 in the next image.
    SoftState<2> s = shuffled_state<2>(3, 6);
    const std::size_t i = 2;
    s.p.position[i][0] = 0.5 * s.box.length(0) - 1e-12;
    s.image[i][0] = 4;
    const fs::path file = dir / "edge.gsd";
    {
        GsdWriter<2> w(file);
        w.append(s.frame());
        w.commit();
    }
    const json j = read(file);
    const json& row = j.at("frames")[0];
    const std::uint32_t tag = s.p.tag[i];
    EXPECT_EQ(row.at("position")[tag][0].get<double>(), -0.5 * f32(s.box.length(0)));
    EXPECT_EQ(row.at("image")[tag][0].get<int>(), 5);
}

TEST_F(io_gsd, ChangedSpeciesTableIsWrittenAgain) {
    SoftState<2> s = shuffled_state<2>(6, 7);
    const fs::path file = dir / "types.gsd";
    {
        GsdWriter<2> w(file);
        w.append(s.frame());
        s.p.species_table[1].name = "B";
        w.append(s.frame());
        w.append(s.frame());
        w.commit();
    }
    const json j = read(file);
    const std::vector<std::string> before{"A", "Bigger", "wall"}, after{"A", "B", "wall"};
    EXPECT_EQ(j.at("frames")[0].at("types").get<std::vector<std::string>>(), before);
    EXPECT_EQ(j.at("frames")[1].at("types").get<std::vector<std::string>>(), after);
    EXPECT_EQ(j.at("frames")[2].at("types").get<std::vector<std::string>>(), after);
}
