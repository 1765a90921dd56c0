// The extended-XYZ reader against what xyz_frame writes (every value back bit for bit,
// rows in tag order, 2D and 3D, walls and periodic axes), against other tools' column
// layouts, and against truncated and corrupt files, which must be refused with a
// message naming the file and the line.
#include "pedesis/core/error.hpp"
#include "pedesis/io/xyz_reader.hpp"
#include "pedesis/io/xyz_writer.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <limits>
#include <numeric>
#include <random>
#include <string>
#include <unistd.h>

using namespace pedesis;
namespace fs = std::filesystem;

namespace {

constexpr double inf = std::numeric_limits<double>::infinity();

// Storage order deliberately differs from tag order, as a sorting engine leaves it.
template <int D> ParticleStore<D> shuffled_store(std::size_t n, unsigned seed) {
    ParticleStore<D> p;
    p.species_table = {Species{"A", 0.5, 1.0}, Species{"Big", 1.25, 3.0 / 7.0},
                       Species{"post", 2.0, inf}};
    p.resize(n);
    std::mt19937_64 gen(seed);
    std::uniform_real_distribution<double> u(-5.0, 5.0);
    std::vector<std::uint32_t> tags(n);
    std::iota(tags.begin(), tags.end(), 0u);
    std::shuffle(tags.begin(), tags.end(), gen);
    for (std::size_t i = 0; i < n; ++i) {
        for (int a = 0; a < D; ++a) {
            p.position[i][a] = u(gen);
            p.velocity[i][a] = u(gen) / 3.0;
        }
        p.tag[i] = tags[i];
        p.species[i] = static_cast<std::uint16_t>(tags[i] % 3);
    }
    return p;
}

class XyzReaderTest : public ::testing::Test {
  protected:
    void SetUp() override {
        const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
        dir = fs::temp_directory_path() / ("pedesis_xyz_reader_" + std::string(info->name()) + "_" +
                                           std::to_string(::getpid()));
        fs::remove_all(dir);
        fs::create_directories(dir);
    }
    void TearDown() override { fs::remove_all(dir); }

    fs::path write(const std::string& name, const std::string& text) {
        std::ofstream(dir / name, std::ios::binary) << text;
        return dir / name;
    }

    // The message of the InputError that reading frame `k` (or opening) throws.
    static std::string error_of(const fs::path& file, std::size_t k = 0) {
        try {
            XyzReader reader(file);
            reader.frame(k);
        } catch (const InputError& e) {
            return e.what();
        }
        return "(no error)";
    }

