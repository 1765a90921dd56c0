// The extended-XYZ frame is parsed back here independently of the writer: the
// header keys OVITO and ASE rely on, rows in tag order, values bit for bit.
#include "pedesis/core/error.hpp"
#include "pedesis/io/xyz_writer.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <limits>
#include <map>
#include <numeric>
#include <random>
#include <sstream>
#include <string>
#include <vector>

using namespace pedesis;

namespace {

constexpr double inf = std::numeric_limits<double>::infinity();

// Storage order deliberately differs from tag order.
template <int D> ParticleStore<D> shuffled_store(std::size_t n, unsigned seed) {
    ParticleStore<D> p;
    p.species_table = {Species{"A", 0.5, 1.0}, Species{"Big", 1.25, 3.0 / 7.0},
                       Species{"wall", 2.0, inf}};
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
        p.species[i] = static_cast<std::uint16_t>(i % 3);
    }
    return p;
}

// key=value and key="quoted value" pairs of the comment line.
std::map<std::string, std::string> header_pairs(const std::string& line) {
    std::map<std::string, std::string> kv;
    std::size_t i = 0;
    while (i < line.size()) {
        while (i < line.size() && line[i] == ' ') ++i;
        if (i >= line.size()) break;
        const std::size_t eq = line.find('=', i);
        if (eq == std::string::npos) {
            ADD_FAILURE() << "token without '=' in: " << line;
            break;
        }
        const std::string key = line.substr(i, eq - i);
        std::size_t end;
        std::string value;
        if (line[eq + 1] == '"') {
            end = line.find('"', eq + 2);
            value = line.substr(eq + 2, end - eq - 2);
            ++end;
        } else {
            end = line.find(' ', eq + 1);
            if (end == std::string::npos) end = line.size();
            value = line.substr(eq + 1, end - eq - 1);
        }
        kv[key] = value;
        i = end;
    }
    return kv;
}

std::vector<double> numbers(const std::string& s) {
    std::istringstream in(s);
    std::vector<double> out;
    std::string tok;
    while (in >> tok) out.push_back(std::strtod(tok.c_str(), nullptr));
    return out;
}

struct Row {
    std::string species;
    std::vector<double> values; // pos(3) velo(3) radius mass
    long id;
};

struct ParsedFrame {
    std::size_t n = 0;
    std::map<std::string, std::string> header;
    std::vector<Row> rows;
};

ParsedFrame parse_frame(const std::string& text) {
    std::istringstream in(text);
    ParsedFrame f;
    std::string line;
    std::getline(in, line);
    f.n = std::stoul(line);
    std::getline(in, line);
    f.header = header_pairs(line);
    while (std::getline(in, line)) {
        std::istringstream row(line);
        std::vector<std::string> tokens;
        std::string tok;
        while (row >> tok) tokens.push_back(tok);
        EXPECT_EQ(tokens.size(), 10u) << line; // species, 3 pos, 3 velo, radius, mass, id
        if (tokens.size() != 10u) continue;
        Row r{tokens[0], {}, std::stol(tokens[9])};
        // strtod reads "inf", as Python's float() does.
        for (int k = 1; k <= 8; ++k) r.values.push_back(std::strtod(tokens[k].c_str(), nullptr));
        f.rows.push_back(r);
    }
    return f;
}

} // namespace

