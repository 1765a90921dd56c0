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
#include <optional>
#include <stdexcept>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

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
    // Lees-Edwards shear: the image above is displaced along x by shear_offset
    if (box.sheared()) {
        box_json["shear_rate"] = box.shear_rate();
        box_json["shear_offset"] = box.shear_offset();
    }

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

// The file as it is read: opened (with the messages a missing file or a directory
// gets), and checked against the machine's memory before anything is parsed.
std::ifstream open_document(const fs::path& path) {
    const std::string name = path.string();
    std::error_code ec;
    if (fs::is_directory(path, ec)) throw InputError(name + ": is a directory, not a file");
    std::ifstream in(path, std::ios::binary);
    if (!in) throw InputError(name + ": cannot open");
    // the text is streamed and only the particles are kept (100-130 bytes each, up to
    // twice that while their vector grows): with the 140-210 bytes of text a particle
    // takes in the tutorial's layout, under 2 bytes per byte of text (measured: 0.7)
    const auto size = fs::file_size(path, ec);
    const double need = 2.0 * static_cast<double>(ec ? 0 : size);
    if (const double have = physical_memory_bytes(); have > 0.0 && need > have)
        throw InputError(fmt::format("{}: a JSON file of {:.3g} GB needs about {:.3g} GB to read "
                                     "(an estimate), more than this machine's {:.3g} GB of memory",
                                     name, static_cast<double>(size) / 1e9, need / 1e9,
                                     have / 1e9));
    return in;
}

