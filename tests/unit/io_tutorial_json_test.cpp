// The tutorial JSON layout: a write/read round trip is bit-exact, and every kind
// of bad input is an InputError that names the file and the particle and key.
#include "pedesis/core/error.hpp"
#include "pedesis/io/atomic_file.hpp"
#include "pedesis/io/tutorial_json.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <limits>
#include <numeric>
#include <random>
#include <string>
#include <unistd.h>
#include <vector>

#include "support/soft_builder.hpp"

namespace fs = std::filesystem;
using namespace pedesis;

namespace {

constexpr double inf = std::numeric_limits<double>::infinity();

class io_tutorial_json : public ::testing::Test {
  protected:
    void SetUp() override {
        const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
        dir = fs::temp_directory_path() /
              ("pedesis_io_json_" + std::string(info->name()) + "_" + std::to_string(::getpid()));
        fs::remove_all(dir);
        fs::create_directories(dir);
    }
    void TearDown() override { fs::remove_all(dir); }

    fs::path write(const std::string& name, const std::string& text) const {
        const fs::path p = dir / name;
        std::ofstream(p, std::ios::binary) << text;
        return p;
    }

    fs::path dir;
};

// Values that a decimal printer gets wrong unless it round-trips: thirds,
// subnormals, huge and tiny magnitudes, negative zero.
double awkward(std::mt19937_64& gen, std::size_t k) {
    static const double special[] = {1.0 / 3.0,
                                     -0.0,
                                     4.9406564584124654e-324,
                                     1e-300,
                                     0.1 + 0.2,
                                     -2.2250738585072014e-308,
                                     123456789.123456789};
    if (k % 5 == 0) return special[(k / 5) % std::size(special)];
    std::uniform_real_distribution<double> u(-10.0, 10.0);
    return u(gen);
}

template <int D> ParticleStore<D> shuffled_store(std::size_t n, unsigned seed) {
    ParticleStore<D> p;
    p.species_table = {Species{"A", 0.5, 1.0}, Species{"B", 0.7, 2.0 / 3.0},
                       Species{"wall", 1.5, inf}};
    p.resize(n);
    std::mt19937_64 gen(seed);
    std::vector<std::uint32_t> tags(n);
    std::iota(tags.begin(), tags.end(), 0u);
    std::shuffle(tags.begin(), tags.end(), gen);
    std::size_t k = 0;
    for (std::size_t i = 0; i < n; ++i) {
        for (int a = 0; a < D; ++a) {
            p.position[i][a] = awkward(gen, k++);
            p.velocity[i][a] = awkward(gen, k++);
        }
        p.tag[i] = tags[i];
        p.species[i] = static_cast<std::uint16_t>((i * 7) % 3);
    }
    return p;
}

std::uint64_t bits(double x) {
    return std::bit_cast<std::uint64_t>(x);
}

template <int D> void expect_round_trip(const fs::path& file) {
    const ParticleStore<D> p = shuffled_store<D>(40, 17 + D);
    Vec<D> L;
    for (int a = 0; a < D; ++a) L[a] = 10.0 + a / 3.0;
    const Box<D> box(L, {});
    write_file_atomically(
        file, [&](std::ostream& out) { out << to_tutorial_json(frame_of(p, box, 0.125)).dump(2); });

    const ParticleFile<D> f = read_tutorial_json<D>(file);
    ASSERT_TRUE(f.box.has_value());
    for (int a = 0; a < D; ++a) EXPECT_EQ(bits((*f.box)[a]), bits(L[a]));
    ASSERT_EQ(f.particles.size(), p.size());
    const auto index = p.index_of_tags();
    for (std::size_t k = 0; k < f.particles.size(); ++k) {
        const FileParticle<D>& q = f.particles[k];
        EXPECT_EQ(q.id, k) << "particles are written in tag order";
        const std::size_t i = index[q.id];
        ASSERT_TRUE(q.v.has_value());
        for (int a = 0; a < D; ++a) {
            EXPECT_EQ(bits(q.r[a]), bits(p.position[i][a])) << "tag " << k << " axis " << a;
            EXPECT_EQ(bits((*q.v)[a]), bits(p.velocity[i][a])) << "tag " << k << " axis " << a;
        }
        EXPECT_EQ(q.type, p.species[i]);
        EXPECT_EQ(q.radius, p.radius(i));
        EXPECT_EQ(q.mass, p.mass(i));
        EXPECT_FALSE(q.n.has_value());
    }
}

// Runs `read` expecting an InputError whose message contains the file name and
// each of `parts`.
template <class F>
void expect_input_error(F&& read, const fs::path& file, const std::vector<std::string>& parts) {
    try {
        read();
        ADD_FAILURE() << "expected InputError for " << file;
    } catch (const InputError& e) {
        const std::string what = e.what();
        EXPECT_NE(what.find(file.string()), std::string::npos) << what;
        for (const auto& part : parts)
            EXPECT_NE(what.find(part), std::string::npos) << "'" << part << "' not in: " << what;
    }
}

} // namespace