TEST(io_xyz_writer, HeaderAndRowsIn3D) {
    const ParticleStore<3> p = shuffled_store<3>(17, 5);
    const Box<3> box({10.0, 12.5, 0.1 + 0.2}, {true, true, false});
    const double time = 1.0 / 3.0;
    const std::string text = xyz_frame(frame_of(p, box, time));
    ASSERT_EQ(text.back(), '\n');

    const ParsedFrame f = parse_frame(text);
    EXPECT_EQ(f.n, 17u);
    ASSERT_EQ(f.rows.size(), 17u);
    EXPECT_EQ(f.header.at("Properties"), "species:S:1:pos:R:3:velo:R:3:radius:R:1:mass:R:1:id:I:1");
    EXPECT_EQ(numbers(f.header.at("Lattice")),
              (std::vector<double>{10.0, 0, 0, 0, 12.5, 0, 0, 0, 0.1 + 0.2}));
    EXPECT_EQ(numbers(f.header.at("Origin")),
              (std::vector<double>{-5.0, -6.25, -0.5 * (0.1 + 0.2)}));
    EXPECT_EQ(f.header.at("pbc"), "T T F");
    EXPECT_EQ(std::strtod(f.header.at("Time").c_str(), nullptr), time);

    const auto index = p.index_of_tags();
    for (std::size_t k = 0; k < f.rows.size(); ++k) {
        const Row& r = f.rows[k];
        EXPECT_EQ(r.id, static_cast<long>(k)) << "rows must be in tag order";
        const std::size_t i = index[k];
        EXPECT_EQ(r.species, p.species_table[p.species[i]].name);
        for (int a = 0; a < 3; ++a) {
            EXPECT_EQ(r.values[a], p.position[i][a]) << "row " << k;
            EXPECT_EQ(r.values[3 + a], p.velocity[i][a]) << "row " << k;
        }
        EXPECT_EQ(r.values[6], p.radius(i));
        EXPECT_EQ(r.values[7], p.mass(i)); // inf == inf for the walls
    }
    // At least one fixed obstacle actually went through the "inf" path.
    EXPECT_NE(text.find(" inf "), std::string::npos);
}

TEST(io_xyz_writer, TwoDimensionalFrameHasFlatThirdAxis) {
    const ParticleStore<2> p = shuffled_store<2>(9, 11);
    const Box<2> box({7.0, 3.0}, {true, false});
    const ParsedFrame f = parse_frame(xyz_frame(frame_of(p, box, 2.5)));

    EXPECT_EQ(f.n, 9u);
    ASSERT_EQ(f.rows.size(), 9u);
    EXPECT_EQ(numbers(f.header.at("Lattice")), (std::vector<double>{7, 0, 0, 0, 3, 0, 0, 0, 1}));
    EXPECT_EQ(numbers(f.header.at("Origin")), (std::vector<double>{-3.5, -1.5, -0.5}));
    EXPECT_EQ(f.header.at("pbc"), "T F F");
    EXPECT_EQ(f.header.at("Time"), "2.5");

    const auto index = p.index_of_tags();
    for (std::size_t k = 0; k < f.rows.size(); ++k) {
        const Row& r = f.rows[k];
        const std::size_t i = index[k];
        EXPECT_EQ(r.id, static_cast<long>(k));
        EXPECT_EQ(r.values[0], p.position[i][0]);
        EXPECT_EQ(r.values[1], p.position[i][1]);
        EXPECT_EQ(r.values[2], 0.0);
        EXPECT_EQ(r.values[3], p.velocity[i][0]);
        EXPECT_EQ(r.values[4], p.velocity[i][1]);
        EXPECT_EQ(r.values[5], 0.0);
        EXPECT_EQ(r.values[7], p.mass(i));
    }
}

TEST(io_xyz_writer, FramesConcatenateIntoATrajectory) {
    const ParticleStore<2> p = shuffled_store<2>(4, 3);
    const Box<2> box({4.0, 4.0}, {true, true});
    const std::string two = xyz_frame(frame_of(p, box, 0.0)) + xyz_frame(frame_of(p, box, 1.0));
    std::istringstream in(two);
    std::string line;
    int lines = 0;
    while (std::getline(in, line)) ++lines;
    EXPECT_EQ(lines, 2 * (2 + 4));
}

TEST(io_xyz_writer, SpeciesNameWithSpaceIsRejected) {
    ParticleStore<2> p = shuffled_store<2>(3, 1);
    p.species_table[1].name = "big one";
    const Box<2> box({4.0, 4.0}, {true, true});
    try {
        (void)xyz_frame(frame_of(p, box, 0.0));
        FAIL() << "expected InputError";
    } catch (const InputError& e) {
        EXPECT_NE(std::string(e.what()).find("big one"), std::string::npos) << e.what();
    }
}
