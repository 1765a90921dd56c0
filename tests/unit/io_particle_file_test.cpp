// Starts from GSD and extended XYZ files (io/particle_file.hpp): pedesis' own trajectories
// read back as the state that was written (GSD to its single precision, XYZ to the
// digit), frames chosen from either end, the format told by the content, and the
// faults named. HOOMD-blue's files, written by the gsd package, are the CLI test's
// (tests/cli/cli_initial_gsd_xyz_test.cpp).
#include "pedesis/core/error.hpp"
#include "pedesis/io/gsd_writer.hpp"
#include "pedesis/io/particle_file.hpp"
#include "pedesis/io/xyz_writer.hpp"

#include <fmt/format.h>
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <random>
#include <string>

#include "support/soft_builder.hpp"

using namespace pedesis;
namespace fs = std::filesystem;

namespace {

class ParticleFileTest : public ::testing::Test {
  protected:
    void SetUp() override {
        dir = fs::temp_directory_path() /
              (std::string("pedesis_particle_file_") +
               ::testing::UnitTest::GetInstance()->current_test_info()->name());
        fs::remove_all(dir);
        fs::create_directories(dir);
    }
    void TearDown() override {
        if (!HasFailure()) fs::remove_all(dir);
    }
    fs::path write(const std::string& name, const std::string& text) {
        std::ofstream(dir / name) << text;
        return dir / name;
    }
    fs::path dir;
};

// Two species of other radii and masses, velocities, and storage in no tag order.
template <int D> SoftState<D> two_species_state(std::uint64_t seed) {
    SoftState<D> s = test::random_soft_system<D>(30, 12.0, 0.5, seed, 0.5);
    s.p.species_table = {Species{"big", 0.65, 1.5}, Species{"small", 0.35, 0.5}};
    std::mt19937_64 gen(seed);
    std::normal_distribution<double> normal;
    for (std::size_t i = 0; i < s.size(); ++i) {
        s.p.species[i] = static_cast<std::uint16_t>(i % 3 == 0);
        for (int a = 0; a < D; ++a) s.p.velocity[i][a] = normal(gen);
    }
    return test::permuted_storage(s, gen);
}

// `path` lies in the test's own directory: one shared name let the 2D and 3D tests,
// run side by side by ctest -j, overwrite each other's file.
template <int D> void expect_gsd_round_trip(const fs::path& path) {
    const SoftState<D> first = two_species_state<D>(1), last = two_species_state<D>(2);
    {
        GsdWriter<D> w(path);
        w.append(first.frame());
        w.append(last.frame());
        w.commit();
    }
    for (const auto& [frame, s] :
         {std::pair{std::optional<std::int64_t>{}, &last}, std::pair{std::optional{0l}, &first},
          std::pair{std::optional{-1l}, &last}, std::pair{std::optional{-2l}, &first}}) {
        const ParticleFile<D> f = read_particle_file<D>(path, frame);
        ASSERT_TRUE(f.box);
        for (int a = 0; a < D; ++a) EXPECT_EQ((*f.box)[a], 12.0);
        EXPECT_EQ(f.type_names, (std::vector<std::string>{"big", "small"}));
        EXPECT_EQ(f.default_radius, 0.5);
        ASSERT_EQ(f.particles.size(), s->size());
        for (std::size_t i = 0; i < s->size(); ++i) {
            const std::uint32_t tag = s->p.tag[i];
            const FileParticle<D>& p = f.particles[tag]; // written in tag order
            EXPECT_EQ(p.id, tag);
            EXPECT_EQ(p.type, s->p.species[i]);
            const Species& sp = s->p.species_table[s->p.species[i]];
            // single precision, as the schema stores them
            EXPECT_EQ(*p.radius, 0.5 * static_cast<float>(2.0 * sp.radius));
            EXPECT_EQ(*p.mass, static_cast<double>(static_cast<float>(sp.mass)));
            for (int a = 0; a < D; ++a) {
                EXPECT_EQ(p.r[a], static_cast<double>(static_cast<float>(s->p.position[i][a])));
                EXPECT_EQ((*p.v)[a], static_cast<double>(static_cast<float>(s->p.velocity[i][a])));
                EXPECT_NEAR((*p.n)[a], s->director[i][a], 1e-6);
            }
        }
    }
    EXPECT_EQ(particle_file_dimension(path), D);
    try {
        read_particle_file<D>(path, 2);
        ADD_FAILURE() << "frame 2 of 2 was read";
    } catch (const InputError& e) {
        EXPECT_NE(std::string(e.what()).find("[initial] frame = 2, but the file has 2 frame(s): "
                                             "0 to 1 (or -1 for the last, -2 for the first)"),
                  std::string::npos)
            << e.what();
    }
    // the other dimension is refused, naming both
    try {
        read_particle_file<5 - D>(path);
        ADD_FAILURE() << "a " << D << "D frame was read as " << 5 - D << "D";
    } catch (const InputError& e) {
        EXPECT_NE(std::string(e.what()).find(fmt::format("the frame is {}D", D)), std::string::npos)
            << e.what();
    }
    fs::remove(path);
}

TEST_F(ParticleFileTest, PedesisGsdFramesReadBackAsWritten2D) {
    expect_gsd_round_trip<2>(dir / "rt.gsd");
}

TEST_F(ParticleFileTest, PedesisGsdFramesReadBackAsWritten3D) {
    expect_gsd_round_trip<3>(dir / "rt.gsd");
}

template <int D> void expect_xyz_round_trip(const fs::path& path) {
    const SoftState<D> s = two_species_state<D>(3);
    std::ofstream(path) << xyz_frame(two_species_state<D>(4).frame()) << xyz_frame(s.frame());
    const ParticleFile<D> f = read_particle_file<D>(path);
    ASSERT_TRUE(f.box);
    for (int a = 0; a < D; ++a) EXPECT_EQ((*f.box)[a], 12.0);
    ASSERT_EQ(f.particles.size(), s.size());
    for (std::size_t k = 0; k < f.particles.size(); ++k) {
        const FileParticle<D>& p = f.particles[k];
        std::size_t i = 0; // the particle of that id
        while (s.p.tag[i] != p.id) ++i;
        EXPECT_EQ(f.type_names[static_cast<std::size_t>(p.type)],
                  s.p.species_table[s.p.species[i]].name);
        EXPECT_EQ(*p.radius, s.p.species_table[s.p.species[i]].radius);
        EXPECT_EQ(*p.mass, s.p.species_table[s.p.species[i]].mass);
        for (int a = 0; a < D; ++a) {
            EXPECT_EQ(p.r[a], s.p.position[i][a]); // the Origin is -L/2: centred as it was
            EXPECT_EQ((*p.v)[a], s.p.velocity[i][a]);
        }
        EXPECT_FALSE(p.n); // XYZ has no directors
    }
    EXPECT_EQ(particle_file_dimension(path), D);
}

TEST_F(ParticleFileTest, PedesisXyzFramesReadBackToTheDigit) {
    expect_xyz_round_trip<2>(dir / "t2.xyz");
    expect_xyz_round_trip<3>(dir / "t3.xyz");
}

// A walled box comes back walled from either format (GSD's log/pedesis/periodic, XYZ's
// pbc), and a file that does not say (HOOMD-blue's GSD, an XYZ without pbc) says nothing.
template <int D> void expect_walls_read_back(const fs::path& dir) {
    SoftState<D> s = two_species_state<D>(5);
    std::array<bool, D> periodic{};
    periodic.fill(true);
    periodic[D - 1] = false;
    s.box = Box<D>(s.box.lengths(), periodic);
    {
        GsdWriter<D> w(dir / "walled.gsd");
        w.append(s.frame());
        w.commit();
    }
    std::ofstream(dir / "walled.xyz") << xyz_frame(s.frame());
    for (const char* name : {"walled.gsd", "walled.xyz"}) {
        SCOPED_TRACE(name);
        const ParticleFile<D> f = read_particle_file<D>(dir / name);
        ASSERT_TRUE(f.periodic);
        EXPECT_EQ(*f.periodic, periodic);
    }
}

TEST_F(ParticleFileTest, WallsReadBackFromGsdAndXyz) {
    expect_walls_read_back<2>(dir);
    expect_walls_read_back<3>(dir);
    const fs::path silent =
        write("silent.xyz", "1\nLattice=\"10 0 0 0 20 0 0 0 30\" Properties=species:S:1:pos:R:3\n"
                            "X 0.5 1.5 29.5\n");
    EXPECT_FALSE(read_particle_file<3>(silent).periodic);
}

TEST_F(ParticleFileTest, XyzCellAtItsCornerIsCentred) {
    const fs::path path =
        write("corner.xyz", "2\nLattice=\"10 0 0 0 20 0 0 0 30\" Properties=species:S:1:pos:R:3 "
                            "pbc=\"T T T\"\nX 0.5 1.5 29.5\nY 9.75 10 0\n");
    const ParticleFile<3> f = read_particle_file<3>(path);
    EXPECT_EQ(f.type_names, (std::vector<std::string>{"X", "Y"}));
    EXPECT_EQ(f.default_radius, 0.5);
    EXPECT_EQ(f.particles[0].r, (Vec<3>{{-4.5, -8.5, 14.5}}));
    EXPECT_EQ(f.particles[1].r, (Vec<3>{{4.75, 0.0, -15.0}}));
    EXPECT_EQ(f.particles[1].id, 1u);
    EXPECT_EQ(f.particles[1].type, 1);
    EXPECT_FALSE(f.particles[0].v || f.particles[0].radius || f.particles[0].mass);
    EXPECT_EQ(particle_file_dimension(path), 3);
}

TEST_F(ParticleFileTest, A2DXyzStartLiesInOnePlane) {
    const std::string head = "2\nLattice=\"10 0 0 0 10 0 0 0 1\" Properties=species:S:1:pos:R:3:"
                             "velo:R:3 pbc=\"T T F\"\n";
    const fs::path flat = write("flat.xyz", head + "A 1 1 0.25 1 0 0\nA 2 2 0.25 0 1 0\n");
    EXPECT_EQ(particle_file_dimension(flat), 2);
    EXPECT_EQ(read_particle_file<2>(flat).particles[1].r, (Vec<2>{{-3.0, -3.0}}));
    const fs::path tilted = write("tilted.xyz", head + "A 1 1 0.25 1 0 0\nA 2 2 0.5 0 1 0\n");
    EXPECT_EQ(particle_file_dimension(tilted), 3);
    EXPECT_THROW(read_particle_file<2>(tilted), InputError);
    const fs::path moving = write("moving.xyz", head + "A 1 1 0 1 0 0\nA 2 2 0 0 1 0.5\n");
    try {
        read_particle_file<2>(moving);
        ADD_FAILURE() << "a velocity along z was dropped";
    } catch (const InputError& e) {
        EXPECT_NE(std::string(e.what()).find("moving.xyz: frame 0: particle 1: a velocity along z"),
                  std::string::npos)
            << e.what();
    }
}

TEST_F(ParticleFileTest, FormatIsToldByContent) {
    const fs::path json =
        write("start.xyz", "\n  {\"system\": {\"box\": {\"Lx\": 4, \"Ly\": 4}, \"particles\": "
                           "[{\"id\": 0, \"r\": [1, 1]}]}}");
    EXPECT_EQ(particle_file_format(json), ParticleFileFormat::tutorial_json);
    EXPECT_EQ(read_particle_file<2>(json).particles.size(), 1u);
    EXPECT_TRUE(read_particle_file<2>(json).type_names.empty());
    EXPECT_EQ(read_particle_file<2>(json).default_radius, 1.0);
    EXPECT_EQ(particle_file_dimension(json), 2);
    try {
        read_particle_file<2>(json, 0);
        ADD_FAILURE() << "a frame of a JSON file";
    } catch (const InputError& e) {
        EXPECT_NE(std::string(e.what()).find("is for GSD and XYZ files"), std::string::npos);
    }
    const fs::path xyz = write(
        "start.json", "1\nLattice=\"4 0 0 0 4 0 0 0 4\" Properties=species:S:1:pos:R:3\nA 1 1 1\n");
    EXPECT_EQ(particle_file_format(xyz), ParticleFileFormat::xyz);
    EXPECT_EQ(read_particle_file<3>(xyz).particles[0].r, (Vec<3>{{-1.0, -1.0, -1.0}}));
    // neither: the JSON reader names the fault
    const fs::path junk = write("junk", "hello");
    EXPECT_EQ(particle_file_format(junk), ParticleFileFormat::tutorial_json);
    EXPECT_THROW(read_particle_file<2>(junk), InputError);
    EXPECT_THROW(read_particle_file<2>(dir / "missing.gsd"), InputError);
    EXPECT_THROW(read_particle_file<2>(dir), InputError);
}

} // namespace