TEST_F(io_tutorial_json, RoundTripIsBitExactIn2D) {
    expect_round_trip<2>(dir / "c2.json");
}
TEST_F(io_tutorial_json, RoundTripIsBitExactIn3D) {
    expect_round_trip<3>(dir / "c3.json");
}

TEST_F(io_tutorial_json, DocumentLayout) {
    ParticleStore<2> p = shuffled_store<2>(3, 2);
    const nlohmann::json j = to_tutorial_json(frame_of(p, Box<2>({4.0, 5.0}, {true, false}), 2.5));
    const auto& s = j.at("system");
    EXPECT_EQ(s.at("time"), 2.5);
    EXPECT_EQ(s.at("box"), (nlohmann::json{{"Lx", 4.0}, {"Ly", 5.0}}));
    ASSERT_EQ(s.at("particles").size(), 3u);
    const auto index = p.index_of_tags();
    for (std::size_t k = 0; k < 3; ++k) {
        const auto& q = s.at("particles")[k];
        const std::size_t i = index[k];
        EXPECT_EQ(q.at("id"), k);
        EXPECT_EQ(q.at("type"), p.species[i]);
        EXPECT_EQ(q.at("r").size(), 2u);
        EXPECT_EQ(q.at("radius"), p.radius(i));
        if (std::isinf(p.mass(i)))
            EXPECT_EQ(q.at("mass"), "inf");
        else
            EXPECT_EQ(q.at("mass"), p.mass(i));
    }
}

TEST_F(io_tutorial_json, ReadsTheTutorialsOwnFilesAndOptionalKeys) {
    // As pymd's make_random writes it: id, r, n, v, f; no type, radius or mass.
    const fs::path file = write("tutorial.json", R"({
    "system": {
        "box": {"Lx": 20.0, "Ly": 10.0},
        "particles": [
            {"id": 5, "r": [1.5, -2.0], "n": [0.6, 0.8], "v": [0.0, 0.0], "f": [0.0, 0.0]},
            {"id": 2, "r": [3, 4]},
            {"id": 9, "r": [0.0, 0.0], "type": 1, "radius": 0.25, "mass": "inf"}
        ]
    }
})");
    const ParticleFile<2> f = read_tutorial_json<2>(file);
    ASSERT_TRUE(f.box.has_value());
    EXPECT_EQ((*f.box)[0], 20.0);
    EXPECT_EQ((*f.box)[1], 10.0);
    ASSERT_EQ(f.particles.size(), 3u);
    EXPECT_EQ(f.particles[0].id, 5u);
    EXPECT_EQ(f.particles[1].id, 2u);
    EXPECT_EQ(f.particles[2].id, 9u);
    EXPECT_EQ(f.particles[0].r, (Vec<2>{{1.5, -2.0}}));
    ASSERT_TRUE(f.particles[0].n.has_value());
    EXPECT_EQ(*f.particles[0].n, (Vec<2>{{0.6, 0.8}}));
    EXPECT_EQ(f.particles[1].r, (Vec<2>{{3.0, 4.0}}));
    EXPECT_FALSE(f.particles[1].v.has_value());
    EXPECT_FALSE(f.particles[1].radius.has_value());
    EXPECT_FALSE(f.particles[1].mass.has_value());
    EXPECT_EQ(f.particles[1].type, 0);
    EXPECT_EQ(f.particles[2].type, 1);
    EXPECT_EQ(f.particles[2].radius, 0.25);
    ASSERT_TRUE(f.particles[2].mass.has_value());
    EXPECT_TRUE(std::isinf(*f.particles[2].mass));
}

