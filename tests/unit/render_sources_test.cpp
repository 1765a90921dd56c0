// Which file of a run directory render reads, and what each source adds from config.toml:
// GSD before XYZ before JSON snapshots, the ".part" file of an unfinished run, the time of
// GSD frames from dt, walls and species names for formats that do not store them, the
// scenery (containers, traps, gravity) the pictures draw, and clear errors for directories
// that hold nothing to render.
#include "pedesis/core/error.hpp"
#include "pedesis/io/gsd_writer.hpp"
#include "pedesis/io/tutorial_json.hpp"
#include "pedesis/io/xyz_writer.hpp"
#include "pedesis/render/run_directory.hpp"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <string>
#include <unistd.h>

#include "support/soft_builder.hpp"

using namespace pedesis;
using namespace pedesis::render;
namespace fs = std::filesystem;

namespace {

class RenderSources : public ::testing::Test {
  protected:
    void SetUp() override {
        const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
        dir = fs::temp_directory_path() / ("pedesis_render_sources_" + std::string(info->name()) +
                                           "_" + std::to_string(::getpid()));
        fs::remove_all(dir);
        fs::create_directories(dir / "snapshots");
    }
    void TearDown() override { fs::remove_all(dir); }

    void write(const fs::path& name, const std::string& text) {
        std::ofstream(dir / name, std::ios::binary) << text;
    }
    std::string error_of(const fs::path& run, SourceKind kind = SourceKind::automatic) {
        try {
            open_run_directory(run, kind);
        } catch (const InputError& e) {
            return e.what();
        }
        return "(no error)";
    }

