// The VTK XML PolyData snapshot is parsed back here with a small XML reader of its
// own (not the writer's code): the element structure ParaView needs, array names and
// component counts, and values bit for bit in tag order from a shuffled store.
#include "pedesis/io/vtp_writer.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <map>
#include <memory>
#include <numeric>
#include <random>
#include <sstream>
#include <string>
#include <unistd.h>
#include <vector>

#include "support/soft_builder.hpp"

using namespace pedesis;
namespace fs = std::filesystem;

namespace {

struct Element {
    std::string name;
    std::map<std::string, std::string> attrs;
    std::string text;
    std::vector<std::unique_ptr<Element>> children;

    std::vector<const Element*> all(const std::string& child) const {
        std::vector<const Element*> out;
        for (const auto& c : children)
            if (c->name == child) out.push_back(c.get());
        return out;
    }
    const Element& one(const std::string& child) const {
        const auto found = all(child);
        if (found.size() != 1)
            throw std::runtime_error("<" + name + "> has " + std::to_string(found.size()) + " <" +
                                     child + "> children, expected 1");
        return *found.front();
    }
    std::string attr(const std::string& key) const {
        const auto it = attrs.find(key);
        if (it == attrs.end()) throw std::runtime_error("<" + name + "> lacks " + key);
        return it->second;
    }
};

// Enough XML for this file: a declaration, nested elements with double-quoted
// attributes, text. Any malformation (unclosed or mismatched tags) throws.
std::unique_ptr<Element> parse_xml(const std::string& doc) {
    auto root = std::make_unique<Element>();
    root->name = "#document";
    std::vector<Element*> stack{root.get()};
    std::size_t i = 0;
    while (i < doc.size()) {
        if (doc[i] != '<') {
            const std::size_t next = doc.find('<', i);
            stack.back()->text += doc.substr(i, next - i);
            i = next == std::string::npos ? doc.size() : next;
            continue;
        }
        if (doc.compare(i, 2, "<?") == 0) {
            i = doc.find("?>", i) + 2;
            continue;
        }
        const std::size_t close = doc.find('>', i);
        if (close == std::string::npos) throw std::runtime_error("unterminated tag");
        std::string tag = doc.substr(i + 1, close - i - 1);
        i = close + 1;
        if (tag[0] == '/') {
            if (stack.size() < 2 || stack.back()->name != tag.substr(1))
                throw std::runtime_error("mismatched </" + tag.substr(1) + ">");
            stack.pop_back();
            continue;
        }
        const bool empty = tag.back() == '/';
        if (empty) tag.pop_back();
        auto e = std::make_unique<Element>();
        std::size_t k = tag.find_first_of(" \t\n");
        e->name = tag.substr(0, k);
        while (k != std::string::npos && k < tag.size()) {
            k = tag.find_first_not_of(" \t\n", k);
            if (k == std::string::npos) break;
            const std::size_t eq = tag.find('=', k);
            if (eq == std::string::npos || tag[eq + 1] != '"')
                throw std::runtime_error("bad attribute in <" + e->name + ">");
            const std::size_t end = tag.find('"', eq + 2);
            e->attrs[tag.substr(k, eq - k)] = tag.substr(eq + 2, end - eq - 2);
            k = end + 1;
        }
        Element* raw = e.get();
        stack.back()->children.push_back(std::move(e));
        if (!empty) stack.push_back(raw);
    }
    if (stack.size() != 1) throw std::runtime_error("unclosed <" + stack.back()->name + ">");
    return root;
}

std::vector<double> numbers(const std::string& s) {
    std::istringstream in(s);
    std::vector<double> out;
    std::string tok;
    while (in >> tok) {
        char* end = nullptr;
        out.push_back(std::strtod(tok.c_str(), &end));
        EXPECT_EQ(*end, '\0') << "not a number: " << tok;
    }
    return out;
}

// Storage order deliberately differs from tag order; every quantity differs per particle.
template <int D> SoftState<D> shuffled_state(std::size_t n, unsigned seed) {
    SoftState<D> s;
    s.box = Box<D>(Vec<D>::filled(10.0), std::array<bool, D>{});
    s.p.species_table = {Species{"A", 0.5, 1.0}, Species{"Big", 4.0 / 3.0, 3.0 / 7.0}};
    s.resize(n);
    std::mt19937_64 gen(seed);
    std::uniform_real_distribution<double> u(-5.0, 5.0);
    std::vector<std::uint32_t> tags(n);
    std::iota(tags.begin(), tags.end(), 0u);
    std::shuffle(tags.begin(), tags.end(), gen);
    for (std::size_t i = 0; i < n; ++i) {
        for (int a = 0; a < D; ++a) {
            s.p.position[i][a] = u(gen);
            s.p.velocity[i][a] = u(gen) / 3.0;
            s.director[i][a] = u(gen) / 7.0;
            s.force[i][a] = u(gen) * 11.0;
        }
        s.p.tag[i] = tags[i];
        s.p.species[i] = static_cast<std::uint16_t>(tags[i] % 2 == 0 ? 1 : 0);
    }
    s.time = 12.375;
    return s;
}

// Component c of the tag-k particle, z = 0 in 2D.
template <int D> double component(const Vec<D>& v, int c) {
    return c < D ? v[c] : 0.0;
}

template <int D> void check_document(const std::string& doc, const SoftState<D>& s) {
    const auto root = parse_xml(doc);
    const Element& file = root->one("VTKFile");
    EXPECT_EQ(file.attr("type"), "PolyData");
    const Element& poly = file.one("PolyData");
    const Element& piece = poly.one("Piece");
    const std::size_t n = s.size();
    EXPECT_EQ(piece.attr("NumberOfPoints"), std::to_string(n));
    EXPECT_EQ(piece.attr("NumberOfVerts"), std::to_string(n));
    for (const char* none : {"NumberOfLines", "NumberOfStrips", "NumberOfPolys"})
        EXPECT_EQ(piece.attr(none), "0") << none;

    const auto time = poly.one("FieldData").all("DataArray");
    ASSERT_EQ(time.size(), 2u);
    EXPECT_EQ(time[0]->attr("Name"), "TimeValue");
    EXPECT_EQ(numbers(time[0]->text), std::vector<double>{s.time});
    // the frame's own box (a barostat changes it from frame to frame)
    EXPECT_EQ(time[1]->attr("Name"), "BoxLengths");
    std::vector<double> lengths(3, 0.0);
    for (int a = 0; a < D; ++a) lengths[static_cast<std::size_t>(a)] = s.box.length(a);
    EXPECT_EQ(numbers(time[1]->text), lengths);

    std::vector<std::uint32_t> storage(n);
    for (std::size_t i = 0; i < n; ++i) storage[s.p.tag[i]] = static_cast<std::uint32_t>(i);

    // Expected rows, built from the state by tag independently of the writer.
    struct Expected {
        std::string name, type;
        int components;
        std::vector<double> values;
    };
    std::vector<Expected> expected = {
        {"id", "Int32", 1, {}},         {"type", "Int32", 1, {}},
        {"radius", "Float64", 1, {}},   {"director", "Float64", 3, {}},
        {"velocity", "Float64", 3, {}}, {"mass", "Float64", 1, {}},
        {"force", "Float64", 3, {}}};
    std::vector<double> points;
    for (std::size_t tag = 0; tag < n; ++tag) {
        const std::size_t i = storage[tag];
        expected[0].values.push_back(static_cast<double>(tag));
        expected[1].values.push_back(s.p.species[i]);
        expected[2].values.push_back(s.p.species_table[s.p.species[i]].radius);
        expected[5].values.push_back(s.p.species_table[s.p.species[i]].mass);
        for (int c = 0; c < 3; ++c) {
            expected[3].values.push_back(component<D>(s.director[i], c));
            expected[4].values.push_back(component<D>(s.p.velocity[i], c));
            expected[6].values.push_back(component<D>(s.force[i], c));
            points.push_back(component<D>(s.p.position[i], c));
        }
    }

    const auto arrays = piece.one("PointData").all("DataArray");
    ASSERT_EQ(arrays.size(), expected.size());
    for (std::size_t k = 0; k < arrays.size(); ++k) {
        SCOPED_TRACE(expected[k].name);
        EXPECT_EQ(arrays[k]->attr("Name"), expected[k].name);
        EXPECT_EQ(arrays[k]->attr("type"), expected[k].type);
        EXPECT_EQ(arrays[k]->attr("format"), "ascii");
        EXPECT_EQ(arrays[k]->attr("NumberOfComponents"), std::to_string(expected[k].components));
        EXPECT_EQ(numbers(arrays[k]->text), expected[k].values);
    }

    const Element& p = piece.one("Points").one("DataArray");
    EXPECT_EQ(p.attr("NumberOfComponents"), "3");
    EXPECT_EQ(p.attr("format"), "ascii");
    EXPECT_EQ(numbers(p.text), points);

    // Every point is its own vertex cell: connectivity 0..n-1, end offsets 1..n.
    std::map<std::string, std::vector<double>> verts;
    for (const Element* a : piece.one("Verts").all("DataArray"))
        verts[a->attr("Name")] = numbers(a->text);
    std::vector<double> conn(n), offsets(n);
    std::iota(conn.begin(), conn.end(), 0.0);
    std::iota(offsets.begin(), offsets.end(), 1.0);
    EXPECT_EQ(verts["connectivity"], conn);
    EXPECT_EQ(verts["offsets"], offsets);
}

} // namespace

