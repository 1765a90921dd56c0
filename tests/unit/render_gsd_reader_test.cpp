// The GSD reader against what GsdWriter writes (2D and 3D, several frames, the ".part"
// file of a running writer, a species table that changes), against a file written by the
// gsd Python package itself (which leaves unchanged chunks out of later frames, so frame 0
// fills them in), and against truncated and corrupt files, which must be refused with a
// message naming the file.
#include "pedesis/core/error.hpp"
#include "pedesis/io/gsd_reader.hpp"
#include "pedesis/io/gsd_writer.hpp"

#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>
#include <sys/wait.h>
#include <unistd.h>

#include "support/soft_builder.hpp"

using namespace pedesis;
namespace fs = std::filesystem;

namespace {

#ifdef PEDESIS_PYTHON
const char* const python = PEDESIS_PYTHON;
#else
const char* const python = "/usr/bin/python3"; // Debian's, which has python3-gsd
#endif

class GsdReaderTest : public ::testing::Test {
  protected:
    void SetUp() override {
        const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
        dir = fs::temp_directory_path() / ("pedesis_gsd_reader_" + std::string(info->name()) + "_" +
                                           std::to_string(::getpid()));
        fs::remove_all(dir);
        fs::create_directories(dir);
    }
    void TearDown() override { fs::remove_all(dir); }

    std::string read_bytes(const fs::path& p) {
        std::ifstream in(p, std::ios::binary);
        return std::string(std::istreambuf_iterator<char>(in), {});
    }
    fs::path write_bytes(const std::string& name, const std::string& bytes) {
        std::ofstream(dir / name, std::ios::binary) << bytes;
        return dir / name;
    }
    // The InputError message of opening `file` and reading every frame.
    static std::string error_of(const fs::path& file) {
        try {
            GsdReader reader(file);
            for (std::uint64_t k = 0; k < reader.frames(); ++k) reader.frame(k);
        } catch (const InputError& e) {
            return e.what();
        }
        return "(no error)";
    }

