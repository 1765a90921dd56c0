#include "pedesis/io/tutorial_json.hpp"

#include "pedesis/core/error.hpp"
#include "pedesis/core/machine_memory.hpp"
#include "pedesis/core/stage.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <climits>
#include <cmath>
#include <fstream>
#include <iterator>
#include <limits>
#include <string>
#include <string_view>
#include <unordered_map>
#include <utility>

namespace pedesis {

namespace {

using nlohmann::json;
namespace fs = std::filesystem;

// ---- writing ----

// JSON has no infinity; the tutorial's convention for a fixed obstacle is the string.
json mass_value(double m) {
    return std::isinf(m) && m > 0 ? json("inf") : json(m);
}

template <int D> json vec_value(const Vec<D>& v) {
    json a = json::array();
    for (int k = 0; k < D; ++k) a.push_back(v[k]);
    return a;
}

template <int D> json particle_value(const ParticleStore<D>& p, std::uint32_t i) {
    json q = json::object();
    q["id"] = p.tag[i];
    q["type"] = p.species[i];
    q["r"] = vec_value(p.position[i]);
    q["v"] = vec_value(p.velocity[i]);
    q["radius"] = p.radius(i);
    q["mass"] = mass_value(p.mass(i));
    return q;
}

template <int D> json document(const Box<D>& box, double time, json particles) {
    static constexpr const char* names[] = {"Lx", "Ly", "Lz"};
    json box_json = json::object();
    for (int a = 0; a < D; ++a) box_json[names[a]] = box.length(a);

    json system = json::object();
    system["time"] = time;
    system["box"] = std::move(box_json);
    system["particles"] = std::move(particles);
    json doc = json::object();
    doc["system"] = std::move(system);
    return doc;
}

// ---- reading ----

// Where a value sits in the file, so that every message can point at it.
struct Where {
    const std::string& file;
    std::string at; // e.g. "particle 3 (id 7)" or "box"; empty at the top level