TEST_F(io_tutorial_json, BoxIsOptional) {
    const fs::path file =
        write("nobox.json", R"({"system": {"particles": [{"id": 0, "r": [1, 2, 3]}]}})");
    const ParticleFile<3> f = read_tutorial_json<3>(file);
    EXPECT_FALSE(f.box.has_value());
    ASSERT_EQ(f.particles.size(), 1u);
}

TEST_F(io_tutorial_json, MalformedJsonReportsLineAndColumn) {
    // Line 4: a trailing comma, so the parser fails on the '}' after it.
    const std::string text = "{\n"
                             "  \"system\": {\n"
                             "    \"particles\": [\n"
                             "      {\"id\": 0, \"r\": [1.0, 2.0],}\n"
                             "    ]\n"
                             "  }\n"
                             "}\n";
    // The offending "}" is at column 33 of line 4.
    const fs::path file = write("broken.json", text);
    try {
        read_tutorial_json<2>(file);
        FAIL() << "expected InputError";
    } catch (const InputError& e) {
        const std::string what = e.what();
        EXPECT_EQ(what.rfind(file.string() + ":4:33: ", 0), 0u) << what;
    }
}

TEST_F(io_tutorial_json, TruncatedJsonReportsTheEnd) {
    const fs::path file = write("cut.json", "{\"system\": {\n  \"particles\": [");
    try {
        read_tutorial_json<2>(file);
        FAIL() << "expected InputError";
    } catch (const InputError& e) {
        const std::string what = e.what();
        // End of input is just past the '[' at column 16 of line 2.
        EXPECT_EQ(what.rfind(file.string() + ":2:17: ", 0), 0u) << what;
    }
}

TEST_F(io_tutorial_json, MissingFileIsCannotOpen) {
    const fs::path file = dir / "absent.json";
    expect_input_error([&] { read_tutorial_json<2>(file); }, file, {"cannot open"});
}

struct BadCase {
    std::string name;
    std::string particles; // the "particles" array, or a whole document if it starts with '{'
    std::vector<std::string> parts;
};

