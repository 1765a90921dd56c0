#include "pedesis/io/xyz_reader.hpp"

#include "pedesis/core/error.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cctype>
#include <charconv>
#include <cmath>
#include <fstream>
#include <limits>
#include <map>
#include <string_view>
#include <system_error>
#include <utility>

namespace pedesis {

namespace {

namespace fs = std::filesystem;

bool is_blank(char c) {
    return c == ' ' || c == '\t' || c == '\r';
}

std::string_view trimmed(std::string_view s) {
    while (!s.empty() && is_blank(s.front())) s.remove_prefix(1);
    while (!s.empty() && is_blank(s.back())) s.remove_suffix(1);
    return s;
}

std::vector<std::string_view> split_fields(std::string_view s) {
    std::vector<std::string_view> out;
    std::size_t i = 0;
    while (i < s.size()) {
        while (i < s.size() && is_blank(s[i])) ++i;
        const std::size_t start = i;
        while (i < s.size() && !is_blank(s[i])) ++i;
        if (i > start) out.push_back(s.substr(start, i - start));
    }
    return out;
}

std::string lowercase(std::string_view s) {
    std::string out(s);
    for (char& c : out) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
    return out;
}

std::optional<double> parse_double(std::string_view t) {
    // from_chars takes no leading '+', which other writers may put before exponents' mantissas
    if (!t.empty() && t.front() == '+') t.remove_prefix(1);
    double v = 0.0;
    const auto [end, ec] = std::from_chars(t.data(), t.data() + t.size(), v);
    if (ec != std::errc{} || end != t.data() + t.size() || t.empty()) return std::nullopt;
    return v;
}

template <class Int> std::optional<Int> parse_integer(std::string_view t) {
    if (!t.empty() && t.front() == '+') t.remove_prefix(1);
    Int v = 0;
    const auto [end, ec] = std::from_chars(t.data(), t.data() + t.size(), v);
    if (ec != std::errc{} || end != t.data() + t.size() || t.empty()) return std::nullopt;
    return v;
}

// Where a message points: "FILE: line L".
std::string at_line(const fs::path& path, std::uint64_t line) {
    return fmt::format("{}: line {}", path.string(), line);
}

// The comment line's key=value pairs (values may be "quoted"); keys compared without case,
// as ASE and OVITO do for the keys this reader knows.
std::map<std::string, std::string> comment_pairs(std::string_view s, const std::string& where) {
    std::map<std::string, std::string> pairs;
    std::size_t i = 0;
    while (i < s.size()) {
        while (i < s.size() && is_blank(s[i])) ++i;
        if (i == s.size()) break;
        const std::size_t key_start = i;
        while (i < s.size() && !is_blank(s[i]) && s[i] != '=') ++i;
        std::string key = lowercase(s.substr(key_start, i - key_start));
        if (i == s.size() || s[i] != '=') { // a bare flag: true, and nothing this reader uses
            pairs.insert_or_assign(std::move(key), std::string(1, 'T'));
            continue;
        }
        ++i;
        std::string value;
        if (i < s.size() && s[i] == '"') {
            ++i;
            bool closed = false;
            while (i < s.size()) {
                if (s[i] == '\\' && i + 1 < s.size()) {
                    value += s[i + 1];
                    i += 2;
                } else if (s[i] == '"') {
                    closed = true;
                    ++i;
                    break;
                } else {
                    value += s[i++];
                }
            }
            if (!closed)
                throw InputError(where + ": unterminated quote in the value of '" + key + "'");
        } else {
            const std::size_t value_start = i;
            while (i < s.size() && !is_blank(s[i])) ++i;
            value = std::string(s.substr(value_start, i - value_start));
        }
        pairs[key] = std::move(value);
    }
    return pairs;
}

struct Column {
    std::string name;
    char type = 'R';
    int count = 1;
    std::size_t first = 0; // index of its first field in a row
};

std::vector<Column> parse_properties(const std::string& text, const std::string& where) {
    std::vector<std::string_view> parts;
    std::string_view rest = text;
    while (true) {
        const std::size_t colon = rest.find(':');
        parts.push_back(rest.substr(0, colon));
        if (colon == std::string_view::npos) break;
        rest.remove_prefix(colon + 1);
    }
    if (parts.size() % 3 != 0)
        throw InputError(where + ": Properties=" + text + " is not a list of name:type:count");
    std::vector<Column> columns;
    std::size_t field = 0;
    for (std::size_t k = 0; k < parts.size(); k += 3) {
        Column c;
        c.name = std::string(parts[k]);
        const std::string type = lowercase(parts[k + 1]);
        const auto count = parse_integer<int>(parts[k + 2]);
        if (c.name.empty() || type.size() != 1 ||
            std::string_view("sril").find(type[0]) == std::string_view::npos)
            throw InputError(where + ": Properties=" + text + ": bad column '" +
                             std::string(parts[k]) + ":" + std::string(parts[k + 1]) + "'");
        if (!count || *count < 1 || *count > 1000)
            throw InputError(where + ": Properties=" + text + ": bad count for column '" + c.name +
                             "'");
        c.type = static_cast<char>(std::toupper(static_cast<unsigned char>(type[0])));
        c.count = *count;
        c.first = field;
        field += static_cast<std::size_t>(c.count);
        columns.push_back(std::move(c));
    }
    return columns;
}

const Column* find_column(const std::vector<Column>& columns, std::string_view name, char type,
                          int count, const std::string& where) {
    for (const Column& c : columns) {
        if (c.name != name) continue;
        if (c.type != type || c.count != count)
            throw InputError(fmt::format("{}: Properties column '{}' must be {}:{}, not {}:{}",
                                         where, name, type, count, c.type, c.count));
        return &c;
    }
    return nullptr;
}

std::array<bool, 3> parse_pbc(const std::string& text, const std::string& where) {
    const auto fields = split_fields(text);
    if (fields.size() != 3)
        throw InputError(where + ": pbc=\"" + text + "\" must be three of T and F");
    std::array<bool, 3> pbc{};
    for (int a = 0; a < 3; ++a) {
        const std::string f = lowercase(fields[static_cast<std::size_t>(a)]);
        if (f == "t" || f == "true" || f == "1")
            pbc[static_cast<std::size_t>(a)] = true;
        else if (f == "f" || f == "false" || f == "0")
            pbc[static_cast<std::size_t>(a)] = false;
        else
            throw InputError(where + ": pbc=\"" + text + "\" must be three of T and F");
    }
    return pbc;
}

std::vector<double> parse_numbers(const std::string& text, std::size_t n, const std::string& key,
                                  const std::string& where) {
    const auto fields = split_fields(text);
    std::vector<double> out;
    for (std::string_view f : fields) {
        const auto v = parse_double(f);
        if (!v || !std::isfinite(*v)) break;
        out.push_back(*v);
    }
    if (out.size() != n || fields.size() != n)
        throw InputError(
            fmt::format("{}: {}=\"{}\" must be {} finite numbers", where, key, text, n));
    return out;
}

} // namespace

XyzReader::XyzReader(fs::path path, bool allow_torn_tail) : path_(std::move(path)) {
    std::error_code ec;
    if (fs::is_directory(path_, ec))
        throw InputError(path_.string() + ": is a directory, not an XYZ file");
    std::ifstream in(path_, std::ios::binary);
    if (!in) throw InputError(path_.string() + ": cannot open");

    std::string line;
    std::uint64_t offset = 0, lineno = 0;
    std::optional<std::uint64_t> blank_since; // blank lines are allowed only at the very end
    while (true) {
        const std::uint64_t start = offset;
        if (!std::getline(in, line)) break;
        ++lineno;
        offset += line.size() + 1;
        const std::string_view count_text = trimmed(line);
        if (count_text.empty()) {
            if (!blank_since) blank_since = lineno;
            continue;
        }
        if (blank_since)
            throw InputError(at_line(path_, *blank_since) +
                             ": blank line where the particle count of a frame was expected");
        const auto count = parse_integer<std::uint64_t>(count_text);
        if (!count || *count > std::numeric_limits<std::uint32_t>::max())
            throw InputError(
                fmt::format("{}: expected the particle count of frame {}, found '{}' (not an "
                            "extended XYZ file, or a corrupt one)",
                            at_line(path_, lineno), starts_.size(), std::string(count_text)));

        // The comment line and one line per particle; only counted here.
        const std::uint64_t count_line = lineno;
        std::uint64_t got = 0;
        bool newline_at_end = true;
        while (got < *count + 1 && std::getline(in, line)) {
            ++got;
            ++lineno;
            offset += line.size() + 1;
            newline_at_end = !in.eof();
        }
        const bool complete = got == *count + 1;
        if (allow_torn_tail && (!complete || !newline_at_end)) {
            // A killed writer leaves at most one torn frame, at the end.
            dropped_torn_tail_ = true;
            break;
        }
        if (complete && !newline_at_end)
            throw InputError(at_line(path_, lineno) +
                             ": the file ends inside a line (a truncated file? complete files "
                             "end with a newline)");
        if (!complete)
            throw InputError(fmt::format(
                "{}: frame {} is cut short: the file ends after {} of its {} lines (a truncated "
                "file?)",
                at_line(path_, count_line), starts_.size(), got + 1, *count + 2));
        starts_.push_back({start, count_line, static_cast<std::size_t>(*count)});
    }
    if (in.bad()) throw InputError(path_.string() + ": read error");
    if (starts_.empty() && !dropped_torn_tail_)
        throw InputError(path_.string() + ": no frames (an empty XYZ file)");
}

XyzFrame XyzReader::frame(std::size_t k) const {
    if (k >= starts_.size())
        throw std::out_of_range(fmt::format("XyzReader::frame({}) of {}", k, starts_.size()));
    const FrameStart& s = starts_[k];
    std::ifstream in(path_, std::ios::binary);
    in.seekg(static_cast<std::streamoff>(s.offset));
    std::string line;
    std::uint64_t lineno = s.line;
    if (!in || !std::getline(in, line) || !std::getline(in, line))
        throw InputError(at_line(path_, lineno) +
                         ": cannot read the frame (was the file changed?)");
    ++lineno;
    const std::string where = at_line(path_, lineno);

    XyzFrame f;
    const auto pairs = comment_pairs(line, where);
    const auto lattice_it = pairs.find("lattice");
    if (lattice_it == pairs.end())
        throw InputError(where + ": the comment line has no Lattice (the cell is needed)");
    const auto cell = parse_numbers(lattice_it->second, 9, "Lattice", where);
    double largest = 0.0;
    for (double c : cell) largest = std::max(largest, std::abs(c));
    for (int r = 0; r < 3; ++r)
        for (int c = 0; c < 3; ++c) {
            const double v = cell[static_cast<std::size_t>(3 * r + c)];
            if (r == c && !(v > 0.0))
                throw InputError(where + ": Lattice=\"" + lattice_it->second +
                                 "\": the cell edges must be positive");
            if (r != c && std::abs(v) > 1e-12 * largest)
                throw InputError(where + ": Lattice=\"" + lattice_it->second +
                                 "\": only orthorhombic cells (diagonal lattices) are supported");
        }
    for (int a = 0; a < 3; ++a)
        f.lattice[static_cast<std::size_t>(a)] = cell[static_cast<std::size_t>(4 * a)];
    if (const auto it = pairs.find("origin"); it != pairs.end()) {
        const auto o = parse_numbers(it->second, 3, "Origin", where);
        std::copy(o.begin(), o.end(), f.origin.begin());
    }
    if (const auto it = pairs.find("pbc"); it != pairs.end()) {
        f.pbc = parse_pbc(it->second, where);
        f.pbc_stated = true;
    }
    if (const auto it = pairs.find("time"); it != pairs.end()) {
        const auto t = parse_double(it->second);
        if (!t || !std::isfinite(*t))
            throw InputError(where + ": Time=" + it->second + " is not a finite number");
        f.time = *t;
    }
    const auto props_it = pairs.find("properties");
    const std::vector<Column> columns = parse_properties(
        props_it != pairs.end() ? props_it->second : std::string("species:S:1:pos:R:3"), where);
    std::size_t width = 0;
    for (const Column& c : columns) width += static_cast<std::size_t>(c.count);
    const Column* species = find_column(columns, "species", 'S', 1, where);
    const Column* pos = find_column(columns, "pos", 'R', 3, where);
    const Column* velo = find_column(columns, "velo", 'R', 3, where);
    const Column* radius = find_column(columns, "radius", 'R', 1, where);
    const Column* mass = find_column(columns, "mass", 'R', 1, where);
    const Column* id = find_column(columns, "id", 'I', 1, where);
    if (!species || !pos)
        throw InputError(where + ": Properties must include species:S:1 and pos:R:3");
    // the other numeric columns, one number per particle each (XyzFrame::extra)
    std::vector<std::pair<const Column*, int>> extra_of;
    for (const Column& c : columns) {
        if (c.type == 'S' || c.type == 'L' || &c == species || &c == pos || &c == velo ||
            &c == radius || &c == mass || &c == id)
            continue;
        for (int k = 0; k < c.count; ++k) {
            std::string name = c.name;
            if (c.count > 1) {
                name.push_back('_');
                if (c.count == 3)
                    name.push_back("xyz"[k]);
                else
                    name.append(std::to_string(k));
            }
            extra_of.emplace_back(&c, k);
            f.extra.emplace_back(std::move(name), std::vector<double>{});
            f.extra.back().second.reserve(s.count);
        }
    }

    f.species.reserve(s.count);
    f.position.reserve(s.count);
    std::map<std::string, std::uint16_t, std::less<>> species_index;
    for (std::size_t row = 0; row < s.count; ++row) {
        if (!std::getline(in, line))
            throw InputError(at_line(path_, lineno + 1) +
                             ": cannot read the frame (was the file changed?)");
        ++lineno;
        const auto fields = split_fields(line);
        if (fields.size() != width)
            throw InputError(fmt::format(
                "{}: particle row {} of frame {} has {} fields; Properties gives {} (a corrupt "
                "or truncated line?)",
                at_line(path_, lineno), row, k, fields.size(), width));
        auto number = [&](const Column& c, int component, bool finite) {
            const std::string_view text = fields[c.first + static_cast<std::size_t>(component)];
            const auto v = parse_double(text);
            if (!v || std::isnan(*v) || (finite && !std::isfinite(*v)))
                throw InputError(fmt::format("{}: column '{}' holds '{}', not a {}number",
                                             at_line(path_, lineno), c.name, std::string(text),
                                             finite ? "finite " : ""));
            return *v;
        };
        auto vector3 = [&](const Column& c) {
            return std::array<double, 3>{number(c, 0, true), number(c, 1, true),
                                         number(c, 2, true)};
        };

        const std::string_view name = fields[species->first];
        auto it = species_index.find(name);
        if (it == species_index.end()) {
            if (f.species_names.size() > std::numeric_limits<std::uint16_t>::max())
                throw InputError(at_line(path_, lineno) + ": more than 65536 species names");
            it = species_index
                     .emplace(std::string(name), static_cast<std::uint16_t>(f.species_names.size()))
                     .first;
            f.species_names.emplace_back(name);
        }
        f.species.push_back(it->second);
        f.position.push_back(vector3(*pos));
        if (velo) f.velocity.push_back(vector3(*velo));
        if (radius) {
            const double r = number(*radius, 0, true);
            if (!(r > 0.0))
                throw InputError(
                    fmt::format("{}: radius {} must be positive", at_line(path_, lineno), r));
            f.radius.push_back(r);
        }
        if (mass) {
            const double m = number(*mass, 0, false);
            if (!(m > 0.0))
                throw InputError(fmt::format("{}: mass {} must be positive (or inf)",
                                             at_line(path_, lineno), m));
            f.mass.push_back(m);
        }
        for (std::size_t e = 0; e < extra_of.size(); ++e)
            f.extra[e].second.push_back(number(*extra_of[e].first, extra_of[e].second, false));
        if (id) {
            const std::string_view text = fields[id->first];
            const auto v = parse_integer<std::int64_t>(text);
            if (!v)
                throw InputError(fmt::format("{}: column 'id' holds '{}', not an integer",
                                             at_line(path_, lineno), std::string(text)));
            f.id.push_back(*v);
        }
    }
    return f;
}

} // namespace pedesis