    fs::path dir;
};

// Two species, velocities, image counts: every chunk the writer fills.
template <int D> SoftState<D> sample_state(std::uint64_t seed, std::uint64_t step) {
    SoftState<D> s = test::random_soft_system<D>(30, 12.0, 0.5, seed);
    s.p.species_table = {Species{"A", 0.5, 1.0}, Species{"Big", 1.5, 2.0}};
    for (std::size_t i = 0; i < s.size(); ++i) {
        s.p.species[i] = static_cast<std::uint16_t>(i % 3 == 0);
        for (int a = 0; a < D; ++a) s.p.velocity[i][a] = 0.1 * static_cast<double>(i) - a;
    }
    s.step = step;
    s.time = 0.01 * static_cast<double>(step) + 1.0 / 3.0;
    std::mt19937_64 gen(seed);
    return test::permuted_storage(s, gen);
}

// x rotated by the unit quaternion q = (w, x, y, z).
std::array<double, 3> rotate_x(const std::array<double, 4>& q) {
    const double w = q[0], x = q[1], y = q[2], z = q[3];
    return {1.0 - 2.0 * (y * y + z * z), 2.0 * (x * y + w * z), 2.0 * (x * z - w * y)};
}

template <int D> void expect_frame(const SoftState<D>& s, const GsdFrame& g) {
    const auto index = s.p.index_of_tags();
    EXPECT_EQ(g.step, s.step);
    ASSERT_TRUE(g.time.has_value());
    EXPECT_EQ(*g.time, s.time);
    EXPECT_EQ(g.dimensions, D);
    for (int a = 0; a < 3; ++a)
        EXPECT_EQ(g.box[static_cast<std::size_t>(a)],
                  a < D ? static_cast<double>(static_cast<float>(s.box.length(a))) : 0.0);
    EXPECT_EQ(g.types, (std::vector<std::string>{"A", "Big"}));
    std::array<bool, 3> periodic{false, false, false};
    for (int a = 0; a < D; ++a) periodic[static_cast<std::size_t>(a)] = s.box.periodic(a);
    EXPECT_EQ(g.periodic, periodic);
    ASSERT_EQ(g.size(), s.size());
    EXPECT_TRUE(g.velocity_stored);
    EXPECT_TRUE(g.orientation_stored);
    for (std::size_t row = 0; row < g.size(); ++row) {
        const std::uint32_t i = index[row];
        EXPECT_EQ(g.type_id[row], s.p.species[i]);
        EXPECT_EQ(g.mass[row], static_cast<double>(static_cast<float>(s.p.mass(i))));
        EXPECT_EQ(g.diameter[row], static_cast<double>(static_cast<float>(2.0 * s.p.radius(i))));
        const auto n = rotate_x(g.orientation[row]);
        for (int a = 0; a < 3; ++a) {
            const auto c = static_cast<std::size_t>(a);
            const double r =
                a < D ? static_cast<double>(static_cast<float>(s.p.position[i][a])) : 0.0;
            // A float that rounds onto +L/2 is stored as -L/2 (GsdWriter's convention).
            const double L = a < D ? static_cast<double>(static_cast<float>(s.box.length(a))) : 0;
            EXPECT_TRUE(g.position[row][c] == r || g.position[row][c] == r - L) << row << " " << a;
            EXPECT_EQ(g.velocity[row][c],
                      a < D ? static_cast<double>(static_cast<float>(s.p.velocity[i][a])) : 0.0);
            EXPECT_NEAR(n[c], a < D ? s.director[i][a] : 0.0, 1e-6);
        }
    }
}

TEST_F(GsdReaderTest, ReadsBackWhatTheWriterWrites2D) {
    const fs::path file = dir / "t.gsd";
    std::vector<SoftState<2>> states;
    {
        GsdWriter<2> w(file);
        for (std::uint64_t k = 0; k < 3; ++k) {
            states.push_back(sample_state<2>(k + 1, 10 * k));
            w.append(states.back().frame());
        }
        w.commit();
    }
    const GsdReader reader(file);
    EXPECT_EQ(reader.frames(), 3u);
    EXPECT_EQ(reader.application(), "pedesis");
    EXPECT_EQ(reader.schema(), "hoomd");
    EXPECT_EQ(reader.gsd_version(), 2u << 16);
    for (std::uint64_t k : {2u, 0u, 1u}) expect_frame(states[k], reader.frame(k));
}

TEST_F(GsdReaderTest, ReadsBackWhatTheWriterWrites3DPastTheFirstIndexBlock) {
    // 12 chunks a frame: 20 frames outgrow the writer's first index block of 128 entries.
    const fs::path file = dir / "t.gsd";
    std::vector<SoftState<3>> states;
    {
        GsdWriter<3> w(file);
        for (std::uint64_t k = 0; k < 20; ++k) {
            states.push_back(sample_state<3>(k + 7, k));
            w.append(states.back().frame());
        }
        w.commit();
    }
    const GsdReader reader(file);
    ASSERT_EQ(reader.frames(), 20u);
    for (std::uint64_t k : {0u, 5u, 10u, 19u}) expect_frame(states[k], reader.frame(k));
}

TEST_F(GsdReaderTest, WalledAxesReadBackWalled) {
    const fs::path file = dir / "t.gsd";
    auto s2 = sample_state<2>(3, 0);
    s2.box = Box<2>(s2.box.lengths(), {false, true});
    auto s3 = sample_state<3>(4, 0);
    s3.box = Box<3>(s3.box.lengths(), {true, false, false});
    {
        GsdWriter<2> w(file);
        w.append(s2.frame());
        w.append(s2.frame());
        w.commit();
    }
    const GsdReader reader(file);
    EXPECT_TRUE(reader.has_chunk(1, "log/pedesis/periodic")); // in every frame
    for (std::uint64_t k : {0u, 1u}) expect_frame(s2, reader.frame(k));
    {
        GsdWriter<3> w(file);
        w.append(s3.frame());
        w.commit();
    }
    expect_frame(s3, GsdReader(file).frame(0));
}

TEST_F(GsdReaderTest, ReadsTheUnfinishedPartFileOfARunningWriter) {
    const fs::path file = dir / "t.gsd";
    GsdWriter<2> w(file);
    EXPECT_EQ(GsdReader(w.part_path()).frames(), 0u); // a valid file with no frames yet
    const auto s0 = sample_state<2>(1, 0), s1 = sample_state<2>(2, 5);
    w.append(s0.frame());
    w.append(s1.frame());
    const GsdReader reader(w.part_path());
    ASSERT_EQ(reader.frames(), 2u);
    expect_frame(s1, reader.frame(1));
}

TEST_F(GsdReaderTest, FramesWithoutTypesTakeThoseOfFrameZero) {
    const fs::path file = dir / "t.gsd";
    auto s0 = sample_state<2>(1, 0), s1 = s0, s2 = s0;
    s1.p.species_table[1].name = "Other"; // written again in frame 1 only
    s1.step = 1;
    s2.step = 2;
    {
        GsdWriter<2> w(file);
        w.append(s0.frame());
        w.append(s1.frame());
        w.append(s2.frame());
        w.commit();
    }
    const GsdReader reader(file);
    EXPECT_TRUE(reader.has_chunk(1, "particles/types"));
    EXPECT_FALSE(reader.has_chunk(2, "particles/types"));
    EXPECT_EQ(reader.frame(1).types, (std::vector<std::string>{"A", "Other"}));
    EXPECT_EQ(reader.frame(2).types, (std::vector<std::string>{"A", "Big"}));
}

// Runs a Python snippet with Debian's interpreter (python3-gsd); its exit status.
int run_python(const std::string& code, const fs::path& dir) {
    std::ofstream(dir / "make.py") << code;
    const std::string cmd = std::string(python) + " '" + (dir / "make.py").string() + "' 2>&1";
    FILE* pipe = popen(cmd.c_str(), "r");
    if (!pipe) return -1;
    std::array<char, 4096> buf;
    while (fgets(buf.data(), buf.size(), pipe)) std::fputs(buf.data(), stderr);
    const int status = pclose(pipe);
    return WIFEXITED(status) ? WEXITSTATUS(status) : -1;
}

constexpr const char* gsd_python_writer = R"PY(
import sys
import gsd.hoomd
Frame = getattr(gsd.hoomd, "Frame", None) or gsd.hoomd.Snapshot
def frame(step, positions, third_type):
    f = Frame()
    f.configuration.step = step
    f.configuration.dimensions = 2
    f.configuration.box = [10, 8, 0, 0, 0, 0]
    f.particles.N = 3
    f.particles.types = ["A", "B"]
    f.particles.typeid = [0, 1, third_type]
    f.particles.diameter = [1, 2, 2]
    f.particles.position = positions
    return f
mode = "wb" if gsd.__version__.startswith("2.") else "w"
with gsd.hoomd.open(name=sys.argv[0].replace("make.py", "py.gsd"), mode=mode) as t:
    t.append(frame(0, [[0, 0, 0], [1, 1, 0], [-2, 3, 0]], 1))
    t.append(frame(100, [[0.5, 0, 0], [1, 1.5, 0], [-2, 3, 0]], 1))
with gsd.hoomd.open(name=sys.argv[0].replace("make.py", "bad.gsd"), mode=mode) as t:
    t.append(frame(0, [[0, 0, 0], [1, 1, 0], [-2, 3, 0]], 5))
with gsd.hoomd.open(name=sys.argv[0].replace("make.py", "bad_walls.gsd"), mode=mode) as t:
    f = frame(0, [[0, 0, 0], [1, 1, 0], [-2, 3, 0]], 1)
    f.log["pedesis/periodic"] = [2, 1]
    t.append(f)
)PY";