TEST(io_vtp, Document2DHasAllArraysInTagOrder) {
    const auto s = shuffled_state<2>(37, 1);
    check_document(vtp_document(s.frame()), s);
}

TEST(io_vtp, Document3DHasAllArraysInTagOrder) {
    const auto s = shuffled_state<3>(23, 2);
    check_document(vtp_document(s.frame()), s);
}

TEST(io_vtp, EmptySystemIsAValidDocument) {
    SoftState<2> s;
    s.box = Box<2>(Vec<2>::filled(4.0), {true, true});
    s.p.species_table = {Species{"A", 0.5, 1.0}};
    check_document(vtp_document(s.frame()), s);
}

TEST(io_vtp, StorageOrderDoesNotChangeTheDocument) {
    // Reordering storage (as the engines do) must not change the file.
    auto s = shuffled_state<3>(16, 3);
    const std::string before = vtp_document(s.frame());
    std::mt19937_64 gen(4);
    EXPECT_EQ(vtp_document(test::permuted_storage(s, gen).frame()), before);
}

TEST(io_vtp, WriteVtpWritesTheDocumentAtomically) {
    const fs::path dir =
        fs::temp_directory_path() / ("pedesis_io_vtp_" + std::to_string(::getpid()));
    fs::remove_all(dir);
    fs::create_directories(dir);
    const auto s = shuffled_state<2>(9, 5);
    const fs::path file = dir / "test_00010.vtp";
    write_vtp(file, s.frame());
    std::ifstream in(file, std::ios::binary);
    std::ostringstream text;
    text << in.rdbuf();
    EXPECT_EQ(text.str(), vtp_document(s.frame()));
    EXPECT_EQ(std::distance(fs::directory_iterator(dir), fs::directory_iterator{}), 1);
    fs::remove_all(dir);
}
