#include "pedesis/io/gsd_writer.hpp"

#include "pedesis/core/error.hpp"
#include "pedesis/io/atomic_file.hpp"

#include <algorithm>
#include <array>
#include <bit>
#include <cerrno>
#include <cmath>
#include <cstring>
#include <fcntl.h>
#include <limits>
#include <stdexcept>
#include <system_error>
#include <type_traits>
#include <unistd.h>
#include <utility>

namespace pedesis {

namespace {

namespace fs = std::filesystem;

// GSD stores every value in the writer's byte order; all readers in use assume
// little-endian IEEE floats, as does this byte-by-byte encoding.
static_assert(std::endian::native == std::endian::little, "GSD files are little-endian");
static_assert(std::numeric_limits<float>::is_iec559 && std::numeric_limits<double>::is_iec559);

// File layer 2.0 (0xaaaabbbb = aaaa.bbbb); 2.1 only adds a character chunk type.
constexpr std::uint64_t gsd_magic = 0x65DF65DF65DF65DFull;
constexpr std::uint32_t gsd_version = (2u << 16) | 0u;
constexpr std::uint32_t hoomd_schema_version = (1u << 16) | 4u;
constexpr std::size_t header_size = 256;
constexpr std::size_t entry_size = 32;
constexpr std::size_t name_block = 64; // the namelist is allocated in 64-byte units
constexpr std::uint64_t initial_index_capacity = 128;

enum class GsdType : std::uint8_t {
    uint8 = 1,
    uint32 = 3,
    uint64 = 4,
    int8 = 5,
    int32 = 7,
    float32 = 9,
    float64 = 10,
};

// Readers look chunks up by binary search over (frame, name id), so each frame's
// entries must be written in increasing id order: the order of this list.
enum ChunkId : std::uint16_t {
    step_id,
    dimensions_id,
    box_id,
    n_id,
    types_id,
    typeid_id,
    mass_id,
    diameter_id,
    position_id,
    orientation_id,
    velocity_id,
    image_id,
    time_id,
    periodic_id,
    chunk_count
};

constexpr std::array<const char*, chunk_count> chunk_names = {
    "configuration/step", "configuration/dimensions", "configuration/box",  "particles/N",
    "particles/types",    "particles/typeid",         "particles/mass",     "particles/diameter",
    "particles/position", "particles/orientation",    "particles/velocity", "particles/image",
    "log/time",           "log/pedesis/periodic",
};

template <class T> void put(std::string& b, T v) {
    static_assert(std::is_trivially_copyable_v<T>);
    char raw[sizeof(T)];
    std::memcpy(raw, &v, sizeof(T));
    b.append(raw, sizeof(T));
}

template <class T> void put_at(std::string& b, std::size_t offset, T v) {
    static_assert(std::is_trivially_copyable_v<T>);
    std::memcpy(b.data() + offset, &v, sizeof(T));
}

std::string encode_header(std::uint64_t index_location, std::uint64_t index_capacity,
                          std::uint64_t namelist_location, std::uint64_t namelist_bytes) {
    std::string h(header_size, '\0');
    put_at<std::uint64_t>(h, 0, gsd_magic);
    put_at<std::uint64_t>(h, 8, index_location);
    put_at<std::uint64_t>(h, 16, index_capacity);
    put_at<std::uint64_t>(h, 24, namelist_location);
    put_at<std::uint64_t>(h, 32, namelist_bytes / name_block);
    put_at<std::uint32_t>(h, 40, hoomd_schema_version);
    put_at<std::uint32_t>(h, 44, gsd_version);
    const std::string application = "pedesis", schema = "hoomd";
    std::memcpy(h.data() + 48, application.data(), application.size()); // char[64]
    std::memcpy(h.data() + 112, schema.data(), schema.size());          // char[64]
    return h;                                                           // + 80 reserved
}

// Names separated by NUL, an empty name to end the list, zero padding up to the
// allocation unit (readers also require the block to end in NUL).
std::string encode_namelist() {
    std::string names;
    for (const char* name : chunk_names) {
        names += name;
        names += '\0';
    }
    names += '\0';
    names.resize((names.size() + name_block - 1) / name_block * name_block, '\0');
    return names;
}

struct Chunk {
    ChunkId id;
    GsdType type;
    std::uint64_t n; // rows
    std::uint32_t m; // columns
    std::string bytes;
};

template <int D> std::array<double, 3> as_3d(const Vec<D>& v) {
    std::array<double, 3> out{};
    for (int a = 0; a < D; ++a) out[a] = v[a];
    return out;
}

// Shortest rotation taking x onto n: q ~ (1 + n.x, x cross n) = (1 + nx, 0, -nz, ny).
std::array<float, 4> orientation_of(const std::array<double, 3>& director) {
    const double len = std::sqrt(director[0] * director[0] + director[1] * director[1] +
                                 director[2] * director[2]);
    if (!(len > 0.0) || !std::isfinite(len)) return {1.0f, 0.0f, 0.0f, 0.0f};
    const double nx = director[0] / len, ny = director[1] / len, nz = director[2] / len;
    // 1 + nx loses all its digits as n approaches -x; this form keeps them.
    const double w = nx >= 0.0 ? 1.0 + nx : (ny * ny + nz * nz) / (1.0 - nx);
    const double q = std::sqrt(w * w + ny * ny + nz * nz);
    // n = -x: every half-turn about an axis normal to x fits; the one about z keeps
    // 2D orientations in the plane.
    if (q == 0.0) return {0.0f, 0.0f, 0.0f, 1.0f};
    return {static_cast<float>(w / q), 0.0f, static_cast<float>(-nz / q),
            static_cast<float>(ny / q)};
}

std::vector<std::string> type_names(const std::vector<Species>& table) {
    std::vector<std::string> names;
    for (const Species& s : table) {
        if (s.name.find('\0') != std::string::npos)
            throw InputError("species '" + s.name +
                             "': name cannot be written to a GSD file (it contains a NUL byte)");
        names.push_back(s.name);
    }
    return names;
}

template <int D>
std::vector<Chunk> frame_chunks(const Frame<D>& s, bool write_types,
                                const std::vector<std::string>& types) {
    const ParticleStore<D>& p = s.particles;
    const std::vector<std::uint32_t> index = p.index_of_tags();
    const std::size_t n = index.size();
    std::vector<Chunk> chunks;

    Chunk step{step_id, GsdType::uint64, 1, 1, {}};
    put<std::uint64_t>(step.bytes, s.step);
    chunks.push_back(std::move(step));

    Chunk dimensions{dimensions_id, GsdType::uint8, 1, 1, {}};
    put<std::uint8_t>(dimensions.bytes, static_cast<std::uint8_t>(D));
    chunks.push_back(std::move(dimensions));

    Chunk box{box_id, GsdType::float32, 6, 1, {}};
    std::array<float, 3> L{0.0f, 0.0f, 0.0f};
    for (int a = 0; a < D; ++a) L[a] = static_cast<float>(s.box.length(a));
    for (float l : L) put<float>(box.bytes, l);
    // the tilt factors xy, xz, yz: under Lees-Edwards shear the image above is displaced
    // along x by the offset, HOOMD's a2 = (xy L_y, L_y, 0), so xy = offset / L_y
    const double xy = s.box.sheared() ? s.box.shear_offset() / s.box.length(1) : 0.0;
    for (float t : {static_cast<float>(xy), 0.0f, 0.0f}) put<float>(box.bytes, t);
    chunks.push_back(std::move(box));

    Chunk count{n_id, GsdType::uint32, 1, 1, {}};
    put<std::uint32_t>(count.bytes, static_cast<std::uint32_t>(n));
    chunks.push_back(std::move(count));

    if (write_types && !types.empty()) {
        std::size_t width = 1;
        for (const std::string& t : types) width = std::max(width, t.size() + 1);
        Chunk names{types_id, GsdType::int8, types.size(), static_cast<std::uint32_t>(width), {}};
        for (const std::string& t : types) {
            names.bytes += t;
            names.bytes.append(width - t.size(), '\0');
        }
        chunks.push_back(std::move(names));
    }

    // The simulation time, which the schema has no place for (HOOMD-blue's loggers write
    // theirs under log/ too; gsd.hoomd gives it as frame.log["time"]).
    Chunk time{time_id, GsdType::float64, 1, 1, {}};
    put<double>(time.bytes, s.time);

    // The boundaries, which the schema has no place for either (its box is periodic on
    // every axis): 1 periodic, 0 walls, one per axis. In every frame, not only frame 0,
    // so that a reader without the schema's fall-back to frame 0 finds them too.
    Chunk periodic{periodic_id, GsdType::uint8, static_cast<std::uint64_t>(D), 1, {}};
    for (int a = 0; a < D; ++a) put<std::uint8_t>(periodic.bytes, s.box.periodic(a) ? 1 : 0);

    // An empty frame keeps only N, the time and the boundaries: chunks of no bytes would
    // need a location of their own.
    if (n == 0) {
        chunks.push_back(std::move(time));
        chunks.push_back(std::move(periodic));
        return chunks;
    }

    Chunk typeid_chunk{typeid_id, GsdType::uint32, n, 1, {}};
    Chunk mass{mass_id, GsdType::float32, n, 1, {}};
    Chunk diameter{diameter_id, GsdType::float32, n, 1, {}};
    Chunk position{position_id, GsdType::float32, n, 3, {}};
    Chunk orientation{orientation_id, GsdType::float32, n, 4, {}};
    Chunk velocity{velocity_id, GsdType::float32, n, 3, {}};
    Chunk image{image_id, GsdType::int32, n, 3, {}};
    for (std::uint32_t i : index) {
        put<std::uint32_t>(typeid_chunk.bytes, p.species[i]);
        put<float>(mass.bytes, static_cast<float>(p.mass(i)));
        put<float>(diameter.bytes, static_cast<float>(2.0 * p.radius(i)));

        const auto r = as_3d(p.position[i]);
        std::array<std::int32_t, 3> img{0, 0, 0};
        const std::array<std::int32_t, D> stored = s.image(i);
        for (int a = 0; a < D; ++a) img[a] = stored[a];
        std::array<float, 3> x;
        for (int a = 0; a < 3; ++a) x[a] = static_cast<float>(r[a]);
        // (y first: under shear its image shifts x)
        for (int a : {1, 0, 2}) {
            if (a < D && s.box.periodic(a) && x[a] >= 0.5f * L[a]) {
                x[a] -= L[a];
                img[a] += 1;
                if (a == 1 && s.box.sheared()) x[0] -= static_cast<float>(s.box.shear_offset());
            }
        }
        if (s.box.periodic(0) && x[0] < -0.5f * L[0]) { // (only after that shift)
            x[0] += L[0];
            img[0] -= 1;
        }
        for (float c : x) put<float>(position.bytes, c);
        for (std::int32_t k : img) put<std::int32_t>(image.bytes, k);

        if (s.has_director())
            for (float c : orientation_of(as_3d(s.director(i)))) put<float>(orientation.bytes, c);
        for (double v : as_3d(s.lab_velocity(i))) put<float>(velocity.bytes, static_cast<float>(v));
    }
    chunks.push_back(std::move(typeid_chunk));
    chunks.push_back(std::move(mass));
    chunks.push_back(std::move(diameter));
    chunks.push_back(std::move(position));
    // without directors the schema's default, the identity, says it all
    if (s.has_director()) chunks.push_back(std::move(orientation));
    chunks.push_back(std::move(velocity));
    chunks.push_back(std::move(image));
    chunks.push_back(std::move(time));
    chunks.push_back(std::move(periodic));
    return chunks;
}

} // namespace

template <int D> GsdWriter<D>::GsdWriter(const fs::path& path) : path_(path), part_(path) {
    part_ += ".part";
    errno = 0;
    fd_ = ::open(part_.c_str(), O_RDWR | O_CREAT | O_TRUNC | O_CLOEXEC, 0666);
    if (fd_ < 0) throw InputError(part_.string() + ": cannot open for writing" + errno_text(errno));
    std::error_code ec;
    fs::remove(path_, ec);
    if (ec) {
        ::close(fd_);
        fd_ = -1;
        throw InputError(path_.string() + ": cannot remove the old file: " + ec.message());
    }

    // Header, then the name list (every name this writer uses, so it never grows),
    // then an empty index; frames follow. An all-zero index means no frames.
    const std::string names = encode_namelist();
    namelist_location_ = header_size;
    namelist_bytes_ = names.size();
    index_location_ = namelist_location_ + namelist_bytes_;
    index_capacity_ = initial_index_capacity;
    std::string start =
        encode_header(index_location_, index_capacity_, namelist_location_, namelist_bytes_);
    start += names;
    start.append(index_capacity_ * entry_size, '\0');
    write_at(0, start);
    file_end_ = start.size();
}

template <int D>
GsdWriter<D>::GsdWriter(const fs::path& path, const GsdMark& mark) : path_(path), part_(path) {
    part_ += ".part";
    const std::uint64_t index_bytes = mark.index_entries * entry_size;
    if (mark.index_entries > mark.index_capacity || mark.index_capacity > (1ull << 40) ||
        mark.index_location < header_size ||
        mark.index_location + mark.index_capacity * entry_size > mark.file_end)
        throw InputError(part_.string() + ": the checkpoint's record of it is inconsistent");
    cut_back_part_file(path_, part_, mark.file_end);
    errno = 0;
    fd_ = ::open(part_.c_str(), O_RDWR | O_CLOEXEC);
    if (fd_ < 0) throw InputError(part_.string() + ": cannot open for writing" + errno_text(errno));
    frames_ = mark.frames;
    file_end_ = mark.file_end;
    index_location_ = mark.index_location;
    index_capacity_ = mark.index_capacity;
    namelist_location_ = header_size;
    namelist_bytes_ = encode_namelist().size();
    first_types_ = mark.first_types;
    index_.resize(index_bytes);
    std::size_t done = 0;
    while (done < index_bytes) {
        const ssize_t r = ::pread(fd_, index_.data() + done, index_bytes - done,
                                  static_cast<off_t>(index_location_ + done));
        if (r < 0 && errno == EINTR) continue;
        if (r <= 0)
            throw InputError(part_.string() + ": cannot read its index" + errno_text(errno));
        done += static_cast<std::size_t>(r);
    }
    // the entries of frames written after the checkpoint go, and the header points where
    // it pointed then
    write_at(index_location_ + index_bytes,
             std::string((index_capacity_ - mark.index_entries) * entry_size, '\0'));
    write_header();
}

template <int D> GsdMark GsdWriter<D>::mark() const {
    return {frames_,     file_end_, index_location_, index_capacity_, index_.size() / entry_size,
            first_types_};
}

template <int D> void GsdWriter<D>::sync() {
    if (committed_ || fd_ < 0) return;
    if (::fsync(fd_) != 0)
        throw InputError(part_.string() + ": cannot write it to the disk" + errno_text(errno));
}

template <int D> GsdWriter<D>::~GsdWriter() {
    if (fd_ >= 0) ::close(fd_);
}

template <int D> void GsdWriter<D>::write_at(std::uint64_t offset, const std::string& bytes) {
    std::size_t done = 0;
    while (done < bytes.size()) {
        errno = 0;
        const ssize_t w = ::pwrite(fd_, bytes.data() + done, bytes.size() - done,
                                   static_cast<off_t>(offset + done));
        if (w < 0 && errno == EINTR) continue;
        if (w <= 0) throw InputError(part_.string() + ": write error" + errno_text(errno));
        done += static_cast<std::size_t>(w);
    }
}

template <int D> void GsdWriter<D>::write_header() {
    write_at(0,
             encode_header(index_location_, index_capacity_, namelist_location_, namelist_bytes_));
}

// The order of the writes keeps the file valid whenever the process stops: the data
// goes past everything the index points to, then the frame's index entries are written
// with one write (readers take the first entry at location 0 as the end). A full index
// is copied, with the new entries, to a twice larger block at the end of the file, and
// only then does the header point to it. Writes go straight to the kernel (no user-space buffer),
// so a killed process loses nothing already appended; a power cut is not covered.
template <int D> void GsdWriter<D>::append(const Frame<D>& s) {
    if (committed_) throw std::logic_error("GsdWriter::append after commit");

    const std::vector<std::string> types = type_names(s.particles.species_table);
    const bool write_types = frames_ == 0 || types != first_types_;
    const std::vector<Chunk> chunks = frame_chunks(s, write_types, types);

    std::string data, entries;
    for (const Chunk& c : chunks) {
        put<std::uint64_t>(entries, frames_);
        put<std::uint64_t>(entries, c.n);
        put<std::int64_t>(entries, static_cast<std::int64_t>(file_end_ + data.size()));
        put<std::uint32_t>(entries, c.m);
        put<std::uint16_t>(entries, static_cast<std::uint16_t>(c.id));
        put<std::uint8_t>(entries, static_cast<std::uint8_t>(c.type));
        put<std::uint8_t>(entries, 0); // flags
        data += c.bytes;
    }
    write_at(file_end_, data);
    file_end_ += data.size();

    const std::uint64_t used = index_.size() / entry_size;
    const std::uint64_t needed = used + chunks.size();
    if (needed <= index_capacity_) {
        write_at(index_location_ + index_.size(), entries);
        index_ += entries;
    } else {
        std::uint64_t capacity = index_capacity_;
        while (capacity < needed) capacity *= 2;
        std::string block = index_ + entries;
        block.resize(capacity * entry_size, '\0');
        write_at(file_end_, block);
        index_location_ = file_end_;
        index_capacity_ = capacity;
        file_end_ += block.size();
        write_header();
        index_ += entries;
    }
    if (frames_ == 0) first_types_ = types;
    ++frames_;
}

template <int D> void GsdWriter<D>::commit() {
    if (committed_) return;
    errno = 0;
    const int rc = ::close(fd_);
    fd_ = -1;
    if (rc != 0) throw InputError(part_.string() + ": write error" + errno_text(errno));
    publish_part_file(part_, path_);
    committed_ = true;
}

template class GsdWriter<2>;
template class GsdWriter<3>;

} // namespace pedesis