    fs::path dir;
};

template <int D>
void expect_round_trip(const ParticleStore<D>& p, const Box<D>& box, double time,
                       const XyzFrame& f) {
    const auto index = p.index_of_tags();
    ASSERT_EQ(f.size(), p.size());
    for (int a = 0; a < D; ++a) {
        EXPECT_EQ(f.lattice[static_cast<std::size_t>(a)], box.length(a));
        EXPECT_EQ(f.origin[static_cast<std::size_t>(a)], box.lo(a));
        EXPECT_EQ(f.pbc[static_cast<std::size_t>(a)], box.periodic(a));
    }
    if (D == 2) {
        EXPECT_EQ(f.lattice[2], 1.0);
        EXPECT_FALSE(f.pbc[2]);
    }
    ASSERT_TRUE(f.time.has_value());
    EXPECT_EQ(*f.time, time);
    ASSERT_EQ(f.velocity.size(), p.size());
    ASSERT_EQ(f.radius.size(), p.size());
    ASSERT_EQ(f.mass.size(), p.size());
    ASSERT_EQ(f.id.size(), p.size());
    for (std::size_t row = 0; row < f.size(); ++row) {
        const std::uint32_t i = index[row];
        const Species& s = p.species_table[p.species[i]];
        EXPECT_EQ(f.species_names.at(f.species[row]), s.name);
        EXPECT_EQ(f.id[row], static_cast<std::int64_t>(row));
        EXPECT_EQ(f.radius[row], s.radius);
        EXPECT_EQ(f.mass[row], s.mass); // inf for the post
        for (int a = 0; a < 3; ++a) {
            const auto c = static_cast<std::size_t>(a);
            EXPECT_EQ(f.position[row][c], a < D ? p.position[i][a] : 0.0);
            EXPECT_EQ(f.velocity[row][c], a < D ? p.velocity[i][a] : 0.0);
        }
    }
}

TEST_F(XyzReaderTest, ReadsBackWhatTheWriterWrites2D) {
    const auto p = shuffled_store<2>(40, 1);
    const Box<2> box(Vec<2>{{12.0, 10.5}}, {true, false});
    const auto file =
        write("t.xyz", xyz_frame(frame_of(p, box, 0.0)) + xyz_frame(frame_of(p, box, 2.5)));
    const XyzReader reader(file);
    ASSERT_EQ(reader.frames(), 2u);
    EXPECT_FALSE(reader.dropped_torn_tail());
    expect_round_trip(p, box, 0.0, reader.frame(0));
    expect_round_trip(p, box, 2.5, reader.frame(1));
    EXPECT_EQ(reader.frame(0).species_names, (std::vector<std::string>{"A", "Big", "post"}));
}

TEST_F(XyzReaderTest, ReadsBackWhatTheWriterWrites3DAnyFrameInAnyOrder) {
    const Box<3> box(Vec<3>{{8.0, 9.0, 10.0}}, {false, true, false});
    std::string text;
    std::vector<ParticleStore<3>> stores;
    for (unsigned k = 0; k < 5; ++k) {
        stores.push_back(shuffled_store<3>(25, 10 + k));
        text += xyz_frame(frame_of(stores.back(), box, 0.1 * k));
    }
    const XyzReader reader(write("t.xyz", text));
    ASSERT_EQ(reader.frames(), 5u);
    for (std::size_t k : {4u, 0u, 2u, 3u, 1u})
        expect_round_trip(stores[k], box, 0.1 * static_cast<double>(k), reader.frame(k));
}

TEST_F(XyzReaderTest, ReadsOtherColumnLayoutsAndDefaults) {
    // ASE/OVITO style: extra columns between the ones we use, no velocities, no pbc, no
    // Origin, CRLF line ends, a bare flag.
    const auto file = write("ase.xyz", "2\r\n"
                                       "Lattice=\"4 0 0 0 5 0 0 0 6\" "
                                       "Properties=species:S:1:charge:R:1:pos:R:3:tags:I:1 "
                                       "energy=-1.5 flagged\r\n"
                                       "Ar 0.5 1 2 3 7\r\n"
                                       "Ne -0.5 +1e-3 2.5e+0 3 8\r\n");
    const XyzReader reader(file);
    ASSERT_EQ(reader.frames(), 1u);
    const XyzFrame f = reader.frame(0);
    EXPECT_EQ(f.lattice, (std::array<double, 3>{4.0, 5.0, 6.0}));
    EXPECT_EQ(f.origin, (std::array<double, 3>{0.0, 0.0, 0.0}));
    EXPECT_EQ(f.pbc, (std::array<bool, 3>{true, true, true}));
    EXPECT_FALSE(f.time.has_value());
    EXPECT_EQ(f.species_names, (std::vector<std::string>{"Ar", "Ne"}));
    EXPECT_EQ(f.position[1], (std::array<double, 3>{1e-3, 2.5, 3.0}));
    EXPECT_TRUE(f.velocity.empty());
    EXPECT_TRUE(f.radius.empty());
    EXPECT_TRUE(f.id.empty());
    // the columns pedesis does not read itself, one number per particle each
    ASSERT_EQ(f.extra.size(), 2u);
    EXPECT_EQ(f.extra[0].first, "charge");
    EXPECT_EQ(f.extra[0].second, (std::vector<double>{0.5, -0.5}));
    EXPECT_EQ(f.extra[1].first, "tags");
    EXPECT_EQ(f.extra[1].second, (std::vector<double>{7.0, 8.0}));
}

// A wider column is split: name_x, _y, _z for three numbers, name_0, name_1, ... else;
// text and logical columns are not numbers to colour by; NaN is refused, inf kept.
TEST_F(XyzReaderTest, WideColumnsAreSplitAndNaNIsRefused) {
    const auto file = write("wide.xyz", "1\nLattice=\"4 0 0 0 5 0 0 0 6\" "
                                        "Properties=species:S:1:pos:R:3:forces:R:3:q:R:2:"
                                        "label:S:1:on:L:1:e:R:1\n"
                                        "Ar 0 0 0 1 2 3 4 5 x T inf\n");
    const XyzFrame f = XyzReader(file).frame(0);
    std::vector<std::string> names;
    for (const auto& [name, values] : f.extra) names.push_back(name);
    EXPECT_EQ(names,
              (std::vector<std::string>{"forces_x", "forces_y", "forces_z", "q_0", "q_1", "e"}));
    EXPECT_EQ(f.extra[2].second, (std::vector<double>{3.0}));
    EXPECT_EQ(f.extra[4].second, (std::vector<double>{5.0}));
    EXPECT_EQ(f.extra[5].second, (std::vector<double>{inf}));
    const auto bad = write("nan.xyz", "1\nLattice=\"4 0 0 0 5 0 0 0 6\" "
                                      "Properties=species:S:1:pos:R:3:e:R:1\nAr 0 0 0 nan\n");
    try {
        (void)XyzReader(bad).frame(0);
        ADD_FAILURE() << "NaN was accepted";
    } catch (const InputError& e) {
        EXPECT_NE(std::string(e.what()).find("nan.xyz: line 3: column 'e' holds 'nan'"),
                  std::string::npos)
            << e.what();
    }
}

TEST_F(XyzReaderTest, TruncatedFileIsRefusedNamingFileAndFrame) {
    const auto p = shuffled_store<2>(10, 2);
    const Box<2> box(Vec<2>{{12.0, 12.0}}, {false, false});
    const std::string one = xyz_frame(frame_of(p, box, 0.0));
    const std::string text = one + one;
    const auto file = write("cut.xyz", text.substr(0, text.size() - one.size() / 2));
    try {
        XyzReader reader(file);
        FAIL() << "a truncated file was accepted";
    } catch (const InputError& e) {
        const std::string what = e.what();
        EXPECT_NE(what.find(file.string()), std::string::npos) << what;
        EXPECT_NE(what.find("line 13"), std::string::npos) << what; // frame 1's count line
        EXPECT_NE(what.find("cut short"), std::string::npos) << what;
    }
    // Cut inside the last line: every line is there, the last one is not whole.
    const auto torn = write("torn.xyz", text.substr(0, text.size() - 7));
    try {
        XyzReader reader(torn);
        FAIL() << "a file ending inside a line was accepted";
    } catch (const InputError& e) {
        const std::string what = e.what();
        EXPECT_NE(what.find(torn.string() + ": line 24: the file ends inside a line"),
                  std::string::npos)
            << what;
    }
}

TEST_F(XyzReaderTest, PartFileOfAKilledRunDropsOnlyTheTornLastFrame) {
    const auto p = shuffled_store<2>(10, 3);
    const Box<2> box(Vec<2>{{12.0, 12.0}}, {false, false});
    const std::string one = xyz_frame(frame_of(p, box, 0.0));
    const std::string text = one + one + one;
    // Torn inside a line (no newline at the end) and torn at a line end.
    for (std::size_t cut : {text.size() - 7, text.size() - one.size() / 2}) {
        const auto file = write("t.xyz.part", text.substr(0, cut));
        const XyzReader reader(file, true);
        EXPECT_EQ(reader.frames(), 2u);
        EXPECT_TRUE(reader.dropped_torn_tail());
        expect_round_trip(p, box, 0.0, reader.frame(1));
    }
    const XyzReader whole(write("w.xyz.part", text), true);
    EXPECT_EQ(whole.frames(), 3u);
    EXPECT_FALSE(whole.dropped_torn_tail());
}

TEST_F(XyzReaderTest, CorruptFilesAreRefusedNamingFileAndLine) {
    const std::string header = "Lattice=\"4 0 0 0 4 0 0 0 1\" Origin=\"-2 -2 -0.5\" "
                               "Properties=species:S:1:pos:R:3:velo:R:3:radius:R:1:mass:R:1:"
                               "id:I:1 Time=0 pbc=\"T T F\"\n";
    const std::string good = "A 0 0 0 1 0 0 0.5 1 0\n";
    struct Case {
        std::string name, text, expected;
    };
    const std::vector<Case> cases = {
        {"empty", "", "no frames"},
        {"binary", std::string("\x89PNG\r\n\x1a\n", 8), "line 1: expected the particle count"},
        {"count", "two\n" + header + good + good, "line 1: expected the particle count"},
        {"number", "1\n" + header + "A 0 zero 0 1 0 0 0.5 1 0\n", "line 3: column 'pos'"},
        {"nan", "1\n" + header + "A 0 nan 0 1 0 0 0.5 1 0\n", "line 3: column 'pos'"},
        {"fields", "1\n" + header + "A 0 0 0 1 0 0 0.5 1\n", "line 3: particle row 0"},
        {"radius", "1\n" + header + "A 0 0 0 1 0 0 -0.5 1 0\n", "line 3: radius"},
        {"mass", "1\n" + header + "A 0 0 0 1 0 0 0.5 0 0\n", "line 3: mass"},
        {"id", "1\n" + header + "A 0 0 0 1 0 0 0.5 1 0.5\n", "line 3: column 'id'"},
        {"lattice", "1\nProperties=species:S:1:pos:R:3\nA 0 0 0\n",
         "line 2: the comment line has "
         "no Lattice"},
        {"tilted", "1\nLattice=\"4 1 0 0 4 0 0 0 4\"\nA 0 0 0\n", "orthorhombic"},
        {"pbc", "1\nLattice=\"4 0 0 0 4 0 0 0 4\" pbc=\"T X T\"\nA 0 0 0\n", "pbc"},
        {"quote", "1\nLattice=\"4 0 0 0 4 0 0 0 4\nA 0 0 0\n", "unterminated quote"},
        {"properties", "1\nLattice=\"4 0 0 0 4 0 0 0 4\" Properties=species:S:1:pos:R\nA 0 0 0\n",
         "not a list of name:type:count"},
        {"nopos", "1\nLattice=\"4 0 0 0 4 0 0 0 4\" Properties=species:S:1\nA\n",
         "must include species:S:1 and pos:R:3"},
        {"blank", "1\n" + header + good + "\n1\n" + header + good, "line 4: blank line"},
    };
    for (const Case& c : cases) {
        const auto file = write(c.name + ".xyz", c.text);
        const std::string what = error_of(file);
        EXPECT_NE(what.find(file.string()), std::string::npos) << c.name << ": " << what;
        EXPECT_NE(what.find(c.expected), std::string::npos) << c.name << ": " << what;
    }
    EXPECT_NE(error_of(dir).find("is a directory"), std::string::npos);
    EXPECT_NE(error_of(dir / "missing.xyz").find("cannot open"), std::string::npos);
}

} // namespace