TEST_F(io_tutorial_json, BadInputIn2DNamesFileParticleAndKey) {
    const std::vector<BadCase> cases = {
        {"no_system", R"({"System": {}})", {"\"system\"", "missing"}},
        {"system_not_object", R"({"system": [1, 2]})", {"\"system\""}},
        {"no_particles",
         R"({"system": {"box": {"Lx": 1, "Ly": 1}}})",
         {"\"particles\"", "missing"}},
        {"particles_not_array", R"({"system": {"particles": {"id": 0}}})", {"\"particles\""}},
        {"no_r",
         R"([{"id": 0, "r": [0, 0]}, {"id": 1, "v": [0, 0]}])",
         {"particle 1", "\"r\"", "missing"}},
        {"no_id", R"([{"r": [0, 0]}])", {"particle 0", "\"id\"", "missing"}},
        {"r_too_long",
         R"([{"id": 0, "r": [0, 0]}, {"id": 1, "r": [0, 0, 0]}])",
         {"particle 1", "\"r\"", "2"}},
        {"r_too_short", R"([{"id": 0, "r": [0]}])", {"particle 0", "\"r\""}},
        {"r_not_array", R"([{"id": 0, "r": 1.5}])", {"particle 0", "\"r\""}},
        {"v_wrong_length",
         R"([{"id": 3, "r": [0, 0], "v": [1, 2, 3]}])",
         {"particle 0", "id 3", "\"v\""}},
        {"n_wrong_length", R"([{"id": 0, "r": [0, 0], "n": [1]}])", {"particle 0", "\"n\""}},
        {"r_nan_string", R"([{"id": 0, "r": [0, "nan"]}])", {"particle 0", "\"r[1]\"", "finite"}},
        {"r_string", R"([{"id": 0, "r": ["1.0", 2]}])", {"particle 0", "\"r[0]\""}},
        {"r_null", R"([{"id": 0, "r": [null, 2]}])", {"particle 0", "\"r[0]\""}},
        {"radius_negative",
         R"([{"id": 0, "r": [0, 0], "radius": -0.5}])",
         {"particle 0", "\"radius\"", "positive"}},
        {"radius_zero", R"([{"id": 0, "r": [0, 0], "radius": 0}])", {"particle 0", "\"radius\""}},
        {"radius_string",
         R"([{"id": 0, "r": [0, 0], "radius": "inf"}])",
         {"particle 0", "\"radius\""}},
        {"mass_zero",
         R"([{"id": 0, "r": [0, 0], "mass": 0.0}])",
         {"particle 0", "\"mass\"", "positive"}},
        {"mass_negative", R"([{"id": 0, "r": [0, 0], "mass": -1}])", {"particle 0", "\"mass\""}},
        {"mass_nan", R"([{"id": 0, "r": [0, 0], "mass": "nan"}])", {"particle 0", "\"mass\""}},
        {"mass_minus_inf",
         R"([{"id": 0, "r": [0, 0], "mass": "-inf"}])",
         {"particle 0", "\"mass\""}},
        {"duplicate_id",
         R"([{"id": 4, "r": [0, 0]}, {"id": 1, "r": [0, 0]}, {"id": 4, "r": [1, 1]}])",
         {"particle 2", "\"id\"", "4", "particle 0"}},
        {"negative_id", R"([{"id": -1, "r": [0, 0]}])", {"particle 0", "\"id\""}},
        {"fractional_id", R"([{"id": 1.5, "r": [0, 0]}])", {"particle 0", "\"id\""}},
        {"huge_id", R"([{"id": 4294967296, "r": [0, 0]}])", {"particle 0", "\"id\""}},
        {"negative_type", R"([{"id": 0, "r": [0, 0], "type": -1}])", {"particle 0", "\"type\""}},
        {"particle_not_object", R"([{"id": 0, "r": [0, 0]}, 7])", {"particle 1"}},
        {"box_negative",
         R"({"system": {"box": {"Lx": -1, "Ly": 2}, "particles": []}})",
         {"box", "\"Lx\""}},
        {"box_missing_ly",
         R"({"system": {"box": {"Lx": 1}, "particles": []}})",
         {"box", "\"Ly\"", "missing"}},
        {"box_string",
         R"({"system": {"box": {"Lx": 1, "Ly": "2"}, "particles": []}})",
         {"box", "\"Ly\""}},
    };
    for (const BadCase& c : cases) {
        SCOPED_TRACE(c.name);
        const std::string doc =
            c.particles.front() == '{'
                ? c.particles
                : R"({"system": {"box": {"Lx": 5, "Ly": 5}, "particles": )" + c.particles + "}}";
        const fs::path file = write(c.name + ".json", doc);
        expect_input_error([&] { read_tutorial_json<2>(file); }, file, c.parts);
    }
}

TEST_F(io_tutorial_json, BadInputIn3DNamesFileParticleAndKey) {
    const std::vector<BadCase> cases = {
        {"r_2d_in_3d",
         R"({"system": {"particles": [{"id": 0, "r": [0, 0]}]}})",
         {"particle 0", "\"r\"", "3"}},
        {"box_missing_lz",
         R"({"system": {"box": {"Lx": 1, "Ly": 1}, "particles": []}})",
         {"box", "\"Lz\""}},
        {"v_inf_string",
         R"({"system": {"particles": [{"id": 0, "r": [0, 0, 0], "v": [0, "inf", 0]}]}})",
         {"particle 0", "\"v[1]\""}},
    };
    for (const BadCase& c : cases) {
        SCOPED_TRACE(c.name);
        const fs::path file = write(c.name + ".json", c.particles);
        expect_input_error([&] { read_tutorial_json<3>(file); }, file, c.parts);
    }
}

TEST_F(io_tutorial_json, NumberOverflowIsReportedWithItsPosition) {
    // Valid JSON syntax, but no double holds it; 1e999 starts at column 32 of line 2.
    const fs::path file = write("overflow.json", "{\"system\": {\"particles\": [\n"
                                                 "  {\"id\": 0, \"r\": [0, 0], \"v\": [1e999, 0]}\n"
                                                 "]}}\n");
    try {
        read_tutorial_json<2>(file);
        FAIL() << "expected InputError";
    } catch (const InputError& e) {
        const std::string what = e.what();
        EXPECT_EQ(what.rfind(file.string() + ":2:32: ", 0), 0u) << what;
        EXPECT_NE(what.find("1e999"), std::string::npos) << what;
    }
}

TEST_F(io_tutorial_json, PythonInfinityLiteralGetsAHint) {
    // What json.dump writes for float("inf"): not JSON.
    const fs::path file = write(
        "python.json", R"({"system": {"particles": [{"id": 0, "r": [0, 0], "mass": Infinity}]}})");
    expect_input_error([&] { read_tutorial_json<2>(file); }, file, {":1:58: ", "\"inf\""});
}

