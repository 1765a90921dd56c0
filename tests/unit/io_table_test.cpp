// The text table is read back here with a small parser of its own (not the writer's
// code): the two header lines, the documented columns, and every value bit for bit in
// tag order from a state whose storage order differs from the tag order.
#include "pedesis/io/table_writer.hpp"

#include <gtest/gtest.h>

#include <bit>
#include <charconv>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <random>
#include <sstream>
#include <string>
#include <unistd.h>
#include <vector>

#include "support/soft_builder.hpp"

using namespace pedesis;
namespace fs = std::filesystem;

namespace {

struct Table {
    std::vector<std::string> header;  // the '#' lines, '#' and one space stripped
    std::vector<std::string> columns; // the names of the last header line
    std::vector<std::vector<double>> rows;
};

std::vector<std::string> words(const std::string& line) {
    std::istringstream in(line);
    std::vector<std::string> out;
    std::string w;
    while (in >> w) out.push_back(w);
    return out;
}

// from_chars, unlike istream >> double, reads subnormals without failing.
double number(const std::string& w) {
    double x = 0.0;
    const auto [end, ec] = std::from_chars(w.data(), w.data() + w.size(), x);
    EXPECT_TRUE(ec == std::errc() && end == w.data() + w.size()) << "not a number: '" << w << "'";
    return x;
}

Table parse_table(const std::string& text) {
    Table t;
    std::istringstream in(text);
    std::string line;
    while (std::getline(in, line)) {
        if (line.starts_with("#")) {
            EXPECT_TRUE(t.rows.empty()) << "comment after the data: " << line;
            EXPECT_TRUE(line.starts_with("# ")) << line;
            t.header.push_back(line.substr(2));
            continue;
        }
        std::vector<double> row;
        for (const std::string& w : words(line)) row.push_back(number(w));
        t.rows.push_back(std::move(row));
    }
    if (!t.header.empty()) t.columns = words(t.header.back());
    return t;
}

std::uint64_t bits(double x) {
    return std::bit_cast<std::uint64_t>(x);
}

// Values a decimal printer gets wrong unless it round-trips.
double awkward(std::mt19937_64& gen, std::size_t k) {
    static const double special[] = {1.0 / 3.0,
                                     -0.0,
                                     4.9406564584124654e-324,
                                     1e-300,
                                     0.1 + 0.2,
                                     -2.2250738585072014e-308,
                                     123456789.123456789};
    if (k % 4 == 0) return special[(k / 4) % std::size(special)];
    std::uniform_real_distribution<double> u(-10.0, 10.0);
    return u(gen);
}

// Storage index = tag here; the permuted copy is what the writer gets.
template <int D> SoftState<D> state_with_everything(std::size_t n, std::uint64_t seed) {
    SoftState<D> s = test::random_soft_system<D>(n, 12.0, 1.0, seed, 1.0);
    std::mt19937_64 gen(seed);
    std::size_t k = 0;
    for (std::size_t i = 0; i < n; ++i)
        for (int a = 0; a < D; ++a) {
            s.p.velocity[i][a] = awkward(gen, k++);
            s.force[i][a] = awkward(gen, k++);
        }
    s.time = 0.1 * 3.0;
    s.step = 30;
    return s;
}

template <int D> std::vector<std::string> expected_columns() {
    if constexpr (D == 2)
        return {"id", "x", "y", "nx", "ny", "vx", "vy", "fx", "fy"};
    else
        return {"id", "x", "y", "z", "nx", "ny", "nz", "vx", "vy", "vz", "fx", "fy", "fz"};
}

template <int D> void check_table(std::size_t n, std::uint64_t seed) {
    const SoftState<D> s = state_with_everything<D>(n, seed);
    std::mt19937_64 gen(seed + 100);
    const SoftState<D> shuffled = test::permuted_storage(s, gen);
    ASSERT_NE(shuffled.p.tag, s.p.tag) << "the test needs storage order != tag order";

    const Table t = parse_table(table_frame(shuffled.frame()));
    ASSERT_EQ(t.header.size(), 2u);
    std::string first = "time=0.30000000000000004 step=30 Lx=12 Ly=12";
    if (D == 3) first += " Lz=12";
    EXPECT_EQ(t.header[0], first);
    EXPECT_EQ(t.columns, expected_columns<D>());

    ASSERT_EQ(t.rows.size(), n);
    for (std::size_t tag = 0; tag < n; ++tag) {
        SCOPED_TRACE("row " + std::to_string(tag));
        const std::vector<double>& row = t.rows[tag];
        ASSERT_EQ(row.size(), 1u + 4u * D);
        EXPECT_EQ(row[0], static_cast<double>(tag)) << "rows are in tag order";
        for (int a = 0; a < D; ++a) {
            EXPECT_EQ(bits(row[1 + a]), bits(s.p.position[tag][a]));
            EXPECT_EQ(bits(row[1 + D + a]), bits(s.director[tag][a]));
            EXPECT_EQ(bits(row[1 + 2 * D + a]), bits(s.p.velocity[tag][a]));
            EXPECT_EQ(bits(row[1 + 3 * D + a]), bits(s.force[tag][a]));
        }
    }
}

} // namespace

TEST(io_table, Table2DReadsBackExactlyInTagOrder) {
    check_table<2>(40, 3);
}

TEST(io_table, Table3DReadsBackExactlyInTagOrder) {
    check_table<3>(30, 4);
}

TEST(io_table, StorageOrderDoesNotChangeTheTable) {
    const auto s = state_with_everything<2>(25, 5);
    std::mt19937_64 gen(6);
    EXPECT_EQ(table_frame(test::permuted_storage(s, gen).frame()), table_frame(s.frame()));
}

TEST(io_table, EmptySystemHasOnlyTheHeader) {
    SoftState<3> s;
    s.box = Box<3>(Vec<3>{{4.0, 5.0, 6.5}}, {true, true, false});
    s.p.species_table = {Species{"A", 1.0, 1.0}};
    EXPECT_EQ(table_frame(s.frame()), "# time=0 step=0 Lx=4 Ly=5 Lz=6.5\n"
                                      "# id x y z nx ny nz vx vy vz fx fy fz\n");
}

TEST(io_table, WriteTableWritesTheFrameAtomically) {
    const fs::path dir =
        fs::temp_directory_path() / ("pedesis_io_table_" + std::to_string(::getpid()));
    fs::remove_all(dir);
    fs::create_directories(dir);
    const auto s = state_with_everything<2>(9, 7);
    const fs::path file = dir / "frame.dat";
    write_table(file, s.frame());
    std::ifstream in(file, std::ios::binary);
    std::ostringstream text;
    text << in.rdbuf();
    EXPECT_EQ(text.str(), table_frame(s.frame()));
    EXPECT_EQ(std::distance(fs::directory_iterator(dir), fs::directory_iterator{}), 1)
        << "no temporary file is left beside it";
    fs::remove_all(dir);
}