TEST_F(GsdReaderTest, ReadsAFileOfTheGsdPythonPackageFillingInFromFrameZero) {
    ASSERT_EQ(run_python(gsd_python_writer, dir), 0);
    const GsdReader reader(dir / "py.gsd");
    ASSERT_EQ(reader.frames(), 2u);
    EXPECT_EQ(reader.schema(), "hoomd");
    // gsd.hoomd stores in frame 1 only what differs from frame 0
    EXPECT_FALSE(reader.has_chunk(1, "particles/typeid"));
    const GsdFrame f0 = reader.frame(0), f1 = reader.frame(1);
    EXPECT_EQ(f0.step, 0u);
    EXPECT_EQ(f1.step, 100u);
    for (const GsdFrame* f : {&f0, &f1}) {
        EXPECT_EQ(f->dimensions, 2);
        EXPECT_EQ(f->box, (std::array<double, 6>{10, 8, 0, 0, 0, 0}));
        EXPECT_EQ(f->types, (std::vector<std::string>{"A", "B"}));
        EXPECT_EQ(f->type_id, (std::vector<std::uint32_t>{0, 1, 1}));
        EXPECT_EQ(f->diameter, (std::vector<double>{1, 2, 2}));
        EXPECT_EQ(f->mass, (std::vector<double>{1, 1, 1})); // the schema's default
        EXPECT_FALSE(f->velocity_stored);
        EXPECT_FALSE(f->orientation_stored);
        EXPECT_FALSE(f->periodic); // HOOMD-blue's files do not say (its boxes are periodic)
    }
    EXPECT_EQ(f0.position[0], (std::array<double, 3>{0, 0, 0}));
    EXPECT_EQ(f1.position[0], (std::array<double, 3>{0.5, 0, 0}));
    EXPECT_EQ(f1.position[1], (std::array<double, 3>{1, 1.5, 0}));

    const std::string what = error_of(dir / "bad.gsd");
    EXPECT_NE(what.find((dir / "bad.gsd").string() + ": frame 0: particle 2 has typeid 5"),
              std::string::npos)
        << what;
    const std::string walls = error_of(dir / "bad_walls.gsd");
    EXPECT_NE(walls.find((dir / "bad_walls.gsd").string() +
                         ": frame 0: log/pedesis/periodic holds 2; each axis is 1 (periodic) "
                         "or 0 (walls)"),
              std::string::npos)
        << walls;
}