// The line and column of the 1-based byte `byte` (nlohmann counts the characters read:
// size + 1 at the end of input), read again from the file: only a message needs them.
std::pair<std::size_t, std::size_t> line_and_column(const fs::path& path, std::size_t byte) {
    std::ifstream in(path, std::ios::binary);
    std::size_t line = 1, column = 1;
    char c = 0;
    for (std::size_t at = 1; at < byte && in.get(c); ++at) {
        if (c == '\n') {
            ++line;
            column = 1;
        } else {
            ++column;
        }
    }
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

std::string at_position(const fs::path& path, std::size_t byte) {
    if (byte == 0) return path.string();
    const auto [line, column] = line_and_column(path, byte);
    return path.string() + ":" + std::to_string(line) + ":" + std::to_string(column);
}

// Python's json module writes float("inf") and NaN as bare Infinity and NaN,
// which are not JSON; say so, since the parser's own message only shows "I".
std::string python_literal_hint(const fs::path& path, std::size_t byte) {
    if (byte == 0) return {};
    std::ifstream in(path, std::ios::binary);
    in.seekg(static_cast<std::streamoff>(byte - 1));
    std::string rest(8, '\0');
    in.read(rest.data(), static_cast<std::streamsize>(rest.size()));
    rest.resize(static_cast<std::size_t>(std::max<std::streamsize>(0, in.gcount())));
    if (!rest.starts_with("Infinity") && !rest.starts_with("NaN")) return {};
    return " (JSON has no Infinity or NaN; write the mass of a fixed obstacle as the string "
           "\"inf\")";
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

// The document read by nlohmann's SAX interface: a tree is built of everything except
// the elements of system.particles, each of which is built alone, turned into a
// FileParticle at once and dropped. The tree of a 10^6-particle file took ~1 KB per
// particle; this keeps the FileParticles (~100-130 bytes) and one particle's tree.
//
// The faults are the whole-tree reader's, in its order: a syntax error anywhere first,
// then the document's structure (system, box, particles), then the first particle in
// file order that is malformed or repeats an id. So a particle's fault is only recorded
// during the parse, and reading stops converting there.
template <int D> class StreamedDocument {
  public:
    explicit StreamedDocument(const std::string& file) : file_(file) {}

    // SAX events (nlohmann::json_sax)
    bool null() { return value(nullptr); }
    bool boolean(bool b) { return value(b); }
    bool number_integer(json::number_integer_t v) { return value(v); }
    bool number_unsigned(json::number_unsigned_t v) { return value(v); }
    bool number_float(json::number_float_t v, const json::string_t&) { return value(v); }
    bool string(json::string_t& v) { return value(std::move(v)); }
    bool binary(json::binary_t& v) { return value(std::move(v)); }
    bool start_object(std::size_t) {
        stack_.push_back(place(json::object()));
        keys_.emplace_back();
        return true;
    }
    bool key(json::string_t& k) {
        keys_.back() = k;
        slot_ = &(*stack_.back())[k];
        return true;
    }
    bool end_object() {
        stack_.pop_back();
        keys_.pop_back();
        return closed();
    }
    bool start_array(std::size_t) {
        // the array at system.particles (the document's, not one nested deeper): its
        // elements are streamed; a later "particles" or "system" replaces it, as the
        // tree's last key wins
        const bool particles = stack_.size() == 2 && keys_[0] == "system" &&
                               keys_[1] == "particles" && stack_[0]->is_object() &&
                               stack_[1]->is_object();
        stack_.push_back(place(json::array()));
        keys_.emplace_back();
        if (particles) {
            stream_depth_ = stack_.size();
            stream_ = stack_.back();
            particles_.clear();
            count_ = 0;
            fault_.reset();
        }
        return true;
    }
    bool end_array() {
        if (stack_.back() == stream_) stream_depth_ = 0; // (stream_ stays: the tree's array)
        stack_.pop_back();
        keys_.pop_back();
        return closed();
    }
    bool parse_error(std::size_t position, const std::string& token, const json::exception& e) {
        // a number too large for a double is reported after its last character
        const bool overflow = dynamic_cast<const json::out_of_range*>(&e) != nullptr;
        error_byte_ = overflow && position >= token.size() ? position - token.size() + 1 : position;
        error_ = e.what();
        syntax_ = dynamic_cast<const json::parse_error*>(&e) != nullptr;
        return false;
    }

    json root;
    std::size_t error_byte_ = 0;
    std::optional<std::string> error_;
    bool syntax_ = false;
    // the streamed array, in the tree (empty there), if any
    const json* stream_ = nullptr;
    std::vector<FileParticle<D>> particles_; // the particles before the first fault
    std::size_t count_ = 0;                  // elements of the array seen
    std::optional<std::pair<std::size_t, std::string>> fault_; // the first: index, message

  private:
    template <class V> bool value(V&& v) {
        place(json(std::forward<V>(v)));
        return closed();
    }

    // Where a new value goes: the root, the slot of the last key, the end of an array,
    // or, for an element of the streamed array, a tree of its own.
    json* place(json&& v) {
        if (stack_.empty()) {
            root = std::move(v);
            return &root;
        }
        if (stream_depth_ && stack_.size() == stream_depth_) {
            element_ = std::move(v);
            return &element_;
        }
        if (stack_.back()->is_array()) {
            stack_.back()->push_back(std::move(v));
            return &stack_.back()->back();
        }
        *slot_ = std::move(v);
        return slot_;
    }

    // After a value or container ends: a whole element of the streamed array is read.
    bool closed() {
        if (!stream_depth_ || stack_.size() != stream_depth_) return true;
        const std::size_t i = count_++;
        if (!fault_) try {
                particles_.push_back(read_particle<D>(element_, i, file_));
            } catch (const InputError& e) {
                fault_.emplace(i, e.what());
            }
        element_ = json();
        return true;
    }

    const std::string& file_;
    std::vector<json*> stack_;      // the open containers, outermost first
    std::vector<std::string> keys_; // the last key of each open container
    json* slot_ = nullptr;          // the value of the last key
    std::size_t stream_depth_ = 0;  // stack_ size inside the streamed array; 0: none
    json element_;                  // the element being read
};

// The first particle whose id an earlier one has: (its index, the earlier one's), or
// none. By sorting (id, index), 8 bytes a particle, where a hash map took ~50.
template <int D>
std::optional<std::pair<std::size_t, std::size_t>>
first_repeated_id(const std::vector<FileParticle<D>>& particles, const std::string& file) {
    // (more particles than 32-bit ids can number must repeat one, but say so plainly)
    if (particles.size() > 0xffffffffu)
        throw InputError(fmt::format("{}: {} particles, more than the 4294967295 pedesis can "
                                     "number",
                                     file, particles.size()));
    std::vector<std::uint64_t> keys(particles.size());
    for (std::size_t i = 0; i < particles.size(); ++i)
        keys[i] = (static_cast<std::uint64_t>(particles[i].id) << 32) | i;
    std::sort(keys.begin(), keys.end());
    std::optional<std::pair<std::size_t, std::size_t>> first;
    for (std::size_t k = 1; k < keys.size(); ++k) {
        const std::uint64_t id = keys[k] >> 32;
        // the second of an id (sorted, an id's indices are in order) is its first repeat
        if (id != keys[k - 1] >> 32 || (k >= 2 && keys[k - 2] >> 32 == id)) continue;
        const std::size_t repeat = keys[k] & 0xffffffffu, earlier = keys[k - 1] & 0xffffffffu;
        if (!first || repeat < first->first) first.emplace(repeat, earlier);
    }
    return first;
}

// The dimension of a tutorial JSON file, read only as far as needed: 3 when the box has
// "Lz" or the first particle's "r" three components, else 2; what cannot be told (a
// malformed file) is 2, and the reader then names the fault. nlohmann's SAX events;
// returning false stops the parse once the answer is known (pedesis writes the box
// first, so the first particle ends the scan).
class DimensionScan {
  public:
    int dimension() const { return lz_ || r_size_ == 3 ? 3 : 2; }

    bool null() { return value(); }
    bool boolean(bool) { return value(); }
    bool number_integer(json::number_integer_t) { return value(); }
    bool number_unsigned(json::number_unsigned_t) { return value(); }
    bool number_float(json::number_float_t, const json::string_t&) { return value(); }
    bool string(json::string_t&) { return value(); }
    bool binary(json::binary_t&) { return value(); }
    bool start_object(std::size_t) { return open(false); }
    bool start_array(std::size_t) { return open(true); }
    bool key(json::string_t& k) {
        frames_.back().key = k;
        lz_ = lz_ || (in_box() && k == "Lz");
        return !lz_; // 3, whatever else the file holds
    }
    bool end_object() { return close(); }
    bool end_array() { return close(); }
    bool parse_error(std::size_t, const std::string&, const json::exception&) { return false; }

  private:
    struct Frame {
        bool array = false;
        std::string key;       // of an object: its last key
        std::size_t index = 0; // of an array: the elements completed
    };

    // Inside system.box, or inside the first particle's "r".
    bool in_box() const {
        return frames_.size() == 3 && frames_[0].key == "system" && frames_[1].key == "box" &&
               !frames_[2].array;
    }
    bool in_first_r() const {
        return frames_.size() == 5 && frames_[0].key == "system" && frames_[1].key == "particles" &&
               frames_[2].array && frames_[2].index == 0 && !frames_[3].array &&
               frames_[3].key == "r" && frames_[4].array;
    }

    bool value() {
        if (in_first_r()) ++r_count_;
        return done();
    }
    bool open(bool array) {
        if (in_first_r()) ++r_count_; // (malformed, but an element; the reader says why)
        frames_.push_back(Frame{array, {}, 0});
        if (in_first_r()) r_count_ = 0; // (a later "particles" replaces an earlier one)
        return true;
    }
    bool close() {
        if (in_box()) box_seen_ = true;
        if (in_first_r()) r_size_ = r_count_;
        frames_.pop_back();
        return done();
    }
    // After a value or container: the next element of an array; false once known.
    bool done() {
        if (!frames_.empty() && frames_.back().array) ++frames_.back().index;
        return !(r_size_ == 3 || (r_size_ && box_seen_));
    }

    std::vector<Frame> frames_;
    bool lz_ = false, box_seen_ = false;
    std::size_t r_count_ = 0, r_size_ = 0;
};

} // namespace

template <int D> nlohmann::json to_tutorial_json(const Frame<D>& f) {
    json particles = json::array();
    for (std::uint32_t i : f.particles.index_of_tags()) {
        json q = particle_value(f.particles, i);
        if (f.box.sheared()) q["v"] = vec_value(f.lab_velocity(i));
        if (f.has_director()) q["n"] = vec_value(f.director(i));
        if (f.has_force()) q["f"] = vec_value(f.force(i));
        particles.push_back(std::move(q));
    }
    return document(f.box, f.time, std::move(particles));
}

template <int D> ParticleFile<D> read_tutorial_json(const fs::path& path) {
    enter_stage("reading a particle file");
    const std::string file = path.string();
    StreamedDocument<D> doc(file);
    {
        std::ifstream in = open_document(path);
        json::sax_parse(in, &doc);
        if (in.bad()) throw InputError(file + ": cannot read");
    }
    if (doc.error_)
        throw InputError(at_position(path, doc.error_byte_) + ": " + reason_of(*doc.error_) +
                         (doc.syntax_ ? python_literal_hint(path, doc.error_byte_) : ""));

    const Where top{file, ""};
    if (!doc.root.is_object()) top.fail("", "the document must be an object with a \"system\" key");
    const json* system = member(doc.root, "system");
    if (!system) top.fail("system", "is missing");
    if (!system->is_object()) top.fail("system", "must be an object, got " + shown(*system));

    ParticleFile<D> out;
    if (const json* box = member(*system, "box")) out.box = read_box<D>(*box, file);

    const Where sys{file, "system"};
    const json* particles = member(*system, "particles");
    if (!particles) sys.fail("particles", "is missing");
    if (!particles->is_array()) sys.fail("particles", "must be an array, got " + shown(*particles));
    if (particles != doc.stream_)
        throw std::logic_error("read_tutorial_json: system.particles was not the streamed array");

    // the first fault in file order: a malformed particle, or one that repeats an id
    // (only particles before a malformed one were kept)
    if (const auto repeat = first_repeated_id(doc.particles_, file))
        throw InputError(file + ": particle " + std::to_string(repeat->first) + ": \"id\" " +
                         std::to_string(doc.particles_[repeat->first].id) +
                         " is already used by particle " + std::to_string(repeat->second));
    if (doc.fault_) throw InputError(doc.fault_->second);
    out.particles = std::move(doc.particles_);
    return out;
}

int tutorial_json_dimension(const fs::path& path) {
    std::ifstream in(path, std::ios::binary);
    DimensionScan scan;
    json::sax_parse(in, &scan);
    return scan.dimension();
}

template nlohmann::json to_tutorial_json(const Frame<2>&);
template nlohmann::json to_tutorial_json(const Frame<3>&);
template ParticleFile<2> read_tutorial_json(const fs::path&);
template ParticleFile<3> read_tutorial_json(const fs::path&);

} // namespace pedesis