    [[noreturn]] void fail(const std::string& key, const std::string& message) const {
        std::string where = file + ": ";
        if (!at.empty()) where += at + ": ";
        if (!key.empty()) where += "\"" + key + "\" ";
        throw InputError(where + message);
    }
};

// Enough of the offending value to recognise it, not a whole sub-document.
std::string shown(const json& j) {
    std::string s = j.dump();
    if (s.size() > 40) s = s.substr(0, 37) + "...";
    return std::string(j.type_name()) + " " + s;
}

std::string read_text(const fs::path& path) {
    const std::string name = path.string();
    std::error_code ec;
    if (fs::is_directory(path, ec)) throw InputError(name + ": is a directory, not a file");
    std::ifstream in(path, std::ios::binary);
    if (!in) throw InputError(name + ": cannot open");
    // the text and nlohmann's tree of it are held at once: about 10 bytes per byte of text
    // (a particle's line of ~100 bytes becomes a dozen values of ~80 bytes each)
    const auto size = fs::file_size(path, ec);
    const double need = 10.0 * static_cast<double>(ec ? 0 : size);
    if (const double have = physical_memory_bytes(); have > 0.0 && need > have)
        throw InputError(fmt::format("{}: a JSON file of {:.3g} GB needs about {:.3g} GB to read "
                                     "(an estimate), more than this machine's {:.3g} GB of memory",
                                     name, static_cast<double>(size) / 1e9, need / 1e9,
                                     have / 1e9));
    std::string text{std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
    if (in.bad()) throw InputError(name + ": cannot read");
    return text;
}

// nlohmann reports the 1-based byte of the last character read (size + 1 at the
// end of input); editors want the line and column of that character.
std::pair<std::size_t, std::size_t> line_and_column(const std::string& text, std::size_t byte) {
    const std::size_t at = std::min(byte - 1, text.size());
    const std::size_t line =
        1 + static_cast<std::size_t>(
                std::count(text.begin(), text.begin() + static_cast<std::ptrdiff_t>(at), '\n'));
    const std::size_t last_newline = at == 0 ? std::string::npos : text.rfind('\n', at - 1);
    const std::size_t column = last_newline == std::string::npos ? at + 1 : at - last_newline;
    return {line, column};
}

// nlohmann's messages start "[json.exception.parse_error.101] parse error at line
// 4, column 9: "; the position is reported in the file:line:column form instead.
std::string reason_of(const std::string& what) {
    std::size_t start = 0;
    if (what.starts_with("[json.exception.")) {
        const std::size_t close = what.find("] ");
        if (close != std::string::npos) start = close + 2;
    }
    if (what.compare(start, 11, "parse error") == 0) {
        const std::size_t colon = what.find(": ", start);
        if (colon != std::string::npos) start = colon + 2;
    }
    return what.substr(start);
}

std::string at_position(const fs::path& path, const std::string& text, std::size_t byte) {
    if (byte == 0) return path.string();
    const auto [line, column] = line_and_column(text, byte);
    return path.string() + ":" + std::to_string(line) + ":" + std::to_string(column);
}

// A literal such as 1e999 is valid JSON syntax but overflows a double; nlohmann
// reports only the literal ("number overflow parsing '1e999'"), so locate it.
std::size_t byte_of_literal(const std::string& text, const std::string& what) {
    const std::size_t open = what.find(" parsing '");
    if (open == std::string::npos) return 0;
    const std::size_t begin = open + 10, close = what.find('\'', begin);
    if (close == std::string::npos) return 0;
    const std::size_t at = text.find(what.substr(begin, close - begin));
    return at == std::string::npos ? 0 : at + 1;
}

// Python's json module writes float("inf") and NaN as bare Infinity and NaN,
// which are not JSON; say so, since the parser's own message only shows "I".
std::string python_literal_hint(const std::string& text, std::size_t byte) {
    if (byte == 0 || byte > text.size()) return {};
    const std::string_view rest = std::string_view(text).substr(byte - 1);
    if (!rest.starts_with("Infinity") && !rest.starts_with("NaN")) return {};
    return " (JSON has no Infinity or NaN; write the mass of a fixed obstacle as the string "
           "\"inf\")";
}

json parse_document(const fs::path& path) {
    const std::string text = read_text(path);
    try {
        return json::parse(text);
    } catch (const json::parse_error& e) {
        throw InputError(at_position(path, text, e.byte) + ": " + reason_of(e.what()) +
                         python_literal_hint(text, e.byte));
    } catch (const json::exception& e) {
        throw InputError(at_position(path, text, byte_of_literal(text, e.what())) + ": " +
                         reason_of(e.what()));
    }
}

double finite_number(const json& j, const Where& w, const std::string& key) {
    // Strings such as "nan" or "inf" are the usual way NaN and infinity sneak into
    // JSON; they are not numbers here (mass "inf" is handled by its own reader).
    if (!j.is_number() || !std::isfinite(j.get<double>()))
        w.fail(key, "must be a finite number, got " + shown(j));
    return j.get<double>();
}

double positive_number(const json& j, const Where& w, const std::string& key) {
    const double x = finite_number(j, w, key);
    if (!(x > 0.0)) w.fail(key, "must be positive, got " + shown(j));
    return x;
}

double mass_number(const json& j, const Where& w, const std::string& key) {
    if (j.is_string() && j.get<std::string>() == "inf")
        return std::numeric_limits<double>::infinity();
    if (!j.is_number())
        w.fail(key, "must be a positive number or \"inf\" (fixed obstacle), got " + shown(j));
    return positive_number(j, w, key);
}

std::uint64_t non_negative_integer(const json& j, const Where& w, const std::string& key,
                                   std::uint64_t max) {
    if (!j.is_number_unsigned() || j.get<std::uint64_t>() > max)
        w.fail(key, "must be an integer in [0, " + std::to_string(max) + "], got " + shown(j));
    return j.get<std::uint64_t>();
}

template <int D> Vec<D> vector_value(const json& j, const Where& w, const std::string& key) {
    if (!j.is_array() || j.size() != static_cast<std::size_t>(D))
        w.fail(key, "must be an array of " + std::to_string(D) + " numbers (a " +
                        std::to_string(D) + "D system), got " + shown(j));
    Vec<D> v;
    for (int k = 0; k < D; ++k)
        v[k] =
            finite_number(j[static_cast<std::size_t>(k)], w, key + "[" + std::to_string(k) + "]");
    return v;
}

const json* member(const json& object, const std::string& key) {
    const auto it = object.find(key);
    return it == object.end() ? nullptr : &*it;
}

template <int D> Vec<D> read_box(const json& j, const std::string& file) {
    const Where w{file, "box"};
    if (!j.is_object())
        w.fail("", "must be an object with Lx, Ly" + std::string(D == 3 ? ", Lz" : "") + ", got " +
                       shown(j));
    static constexpr const char* names[] = {"Lx", "Ly", "Lz"};
    Vec<D> L;
    for (int a = 0; a < D; ++a) {
        const json* v = member(j, names[a]);
        if (!v) w.fail(names[a], "is missing");
        L[a] = positive_number(*v, w, names[a]);
    }
    // a 3D box given to a 2D run is a mistake, not a detail to drop
    if (D == 2 && member(j, "Lz"))
        w.fail("Lz", "is given, but this run is 2D (dimension = 2): remove it or run in 3D");
    return L;
}

template <int D>
FileParticle<D> read_particle(const json& j, std::size_t index, const std::string& file) {
    Where w{file, "particle " + std::to_string(index)};
    if (!j.is_object()) w.fail("", "must be an object, got " + shown(j));

    FileParticle<D> p;
    const json* id = member(j, "id");
    if (!id) w.fail("id", "is missing");
    p.id = static_cast<std::uint32_t>(
        non_negative_integer(*id, w, "id", std::numeric_limits<std::uint32_t>::max()));
    w.at += " (id " + std::to_string(p.id) + ")";

    const json* r = member(j, "r");
    if (!r) w.fail("r", "(position) is missing");
    p.r = vector_value<D>(*r, w, "r");
    if (const json* v = member(j, "v")) p.v = vector_value<D>(*v, w, "v");
    if (const json* n = member(j, "n")) p.n = vector_value<D>(*n, w, "n");
    if (const json* t = member(j, "type"))
        p.type = static_cast<int>(non_negative_integer(*t, w, "type", INT_MAX));
    if (const json* a = member(j, "radius")) p.radius = positive_number(*a, w, "radius");
    if (const json* m = member(j, "mass")) p.mass = mass_number(*m, w, "mass");
    return p;
}

} // namespace

template <int D> nlohmann::json to_tutorial_json(const Frame<D>& f) {
    json particles = json::array();
    for (std::uint32_t i : f.particles.index_of_tags()) {
        json q = particle_value(f.particles, i);
        if (f.has_director()) q["n"] = vec_value(f.director(i));
        if (f.has_force()) q["f"] = vec_value(f.force(i));
        particles.push_back(std::move(q));
    }
    return document(f.box, f.time, std::move(particles));
}

template <int D> ParticleFile<D> read_tutorial_json(const fs::path& path) {
    enter_stage("reading a particle file");
    const std::string file = path.string();
    const json doc = parse_document(path);
    const Where top{file, ""};
    if (!doc.is_object()) top.fail("", "the document must be an object with a \"system\" key");
    const json* system = member(doc, "system");
    if (!system) top.fail("system", "is missing");
    if (!system->is_object()) top.fail("system", "must be an object, got " + shown(*system));

    ParticleFile<D> out;
    if (const json* box = member(*system, "box")) out.box = read_box<D>(*box, file);

    const Where sys{file, "system"};
    const json* particles = member(*system, "particles");
    if (!particles) sys.fail("particles", "is missing");
    if (!particles->is_array()) sys.fail("particles", "must be an array, got " + shown(*particles));

    out.particles.reserve(particles->size());
    std::unordered_map<std::uint32_t, std::size_t> first_with_id;
    for (std::size_t i = 0; i < particles->size(); ++i) {
        FileParticle<D> p = read_particle<D>((*particles)[i], i, file);
        const auto [it, fresh] = first_with_id.emplace(p.id, i);
        if (!fresh)
            throw InputError(file + ": particle " + std::to_string(i) + ": \"id\" " +
                             std::to_string(p.id) + " is already used by particle " +
                             std::to_string(it->second));
        out.particles.push_back(std::move(p));
    }
    return out;
}

template nlohmann::json to_tutorial_json(const Frame<2>&);
template nlohmann::json to_tutorial_json(const Frame<3>&);
template ParticleFile<2> read_tutorial_json(const fs::path&);
template ParticleFile<3> read_tutorial_json(const fs::path&);

} // namespace pedesis