TEST_F(GsdReaderTest, TruncatedFilesAreRefusedNamingTheFile) {
    const fs::path file = dir / "t.gsd";
    {
        GsdWriter<2> w(file);
        w.append(sample_state<2>(1, 0).frame());
        w.append(sample_state<2>(2, 1).frame());
        w.commit();
    }
    const std::string bytes = read_bytes(file);
    for (std::size_t cut : {std::size_t{0}, std::size_t{100}, std::size_t{255}, std::size_t{300},
                            bytes.size() / 2, bytes.size() - 1}) {
        const fs::path cut_file = write_bytes("cut.gsd", bytes.substr(0, cut));
        const std::string what = error_of(cut_file);
        EXPECT_EQ(what.rfind(cut_file.string() + ": ", 0), 0u) << cut << ": " << what;
        EXPECT_TRUE(what.find("truncated") != std::string::npos ||
                    what.find("not a GSD file") != std::string::npos)
            << cut << ": " << what;
    }
}

TEST_F(GsdReaderTest, CorruptFilesAreRefusedNamingTheFile) {
    const fs::path file = dir / "t.gsd";
    {
        GsdWriter<2> w(file);
        w.append(sample_state<2>(1, 0).frame());
        w.commit();
    }
    const std::string bytes = read_bytes(file);
    // The first index entry lies right after the header and the 64-byte-aligned name list.
    const std::size_t index = 256 + 256;
    ASSERT_EQ(bytes[index + 16] != 0 || bytes[index + 17] != 0, true); // its location is set
    struct Case {
        std::string name;
        std::size_t offset;
        char value;
        std::string expected;
    };
    const std::vector<Case> cases = {
        {"magic", 0, 'X', "not a GSD file (wrong magic number)"},
        {"version", 46, 3, "GSD file layer version 3.0 is not supported"},
        {"type", index + 30, 42, "unknown data type"},
        {"name", index + 28, 99, "unknown chunk name"},
        {"size", index + 15, 0x7f, "lies beyond the end of the file"},
    };
    for (const Case& c : cases) {
        std::string corrupt = bytes;
        corrupt[c.offset] = c.value;
        const fs::path bad = write_bytes(c.name + ".gsd", corrupt);
        const std::string what = error_of(bad);
        EXPECT_EQ(what.rfind(bad.string() + ": ", 0), 0u) << c.name << ": " << what;
        EXPECT_NE(what.find(c.expected), std::string::npos) << c.name << ": " << what;
    }
    EXPECT_NE(error_of(dir / "missing.gsd").find("cannot open"), std::string::npos);
    EXPECT_NE(error_of(dir).find("not a regular file"), std::string::npos);
}

} // namespace
