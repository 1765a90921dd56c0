#include "pedesis/io/gsd_reader.hpp"

#include "pedesis/core/error.hpp"
#include "pedesis/io/atomic_file.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <bit>
#include <cerrno>
#include <cmath>
#include <cstring>
#include <fcntl.h>
#include <limits>
#include <stdexcept>
#include <sys/stat.h>
#include <unistd.h>
#include <utility>

namespace pedesis {

namespace {

namespace fs = std::filesystem;

// Values are read byte for byte as the writer's memory held them; every GSD writer in
// use runs little-endian, as GsdWriter assumes too.
static_assert(std::endian::native == std::endian::little, "GSD files are little-endian");

constexpr std::uint64_t gsd_magic = 0x65DF65DF65DF65DFull;
constexpr std::size_t header_size = 256;
constexpr std::size_t entry_size = 32;
constexpr std::size_t name_segment = 64;

// Bytes per value of each chunk type (gsd.h: uint8 = 1 ... double = 10, character = 11).
std::size_t type_size(std::uint8_t type) {
    static constexpr std::array<std::size_t, 12> sizes = {0, 1, 2, 4, 8, 1, 2, 4, 8, 4, 8, 1};
    return type < sizes.size() ? sizes[type] : 0;
}

bool is_real_type(std::uint8_t type) {
    return type == 9 || type == 10;
}

template <class T> T load(const char* p) {
    T v;
    std::memcpy(&v, p, sizeof(T));
    return v;
}

// A NUL-terminated name in a fixed field (the header's application and schema).
std::string fixed_string(const char* p, std::size_t n) {
    return std::string(p, strnlen(p, n));
}

} // namespace

GsdReader::GsdReader(fs::path path) : path_(std::move(path)) {
    const std::string name = path_.string();
    errno = 0;
    fd_ = ::open(path_.c_str(), O_RDONLY | O_CLOEXEC);
    if (fd_ < 0) throw InputError(name + ": cannot open" + errno_text(errno));
    struct stat st {};
    if (::fstat(fd_, &st) != 0 || !S_ISREG(st.st_mode)) {
        ::close(fd_);
        fd_ = -1;
        throw InputError(name + ": not a regular file");
    }
    file_size_ = static_cast<std::uint64_t>(st.st_size);

    // Everything below may throw; the destructor does not run for a half-built object.
    try {
        if (file_size_ < header_size)
            throw InputError(name + ": not a GSD file (shorter than the 256-byte GSD header)");
        std::array<char, header_size> h{};
        read_at(0, h.data(), header_size);
        if (load<std::uint64_t>(h.data()) != gsd_magic)
            throw InputError(name + ": not a GSD file (wrong magic number)");
        const auto index_location = load<std::uint64_t>(h.data() + 8);
        const auto index_allocated = load<std::uint64_t>(h.data() + 16);
        const auto namelist_location = load<std::uint64_t>(h.data() + 24);
        const auto namelist_allocated = load<std::uint64_t>(h.data() + 32);
        gsd_version_ = load<std::uint32_t>(h.data() + 44);
        application_ = fixed_string(h.data() + 48, 64);
        schema_ = fixed_string(h.data() + 112, 64);
        const std::uint32_t major = gsd_version_ >> 16;
        if (major != 1 && major != 2)
            throw InputError(fmt::format("{}: GSD file layer version {}.{} is not supported (1.x "
                                         "and 2.x are)",
                                         name, major, gsd_version_ & 0xFFFFu));

        const auto within_file = [&](std::uint64_t location, std::uint64_t count,
                                     std::uint64_t unit) {
            return count <= file_size_ / unit && location <= file_size_ &&
                   count * unit <= file_size_ - location;
        };
        if (!within_file(namelist_location, namelist_allocated, name_segment) ||
            !within_file(index_location, index_allocated, entry_size))
            throw InputError(name + ": truncated or corrupt GSD file (its name list or index "
                                    "lies beyond the end of the file)");

        std::string names(namelist_allocated * name_segment, '\0');
        read_at(namelist_location, names.data(), names.size());
        if (major == 1) {
            for (std::size_t at = 0; at < names.size() && names[at] != '\0'; at += name_segment)
                names_.push_back(fixed_string(names.data() + at, name_segment));
        } else {
            std::size_t at = 0;
            while (at < names.size() && names[at] != '\0') {
                const std::size_t end = names.find('\0', at);
                if (end == std::string::npos)
                    throw InputError(name + ": corrupt GSD file (unterminated chunk name)");
                names_.push_back(names.substr(at, end - at));
                at = end + 1;
            }
        }

        std::string index(index_allocated * entry_size, '\0');
        read_at(index_location, index.data(), index.size());
        for (std::size_t at = 0; at < index.size(); at += entry_size) {
            const char* p = index.data() + at;
            Entry e{load<std::uint64_t>(p),      load<std::uint64_t>(p + 8),
                    load<std::int64_t>(p + 16),  load<std::uint32_t>(p + 24),
                    load<std::uint16_t>(p + 28), load<std::uint8_t>(p + 30)};
            if (e.location == 0) break; // the first unused entry ends the index
            const std::size_t size = type_size(e.type);
            const std::string chunk =
                e.id < names_.size() ? "'" + names_[e.id] + "'" : fmt::format("#{}", e.id);
            if (size == 0 || e.id >= names_.size())
                throw InputError(fmt::format("{}: corrupt GSD file (index entry {} has an unknown "
                                             "{})",
                                             name, at / entry_size,
                                             size == 0 ? "data type" : "chunk name"));
            if (!entries_.empty() && e.frame < entries_.back().frame)
                throw InputError(fmt::format("{}: corrupt GSD file (index entry {}: frame {} after "
                                             "frame {})",
                                             name, at / entry_size, e.frame,
                                             entries_.back().frame));
            const bool fits = e.location > 0 && e.m > 0 && e.n <= file_size_ / e.m / size &&
                              within_file(static_cast<std::uint64_t>(e.location), e.n * e.m, size);
            if (!fits)
                throw InputError(fmt::format("{}: truncated or corrupt GSD file (chunk {} of frame "
                                             "{} lies beyond the end of the file)",
                                             name, chunk, e.frame));
            entries_.push_back(e);
        }
        frames_ = entries_.empty() ? 0 : entries_.back().frame + 1;
    } catch (...) {
        ::close(fd_);
        fd_ = -1;
        throw;
    }
}

GsdReader::~GsdReader() {
    if (fd_ >= 0) ::close(fd_);
}

void GsdReader::read_at(std::uint64_t offset, char* out, std::uint64_t size) const {
    std::uint64_t done = 0;
    while (done < size) {
        errno = 0;
        const ssize_t r = ::pread(fd_, out + done, size - done, static_cast<off_t>(offset + done));
        if (r < 0 && errno == EINTR) continue;
        if (r <= 0)
            throw InputError(path_.string() + ": " +
                             (r == 0 ? std::string("truncated GSD file (unexpected end of file)")
                                     : "read error" + errno_text(errno)));
        done += static_cast<std::uint64_t>(r);
    }
}

const GsdReader::Entry* GsdReader::find(std::uint64_t frame, std::string_view name) const {
    const auto id_it = std::find(names_.begin(), names_.end(), name);
    if (id_it == names_.end()) return nullptr;
    const auto id = static_cast<std::uint16_t>(id_it - names_.begin());
    const auto [lo, hi] =
        std::equal_range(entries_.begin(), entries_.end(), Entry{frame, 0, 0, 0, 0, 0},
                         [](const Entry& a, const Entry& b) { return a.frame < b.frame; });
    for (auto it = lo; it != hi; ++it)
        if (it->id == id) return &*it;
    return nullptr;
}

const GsdReader::Entry* GsdReader::find_with_fallback(std::uint64_t frame,
                                                      std::string_view name) const {
    if (const Entry* e = find(frame, name)) return e;
    return frame != 0 ? find(0, name) : nullptr;
}

bool GsdReader::has_chunk(std::uint64_t frame, std::string_view name) const {
    return find(frame, name) != nullptr;
}

std::string GsdReader::bytes(const Entry& e) const {
    std::string raw(e.n * e.m * type_size(e.type), '\0');
    read_at(static_cast<std::uint64_t>(e.location), raw.data(), raw.size());
    return raw;
}

std::vector<double> GsdReader::reals(const Entry& e, std::uint64_t frame) const {
    if (!is_real_type(e.type))
        throw InputError(fmt::format("{}: frame {}: chunk '{}' should hold floating-point values",
                                     path_.string(), frame, names_[e.id]));
    const std::string raw = bytes(e);
    std::vector<double> out(e.n * e.m);
    for (std::size_t i = 0; i < out.size(); ++i)
        out[i] = e.type == 9 ? static_cast<double>(load<float>(raw.data() + 4 * i))
                             : load<double>(raw.data() + 8 * i);
    return out;
}

std::vector<std::int64_t> GsdReader::integers(const Entry& e, std::uint64_t frame) const {
    if (e.type < 1 || e.type > 8)
        throw InputError(fmt::format("{}: frame {}: chunk '{}' should hold integers",
                                     path_.string(), frame, names_[e.id]));
    const std::string raw = bytes(e);
    const char* p = raw.data();
    std::vector<std::int64_t> out(e.n * e.m);
    for (std::size_t i = 0; i < out.size(); ++i) {
        switch (e.type) {
        case 1:
            out[i] = load<std::uint8_t>(p + i);
            break;
        case 2:
            out[i] = load<std::uint16_t>(p + 2 * i);
            break;
        case 3:
            out[i] = load<std::uint32_t>(p + 4 * i);
            break;
        case 4: {
            const auto v = load<std::uint64_t>(p + 8 * i);
            out[i] = v > static_cast<std::uint64_t>(std::numeric_limits<std::int64_t>::max())
                         ? std::numeric_limits<std::int64_t>::max()
                         : static_cast<std::int64_t>(v);
            break;
        }
        case 5:
            out[i] = load<std::int8_t>(p + i);
            break;
        case 6:
            out[i] = load<std::int16_t>(p + 2 * i);
            break;
        case 7:
            out[i] = load<std::int32_t>(p + 4 * i);
            break;
        default:
            out[i] = load<std::int64_t>(p + 8 * i);
            break;
        }
    }
    return out;
}

GsdFrame GsdReader::frame(std::uint64_t k) const {
    if (k >= frames_)
        throw std::out_of_range(fmt::format("GsdReader::frame({}) of {}", k, frames_));
    const std::string where = fmt::format("{}: frame {}", path_.string(), k);
    GsdFrame f;

    // Shape of a chunk: n rows of m columns, or the message says what was expected.
    auto shaped = [&](const Entry& e, std::uint64_t n, std::uint32_t m, const char* expected) {
        if (e.n != n || e.m != m)
            throw InputError(fmt::format("{}: chunk '{}' is {}x{}, expected {}", where,
                                         names_[e.id], e.n, e.m, expected));
    };
    auto finite = [&](const std::vector<double>& v, const Entry& e) {
        for (double x : v)
            if (!std::isfinite(x))
                throw InputError(
                    fmt::format("{}: chunk '{}' holds a non-finite value", where, names_[e.id]));
    };

    if (const Entry* e = find_with_fallback(k, "configuration/step")) {
        shaped(*e, 1, 1, "1x1");
        f.step = static_cast<std::uint64_t>(std::max<std::int64_t>(0, integers(*e, k)[0]));
    }
    // not from frame 0: a time is of its own frame
    if (const Entry* e = find(k, "log/time")) {
        shaped(*e, 1, 1, "1x1");
        const double t = reals(*e, k)[0];
        if (std::isfinite(t)) f.time = t;
    }
    if (const Entry* e = find_with_fallback(k, "configuration/dimensions")) {
        shaped(*e, 1, 1, "1x1");
        const std::int64_t d = integers(*e, k)[0];
        if (d != 2 && d != 3)
            throw InputError(
                fmt::format("{}: configuration/dimensions is {}, not 2 or 3", where, d));
        f.dimensions = static_cast<int>(d);
    }
    if (const Entry* e = find_with_fallback(k, "configuration/box")) {
        shaped(*e, 6, 1, "6x1 (Lx, Ly, Lz, xy, xz, yz)");
        const auto b = reals(*e, k);
        finite(b, *e);
        for (int a = 0; a < 3; ++a)
            if (b[static_cast<std::size_t>(a)] < 0.0)
                throw InputError(fmt::format("{}: configuration/box has a negative length", where));
        std::copy(b.begin(), b.end(), f.box.begin());
    }
    if (const Entry* e = find_with_fallback(k, "log/pedesis/periodic")) {
        const auto dims = static_cast<std::uint64_t>(f.dimensions);
        shaped(*e, dims, 1, fmt::format("{}x1 (one flag per axis)", dims).c_str());
        const auto flags = integers(*e, k);
        std::array<bool, 3> periodic{false, false, false};
        for (std::size_t a = 0; a < flags.size(); ++a) {
            if (flags[a] != 0 && flags[a] != 1)
                throw InputError(fmt::format("{}: log/pedesis/periodic holds {}; each axis is 1 "
                                             "(periodic) or 0 (walls)",
                                             where, flags[a]));
            periodic[a] = flags[a] == 1;
        }
        f.periodic = periodic;
    }

    std::uint64_t n = 0;
    if (const Entry* e = find_with_fallback(k, "particles/N")) {
        shaped(*e, 1, 1, "1x1");
        const std::int64_t v = integers(*e, k)[0];
        if (v < 0 || v > std::numeric_limits<std::uint32_t>::max())
            throw InputError(fmt::format("{}: particles/N is {}", where, v));
        n = static_cast<std::uint64_t>(v);
    }
    auto shape = [n](std::uint32_t m) { return fmt::format("{}x{} (particles/N = {})", n, m, n); };
    // N sets the size of every array below: it must be backed by the positions in the file
    // before anything of that size is allocated (a crafted N of 10^9 asked for 4 GB)
    if (n > 0) {
        const Entry* pos = find_with_fallback(k, "particles/position");
        if (!pos)
            throw InputError(fmt::format("{}: particles/N is {} but the frame has no "
                                         "particles/position",
                                         where, n));
        shaped(*pos, n, 3, shape(3).c_str());
    }

    if (const Entry* e = find_with_fallback(k, "particles/types")) {
        if (e->type != 1 && e->type != 5 && e->type != 11)
            throw InputError(where + ": chunk 'particles/types' should hold characters");
        const std::string raw = bytes(*e);
        for (std::uint64_t r = 0; r < e->n; ++r)
            f.types.push_back(fixed_string(raw.data() + r * e->m, e->m));
    } else {
        f.types = {"A"};
    }

    f.type_id.assign(n, 0);
    if (const Entry* e = find_with_fallback(k, "particles/typeid")) {
        shaped(*e, n, 1, shape(1).c_str());
        const auto ids = integers(*e, k);
        for (std::size_t i = 0; i < n; ++i) {
            if (ids[i] < 0 || static_cast<std::uint64_t>(ids[i]) >= f.types.size())
                throw InputError(fmt::format("{}: particle {} has typeid {}, but particles/types "
                                             "names {} type(s)",
                                             where, i, ids[i], f.types.size()));
            f.type_id[i] = static_cast<std::uint32_t>(ids[i]);
        }
    }

    auto scalars = [&](const char* chunk, double fallback, std::vector<double>& out) {
        out.assign(n, fallback);
        if (const Entry* e = find_with_fallback(k, chunk)) {
            shaped(*e, n, 1, shape(1).c_str());
            out = reals(*e, k);
        }
    };
    scalars("particles/mass", 1.0, f.mass);
    scalars("particles/diameter", 1.0, f.diameter);
    for (double d : f.diameter)
        if (!(std::isfinite(d) && d >= 0.0))
            throw InputError(fmt::format("{}: particles/diameter holds {}", where, d));

    auto vectors = [&]<std::size_t M>(const char* chunk, std::array<double, M> fallback,
                                      std::vector<std::array<double, M>>& out) {
        out.assign(n, fallback);
        const Entry* e = find_with_fallback(k, chunk);
        if (!e) return false;
        shaped(*e, n, M, shape(M).c_str());
        const auto v = reals(*e, k);
        finite(v, *e);
        for (std::size_t i = 0; i < n; ++i)
            for (std::size_t c = 0; c < M; ++c) out[i][c] = v[M * i + c];
        return true;
    };
    vectors("particles/position", std::array<double, 3>{0.0, 0.0, 0.0}, f.position);
    f.velocity_stored =
        vectors("particles/velocity", std::array<double, 3>{0.0, 0.0, 0.0}, f.velocity);
    f.orientation_stored =
        vectors("particles/orientation", std::array<double, 4>{1.0, 0.0, 0.0, 0.0}, f.orientation);
    return f;
}

} // namespace pedesis