namespace {

// Storage index = tag; every per-particle vector differs, with awkward values.
template <int D> SoftState<D> soft_state_with_everything(std::size_t n, unsigned seed) {
    SoftState<D> s = test::random_soft_system<D>(n, 9.0, 1.0, seed, 1.0);
    s.p.species_table = {Species{"A", 1.0, 1.0}, Species{"B", 0.7, 2.0 / 3.0}};
    std::mt19937_64 gen(seed);
    std::size_t k = 0;
    for (std::size_t i = 0; i < n; ++i) {
        s.p.species[i] = static_cast<std::uint16_t>(i % 2);
        for (int a = 0; a < D; ++a) {
            s.p.velocity[i][a] = awkward(gen, k++);
            s.force[i][a] = awkward(gen, k++);
        }
    }
    s.time = 7.0 / 3.0;
    return s;
}

template <int D> void expect_soft_round_trip(const fs::path& file) {
    const SoftState<D> s = soft_state_with_everything<D>(30, 40 + D);
    std::mt19937_64 gen(D);
    const SoftState<D> shuffled = test::permuted_storage(s, gen);
    ASSERT_NE(shuffled.p.tag, s.p.tag) << "the test needs storage order != tag order";
    const nlohmann::json doc = to_tutorial_json(shuffled.frame());
    write_file_atomically(file, [&](std::ostream& out) { out << doc.dump(); });

    const ParticleFile<D> f = read_tutorial_json<D>(file);
    ASSERT_TRUE(f.box.has_value());
    for (int a = 0; a < D; ++a) EXPECT_EQ(bits((*f.box)[a]), bits(s.box.length(a)));
    ASSERT_EQ(f.particles.size(), s.size());
    const auto& written = doc.at("system").at("particles");
    for (std::size_t tag = 0; tag < f.particles.size(); ++tag) {
        SCOPED_TRACE("tag " + std::to_string(tag));
        const FileParticle<D>& q = f.particles[tag];
        EXPECT_EQ(q.id, tag) << "particles are written in tag order";
        ASSERT_TRUE(q.v.has_value());
        ASSERT_TRUE(q.n.has_value());
        EXPECT_EQ(q.type, s.p.species[tag]);
        EXPECT_EQ(q.radius, s.p.radius(tag));
        EXPECT_EQ(q.mass, s.p.mass(tag));
        // The reader has no use for "f"; it is checked in the document itself.
        const auto& force = written[tag].at("f");
        ASSERT_EQ(force.size(), static_cast<std::size_t>(D));
        for (int a = 0; a < D; ++a) {
            EXPECT_EQ(bits(q.r[a]), bits(s.p.position[tag][a])) << "axis " << a;
            EXPECT_EQ(bits((*q.v)[a]), bits(s.p.velocity[tag][a])) << "axis " << a;
            EXPECT_EQ(bits((*q.n)[a]), bits(s.director[tag][a])) << "axis " << a;
            EXPECT_EQ(bits(force[static_cast<std::size_t>(a)].get<double>()), bits(s.force[tag][a]))
                << "axis " << a;
        }
    }
}

} // namespace

TEST_F(io_tutorial_json, SoftStateRoundTripIsBitExactIn2D) {
    expect_soft_round_trip<2>(dir / "soft2.json");
}
TEST_F(io_tutorial_json, SoftStateRoundTripIsBitExactIn3D) {
    expect_soft_round_trip<3>(dir / "soft3.json");
}

TEST_F(io_tutorial_json, SoftStateDocumentIsTheStoreDocumentPlusDirectorAndForce) {
    const SoftState<2> s = soft_state_with_everything<2>(6, 9);
    std::mt19937_64 gen(1);
    const SoftState<2> shuffled = test::permuted_storage(s, gen);
    nlohmann::json soft = to_tutorial_json(shuffled.frame());
    for (auto& q : soft.at("system").at("particles")) {
        EXPECT_EQ(q.at("n").size(), 2u);
        EXPECT_EQ(q.at("f").size(), 2u);
        q.erase("n");
        q.erase("f");
    }
    EXPECT_EQ(soft, to_tutorial_json(frame_of(shuffled.p, shuffled.box, shuffled.time)));
}