    fs::path dir;
};

// Two species, the second written after the first in tag order.
SoftState<2> sample_state(std::uint64_t step) {
    SoftState<2> s = test::random_soft_system<2>(12, 10.0, 0.5, step + 1);
    s.p.species_table = {Species{"small", 0.5, 1.0}, Species{"big", 1.0, 2.0}};
    for (std::size_t i = 0; i < s.size(); ++i) {
        s.p.species[i] = static_cast<std::uint16_t>(s.p.tag[i] >= 8);
        s.p.velocity[i][0] = 0.5 * static_cast<double>(i);
    }
    s.step = step;
    s.time = 0.01 * static_cast<double>(step);
    return s;
}

void write_all_formats(const fs::path& dir, int frames) {
    GsdWriter<2> gsd(dir / "trajectory.gsd");
    std::string xyz;
    for (int k = 0; k < frames; ++k) {
        const SoftState<2> s = sample_state(static_cast<std::uint64_t>(10 * k));
        gsd.append(s.frame());
        xyz += xyz_frame(frame_of(s.p, s.box, s.time));
        char name[32];
        std::snprintf(name, sizeof name, "frame_%06d.json", k);
        std::ofstream(dir / "snapshots" / name) << to_tutorial_json(s.frame()).dump();
    }
    gsd.commit();
    std::ofstream(dir / "trajectory.xyz") << xyz;
}

TEST_F(RenderSources, PrefersGsdThenXyzThenJson) {
    write_all_formats(dir, 3);
    write("config.toml", "dimension = 2\n[run]\ndt = 0.01\n");
    auto run = open_run_directory(dir, SourceKind::automatic);
    EXPECT_NE(run.source->description().find("trajectory.gsd (GSD)"), std::string::npos);
    EXPECT_EQ(run.source->frames(), 3u);
    EXPECT_TRUE(run.notes.empty());

    fs::remove(dir / "trajectory.gsd");
    run = open_run_directory(dir, SourceKind::automatic);
    EXPECT_NE(run.source->description().find("trajectory.xyz (extended XYZ)"), std::string::npos);

    fs::remove(dir / "trajectory.xyz");
    run = open_run_directory(dir, SourceKind::automatic);
    EXPECT_NE(run.source->description().find("frame_*.json (tutorial JSON)"), std::string::npos);
    EXPECT_EQ(run.source->frames(), 3u);
}

TEST_F(RenderSources, EveryFormatGivesTheSameFrame) {
    write_all_formats(dir, 2);
    write("config.toml", "dimension = 2\n[box]\nboundary = [\"wall\", \"periodic\"]\n"
                         "[[species]]\nname = \"small\"\n[[species]]\nname = \"big\"\n"
                         "[run]\ndt = 0.01\n");
    const SoftState<2> s = sample_state(10);
    const auto index = s.p.index_of_tags();
    for (SourceKind kind : {SourceKind::gsd, SourceKind::xyz, SourceKind::json}) {
        const auto run = open_run_directory(dir, kind);
        const render::Frame f = run.source->frame(1);
        const double tolerance = kind == SourceKind::gsd ? 1e-5 : 0.0; // GSD stores float32
        EXPECT_EQ(f.dimension, 2);
        EXPECT_EQ(f.box_length[2], 0.0);
        ASSERT_TRUE(f.time.has_value());
        EXPECT_NEAR(*f.time, 0.1, 1e-15);
        EXPECT_EQ(f.species_names, (std::vector<std::string>{"small", "big"}));
        ASSERT_EQ(f.size(), s.size());
        for (std::size_t row = 0; row < f.size(); ++row) {
            const std::uint32_t i = index[row];
            EXPECT_EQ(f.species[row], s.p.species[i]);
            EXPECT_NEAR(f.radius[row], s.p.radius(i), tolerance);
            for (int a = 0; a < 2; ++a) {
                const auto c = static_cast<std::size_t>(a);
                EXPECT_NEAR(f.box_lo[c], -5.0, tolerance);
                EXPECT_NEAR(f.box_length[c], 10.0, tolerance);
                EXPECT_NEAR(f.position[row][c], s.p.position[i][a], tolerance);
                ASSERT_EQ(f.velocity.size(), f.size());
                EXPECT_NEAR(f.velocity[row][c], s.p.velocity[i][a], tolerance);
                if (kind != SourceKind::xyz) { // XYZ stores no director
                    ASSERT_EQ(f.director.size(), f.size());
                    EXPECT_NEAR(f.director[row][c], s.director[i][a], 1e-6);
                }
            }
        }
        // XYZ (pbc) and GSD (log/pedesis/periodic) store their own flags, all periodic
        // here, and a file's own word comes first; JSON takes config.toml's
        const bool wall_x = kind == SourceKind::json;
        EXPECT_EQ(f.periodic[0], !wall_x);
        EXPECT_TRUE(f.periodic[1]);
        if (kind == SourceKind::xyz) {
            EXPECT_TRUE(f.director.empty());
        }
    }
}

// Without a config (no dt) the time comes from the frame's log/time chunk.
TEST_F(RenderSources, GsdWithoutDtTakesTheTimeItLogged) {
    write_all_formats(dir, 2);
    const render::Frame f = open_run_directory(dir, SourceKind::gsd).source->frame(1);
    ASSERT_TRUE(f.time.has_value());
    EXPECT_EQ(*f.time, 0.1); // sample_state(10): 0.01 * 10
    ASSERT_TRUE(f.step.has_value());
    EXPECT_EQ(*f.step, 10u);
    EXPECT_EQ(f.species_names, (std::vector<std::string>{"small", "big"}));
}

// A walled GSD without a config beside it is drawn with its walls (log/pedesis/periodic).
TEST_F(RenderSources, GsdWithoutConfigDrawsTheWallsItStores) {
    SoftState<2> s = sample_state(0);
    s.box = Box<2>(s.box.lengths(), {false, true});
    {
        GsdWriter<2> gsd(dir / "trajectory.gsd");
        gsd.append(s.frame());
        gsd.commit();
    }
    const render::Frame f = open_run_directory(dir, SourceKind::gsd).source->frame(0);
    EXPECT_EQ(f.periodic, (std::array<bool, 3>{false, true, false}));
}

TEST_F(RenderSources, UnfinishedRunIsReadFromItsPartFileWithANote) {
    const SoftState<2> s = sample_state(0);
    const std::string frame = xyz_frame(frame_of(s.p, s.box, 0.0));
    write("trajectory.xyz.part", frame + frame + frame.substr(0, frame.size() / 3));
    const auto run = open_run_directory(dir, SourceKind::automatic);
    EXPECT_EQ(run.source->frames(), 2u);
    ASSERT_EQ(run.notes.size(), 1u);
    EXPECT_NE(run.notes[0].find("trajectory.xyz.part"), std::string::npos);
    EXPECT_NE(run.notes[0].find("unfinished run"), std::string::npos);
}

TEST_F(RenderSources, DirectoriesWithNothingToRenderAreRefused) {
    EXPECT_NE(error_of(dir / "missing").find("missing: no such run directory"), std::string::npos);
    write("file.txt", "x");
    EXPECT_NE(error_of(dir / "file.txt").find("not a directory"), std::string::npos);
    EXPECT_NE(error_of(dir).find("no trajectory to render"), std::string::npos);
    EXPECT_NE(error_of(dir, SourceKind::gsd).find("trajectory.gsd: not found (--source gsd)"),
              std::string::npos);
    EXPECT_NE(error_of(dir, SourceKind::json).find("no frame_NNNNNN.json"), std::string::npos);
    {
        GsdWriter<2> empty(dir / "trajectory.gsd");
        empty.commit();
    }
    EXPECT_NE(error_of(dir).find("trajectory.gsd (GSD): the trajectory has no frames"),
              std::string::npos)
        << error_of(dir);
}

TEST_F(RenderSources, ABrokenConfigOnlyLosesItsFacts) {
    write("config.toml", "dimension = 2\n[run\ndt = ");
    const RunFacts broken = read_run_facts(dir / "config.toml");
    EXPECT_FALSE(broken.dt);
    EXPECT_FALSE(broken.periodic);
    EXPECT_TRUE(broken.species_names.empty());

    write("config.toml", "dimension = 3\n[box]\nboundary = \"wall\"\n[run]\ndt = 0.5\n");
    const RunFacts facts = read_run_facts(dir / "config.toml");
    ASSERT_TRUE(facts.dt);
    EXPECT_EQ(*facts.dt, 0.5);
    ASSERT_TRUE(facts.periodic);
    EXPECT_EQ(*facts.periodic, (std::array<bool, 3>{false, false, false}));
}

// The scenery the pictures draw: containers, traps and gravity, each from its [[force]].
TEST_F(RenderSources, SceneryComesFromTheForceTables) {
    write("config.toml", R"(dimension = 2
[box]
boundary = ["wall", "periodic"]
[[force]]
name = "wall"
potential = "wca"
[[force]]
name = "wall"
potential = "harmonic"
shape = "sphere"
radius = 5
centre = [1.0, -2.5]
[[force]]
name = "wall"
potential = "lj93"
shape = "sphere"
radius = 3.5
centre = 2.0
[[force]]
name = "harmonic_trap"
k = 2.0
[[force]]
name = "harmonic_trap"
k = {A = 1.0, B = 0.5}
centre = [3, 4]
[[force]]
name = "harmonic_trap"
k = [1.0, 2.0]
centre = [-1, 0]
[[force]]
name = "gravity"
force = 0.5
[[force]]
name = "gravity"
axis = "x"
force = {A = 1.0, B = -2.0, C = 0.0}
[[force]]
name = "harmonic"
k = 10.0
)");
    const Scenery s = read_scenery(dir / "config.toml");
    ASSERT_EQ(s.containers.size(), 2u); // shape "planes" (the default): the box's own walls
    EXPECT_EQ(s.containers[0].shape, ContainerShape::sphere);
    EXPECT_EQ(s.containers[0].radius, 5.0);
    EXPECT_EQ(s.containers[0].centre, (Vec3{1.0, -2.5, 0.0}));
    EXPECT_EQ(s.containers[1].radius, 3.5);
    EXPECT_EQ(s.containers[1].centre, (Vec3{2.0, 2.0, 0.0})); // one number for every axis
    EXPECT_EQ(s.traps, (std::vector<Vec3>{{0, 0, 0}, {3, 4, 0}, {-1, 0, 0}}));
    // a positive force pulls along -axis (y, the last, by default); a negative one pushes
    EXPECT_EQ(s.pulls, (std::vector<Vec3>{{0, -1, 0}, {-1, 0, 0}, {1, 0, 0}}));

    write("config.toml", R"(dimension = 3
[[force]]
name = "wall"
shape = "cylinder"
axis = "x"
radius = 2.0
centre = [0, 1, 2]
[[force]]
name = "wall"
shape = "cylinder"
radius = 3.0
centre = -1.5
[[force]]
name = "gravity"
force = -1.0
)");
    const Scenery three = read_scenery(dir / "config.toml");
    ASSERT_EQ(three.containers.size(), 2u);
    EXPECT_EQ(three.containers[0].shape, ContainerShape::cylinder);
    EXPECT_EQ(three.containers[0].axis, 0);
    EXPECT_EQ(three.containers[0].centre, (Vec3{0, 1, 2}));
    EXPECT_EQ(three.containers[1].axis, 2); // the last axis by default
    EXPECT_EQ(three.containers[1].centre, (Vec3{-1.5, -1.5, -1.5}));
    EXPECT_EQ(three.pulls, (std::vector<Vec3>{{0, 0, 1}})); // along z, the last axis in 3D
}

// A value of the wrong kind drops its table alone (the run would refuse the config); a
// broken or hostile config gives no scenery and never an exception.
TEST_F(RenderSources, BadSceneryValuesAreLeftOut) {
    const std::string good_trap = "[[force]]\nname = \"harmonic_trap\"\nk = 1.0\ncentre = [7, 7]\n";
    std::string huge_list = "[";
    for (int k = 0; k < 100000; ++k) huge_list += "1.0, ";
    huge_list += "1.0]";
    const std::vector<std::string> bad = {
        "name = \"wall\"\nshape = \"sphere\"\nradius = -1.0",
        "name = \"wall\"\nshape = \"sphere\"\nradius = 0",
        "name = \"wall\"\nshape = \"sphere\"\nradius = nan",
        "name = \"wall\"\nshape = \"sphere\"\nradius = inf",
        "name = \"wall\"\nshape = \"sphere\"\nradius = \"5\"",
        "name = \"wall\"\nshape = \"sphere\"",
        "name = \"wall\"\nshape = \"cube\"\nradius = 5.0",
        "name = \"wall\"\nshape = 5\nradius = 5.0",
        "name = \"wall\"\nshape = \"sphere\"\nradius = 5.0\ncentre = [\"a\", 1.0]",
        "name = \"wall\"\nshape = \"sphere\"\nradius = 5.0\ncentre = [1.0, 2.0, 3.0]",
        "name = \"wall\"\nshape = \"sphere\"\nradius = 5.0\ncentre = [1.0, -nan]",
        "name = \"wall\"\nshape = \"sphere\"\nradius = 5.0\ncentre = " + huge_list,
        "name = \"wall\"\nshape = \"sphere\"\nradius = 5.0\ncentre = {x = 1.0, y = 2.0}",
        "name = \"wall\"\nshape = \"cylinder\"\nradius = 5.0",             // 3D only
        "name = \"wall\"\nshape = \"sphere\"\nradius = 5.0\naxis = \"z\"", // no z in 2D
        "name = \"wall\"\nshape = \"cylinder\"\nradius = 5.0\naxis = \"w\"",
        "name = \"wall\"\nshape = \"cylinder\"\nradius = 5.0\naxis = \"xy\"",
        "name = \"wall\"\nshape = \"cylinder\"\nradius = 5.0\naxis = 1",
        "name = \"harmonic_trap\"",
        "name = \"harmonic_trap\"\nk = \"1\"",
        "name = \"harmonic_trap\"\nk = nan",
        "name = \"harmonic_trap\"\nk = [1.0]",
        "name = \"harmonic_trap\"\nk = " + huge_list,
        "name = \"harmonic_trap\"\nk = {A = \"1\"}",
        "name = \"harmonic_trap\"\nk = {}",
        "name = \"harmonic_trap\"\nk = 1.0\ncentre = [inf, 0]",
        "name = \"harmonic_trap\"\nk = 1.0\ncentre = [[1.0], [2.0]]",
        "name = \"gravity\"",
        "name = \"gravity\"\nforce = \"down\"",
        "name = \"gravity\"\nforce = inf",
        "name = \"gravity\"\nforce = {A = 1.0, B = \"x\"}",
        "name = \"gravity\"\nforce = [1.0, 2.0]",
        "name = \"gravity\"\nforce = 1.0\naxis = \"z\"", // no z in 2D
        "name = \"gravity\"\nforce = 1.0\naxis = \"\"",
        "name = 5\nk = 1.0",
    };
    for (const std::string& table : bad) {
        write("config.toml", "dimension = 2\n[[force]]\n" + table + "\n" + good_trap);
        Scenery s;
        EXPECT_NO_THROW(s = read_scenery(dir / "config.toml")) << table.substr(0, 80);
        EXPECT_TRUE(s.containers.empty()) << table.substr(0, 80);
        EXPECT_TRUE(s.pulls.empty()) << table.substr(0, 80);
        // the good table beside it stands (only it: the bad one added nothing)
        EXPECT_EQ(s.traps, (std::vector<Vec3>{{7, 7, 0}})) << table.substr(0, 80);
    }

    for (const std::string& broken :
         {std::string("dimension = 2\n[[force]\nname = \"gravity\"\nforce = 1.0\n"),
          std::string("[[force]]\nname = \"harmonic_trap\"\nk = 1.0\ncentre = [1e400, 0]\n"),
          std::string("force = \"gravity\"\n"), std::string("force = [1, \"a\", {}]\n"),
          std::string("[force]\nname = \"gravity\"\nforce = 1.0\n"), std::string("\xff\xfe\x00")}) {
        write("config.toml", broken);
        Scenery s;
        EXPECT_NO_THROW(s = read_scenery(dir / "config.toml"));
        EXPECT_TRUE(s.empty()) << broken;
    }
    EXPECT_TRUE(read_scenery(dir / "no_such.toml").empty());
    fs::create_directories(dir / "a_directory.toml");
    EXPECT_TRUE(read_scenery(dir / "a_directory.toml").empty());

    // Thousands of traps: the first few are drawn.
    std::string many = "dimension = 2\n";
    for (int k = 0; k < 1000; ++k) many += good_trap;
    write("config.toml", many);
    EXPECT_EQ(read_scenery(dir / "config.toml").traps.size(), max_scenery_items);
}

// render reads the scenery with the trajectory, from the run directory's config.toml.
TEST_F(RenderSources, OpenedRunCarriesItsScenery) {
    write_all_formats(dir, 1);
    write("config.toml", "dimension = 2\n[[force]]\nname = \"gravity\"\nforce = 1.0\n");
    EXPECT_EQ(open_run_directory(dir, SourceKind::automatic).scenery.pulls,
              (std::vector<Vec3>{{0, -1, 0}}));
}

} // namespace
