#include "pedesis/io/particle_file.hpp"

#include "pedesis/core/error.hpp"
#include "pedesis/core/stage.hpp"
#include "pedesis/io/gsd_reader.hpp"
#include "pedesis/io/xyz_reader.hpp"

#include <fmt/format.h>

#include <array>
#include <cctype>
#include <cmath>
#include <fstream>
#include <limits>
#include <string>
#include <unordered_map>

namespace pedesis {

namespace {

namespace fs = std::filesystem;

constexpr std::uint64_t gsd_magic = 0x65DF65DF65DF65DFull;

// The frame asked for, 0-based: unset is the last, -1 the last, -2 the one before.
std::uint64_t frame_index(std::optional<std::int64_t> frame, std::uint64_t frames,
                          const std::string& file, const char* format) {
    if (frames == 0) throw InputError(fmt::format("{}: the {} file has no frames", file, format));
    const std::int64_t k = frame.value_or(-1);
    const auto n = static_cast<std::int64_t>(std::min<std::uint64_t>(
        frames, static_cast<std::uint64_t>(std::numeric_limits<std::int64_t>::max())));
    const std::int64_t index = k < 0 ? n + k : k;
    if (index < 0 || index >= n)
        throw InputError(fmt::format("{}: [initial] frame = {}, but the file has {} frame(s): 0 "
                                     "to {} (or -1 for the last, -{} for the first)",
                                     file, k, frames, n - 1, n));
    return static_cast<std::uint64_t>(index);
}

// The x axis turned by the unit quaternion (w, x, y, z): what GsdWriter stores for a
// director, and HOOMD-blue's body frame, whose x axis an active force pushes along.
std::array<double, 3> rotated_x_axis(const std::array<double, 4>& q) {
    const double len2 = q[0] * q[0] + q[1] * q[1] + q[2] * q[2] + q[3] * q[3];
    if (!(len2 > 0.0)) return {0.0, 0.0, 0.0};
    const double s = 2.0 / len2; // also normalises a quaternion stored in single precision
    const double w = q[0], x = q[1], y = q[2], z = q[3];
    return {1.0 - s * (y * y + z * z), s * (x * y + w * z), s * (x * z - w * y)};
}

// A file's three periodic flags cut to the run's axes (a 2D file's z is never periodic).
template <int D> std::array<bool, D> first_axes(const std::array<bool, 3>& flags) {
    std::array<bool, D> out{};
    for (std::size_t a = 0; a < static_cast<std::size_t>(D); ++a) out[a] = flags[a];
    return out;
}

template <int D> ParticleFile<D> from_gsd(const fs::path& path, std::optional<std::int64_t> frame) {
    const std::string file = path.string();
    const GsdReader reader(path);
    const std::uint64_t k = frame_index(frame, reader.frames(), file, "GSD");
    const GsdFrame g = reader.frame(k);
    const std::string where = fmt::format("{}: frame {}", file, k);
    if (g.dimensions != D)
        throw InputError(fmt::format("{}: the frame is {}D (configuration/dimensions = {}), but "
                                     "this run is {}D",
                                     where, g.dimensions, g.dimensions, D));
    if (g.box[3] != 0.0 || g.box[4] != 0.0 || g.box[5] != 0.0)
        throw InputError(where + ": the box is tilted (xy, xz or yz is not 0); pedesis' boxes "
                                 "are orthorhombic");
    ParticleFile<D> out;
    out.default_radius = 0.5; // the hoomd schema's default diameter is 1
    out.precision = 1e-6;     // the schema's floats are single precision
    out.type_names = g.types;
    Vec<D> L;
    for (int a = 0; a < D; ++a) {
        L[a] = g.box[static_cast<std::size_t>(a)];
        if (!(L[a] > 0.0))
            throw InputError(fmt::format("{}: configuration/box: the length along axis {} is {}; "
                                         "it must be positive",
                                         where, a, L[a]));
    }
    out.box = L;
    if (g.periodic) out.periodic = first_axes<D>(*g.periodic);
    // values the frame stores for its particles, else the caller's defaults
    const bool has_diameter =
        reader.has_chunk(k, "particles/diameter") || reader.has_chunk(0, "particles/diameter");
    const bool has_mass =
        reader.has_chunk(k, "particles/mass") || reader.has_chunk(0, "particles/mass");
    out.particles.resize(g.size());
    for (std::size_t i = 0; i < g.size(); ++i) {
        FileParticle<D>& p = out.particles[i];
        const std::string who = fmt::format("{}: particle {}", where, i);
        p.id = static_cast<std::uint32_t>(i);
        p.type = static_cast<int>(g.type_id[i]);
        for (int a = 0; a < D; ++a) p.r[a] = g.position[i][static_cast<std::size_t>(a)];
        // HOOMD-blue keeps a 2D system in the plane z = 0
        if (D == 2 && (g.position[i][2] != 0.0 || (g.velocity_stored && g.velocity[i][2] != 0.0)))
            throw InputError(who + ": a 2D frame with a position or velocity off the plane z = 0");
        if (g.velocity_stored) {
            Vec<D> v;
            for (int a = 0; a < D; ++a) v[a] = g.velocity[i][static_cast<std::size_t>(a)];
            p.v = v;
        }
        if (g.orientation_stored) {
            const auto n = rotated_x_axis(g.orientation[i]);
            if (!(n[0] * n[0] + n[1] * n[1] + n[2] * n[2] > 0.0))
                throw InputError(who + ": particles/orientation is the zero quaternion, which "
                                       "gives no direction");
            // single-precision quaternions of a turn about z leave n_z at rounding level
            if (D == 2 && std::abs(n[2]) > 1e-5)
                throw InputError(fmt::format("{}: particles/orientation turns the x axis out of "
                                             "the plane (to {} {} {}); a 2D director turns about "
                                             "z only",
                                             who, n[0], n[1], n[2]));
            Vec<D> d;
            for (int a = 0; a < D; ++a) d[a] = n[static_cast<std::size_t>(a)];
            p.n = d;
        }
        if (has_diameter) {
            if (!(g.diameter[i] > 0.0))
                throw InputError(fmt::format("{}: particles/diameter is {}; a pedesis particle "
                                             "needs a positive radius",
                                             who, g.diameter[i]));
            p.radius = 0.5 * g.diameter[i];
        }
        if (has_mass) {
            if (!(g.mass[i] > 0.0)) // (+inf is a fixed obstacle, as pedesis writes it)
                throw InputError(
                    fmt::format("{}: particles/mass is {}; it must be positive", who, g.mass[i]));
            p.mass = g.mass[i];
        }
    }
    return out;
}

template <int D> ParticleFile<D> from_xyz(const fs::path& path, std::optional<std::int64_t> frame) {
    const std::string file = path.string();
    const XyzReader reader(path);
    const std::size_t k = frame_index(frame, reader.frames(), file, "XYZ");
    const XyzFrame x = reader.frame(k);
    const std::string where = fmt::format("{}: frame {}", file, k);
    ParticleFile<D> out;
    out.default_radius = 0.5; // pedesis' default radius: the format has none
    out.type_names = x.species_names;
    Vec<D> L, centre;
    for (int a = 0; a < D; ++a) {
        const auto ua = static_cast<std::size_t>(a);
        L[a] = x.lattice[ua];
        if (!(L[a] > 0.0))
            throw InputError(fmt::format("{}: the Lattice length along axis {} is {}; it must be "
                                         "positive",
                                         where, a, L[a]));
        centre[a] = x.origin[ua] + 0.5 * L[a];
    }
    out.box = L;
    if (x.pbc_stated) out.periodic = first_axes<D>(x.pbc);
    std::unordered_map<std::int64_t, std::size_t> row_of_id;
    out.particles.resize(x.size());
    for (std::size_t i = 0; i < x.size(); ++i) {
        FileParticle<D>& p = out.particles[i];
        const std::string who = fmt::format("{}: particle {}", where, i);
        if (x.id.empty()) {
            p.id = static_cast<std::uint32_t>(i);
        } else {
            const std::int64_t id = x.id[i];
            if (id < 0 || id > std::numeric_limits<std::uint32_t>::max())
                throw InputError(fmt::format("{}: id {} must lie in [0, 4294967295]", who, id));
            if (const auto [it, fresh] = row_of_id.emplace(id, i); !fresh)
                throw InputError(
                    fmt::format("{}: id {} is already used by particle {}", who, id, it->second));
            p.id = static_cast<std::uint32_t>(id);
        }
        p.type = x.species[i];
        for (int a = 0; a < D; ++a) p.r[a] = x.position[i][static_cast<std::size_t>(a)] - centre[a];
        // a 2D frame lies in one plane; pedesis writes it at z = 0
        if (D == 2 && x.position[i][2] != x.position[0][2])
            throw InputError(fmt::format("{}: z = {}, but particle 0 has z = {}: a 2D start needs "
                                         "every particle in one plane",
                                         who, x.position[i][2], x.position[0][2]));
        if (!x.velocity.empty()) {
            if (D == 2 && x.velocity[i][2] != 0.0)
                throw InputError(fmt::format("{}: a velocity along z ({}) in a 2D start", who,
                                             x.velocity[i][2]));
            Vec<D> v;
            for (int a = 0; a < D; ++a) v[a] = x.velocity[i][static_cast<std::size_t>(a)];
            p.v = v;
        }
        if (!x.radius.empty()) p.radius = x.radius[i];
        if (!x.mass.empty()) p.mass = x.mass[i];
    }
    return out;
}

} // namespace

ParticleFileFormat particle_file_format(const fs::path& path) {
    const std::string file = path.string();
    std::error_code ec;
    if (fs::is_directory(path, ec)) throw InputError(file + ": is a directory, not a file");
    std::ifstream in(path, std::ios::binary);
    if (!in) throw InputError(file + ": cannot open");
    std::array<unsigned char, 8> head{};
    in.read(reinterpret_cast<char*>(head.data()), head.size());
    if (in.gcount() == static_cast<std::streamsize>(head.size())) {
        std::uint64_t magic = 0;
        for (std::size_t b = 0; b < head.size(); ++b)
            magic |= static_cast<std::uint64_t>(head[b]) << (8 * b); // GSD is little-endian
        if (magic == gsd_magic) return ParticleFileFormat::gsd;
    }
    // text: a JSON document opens with '{', an XYZ frame with its particle count
    in.clear();
    in.seekg(0);
    char c = 0;
    while (in.get(c) && std::isspace(static_cast<unsigned char>(c))) {
    }
    if (in && std::isdigit(static_cast<unsigned char>(c))) return ParticleFileFormat::xyz;
    return ParticleFileFormat::tutorial_json; // its reader names any fault
}

const char* format_name(ParticleFileFormat f) {
    switch (f) {
    case ParticleFileFormat::gsd:
        return "GSD";
    case ParticleFileFormat::xyz:
        return "XYZ";
    case ParticleFileFormat::tutorial_json:
        break;
    }
    return "JSON";
}

template <int D>
ParticleFile<D> read_particle_file(const fs::path& path, std::optional<std::int64_t> frame) {
    const ParticleFileFormat format = particle_file_format(path);
    switch (format) {
    case ParticleFileFormat::gsd:
        enter_stage("reading a particle file");
        return from_gsd<D>(path, frame);
    case ParticleFileFormat::xyz:
        enter_stage("reading a particle file");
        return from_xyz<D>(path, frame);
    case ParticleFileFormat::tutorial_json:
        break;
    }
    if (frame)
        throw InputError(fmt::format("{}: [initial] frame = {} is for GSD and XYZ files; this is "
                                     "the tutorial's JSON, one configuration",
                                     path.string(), *frame));
    return read_tutorial_json<D>(path);
}

int particle_file_dimension(const fs::path& path, std::optional<std::int64_t> frame) {
    switch (particle_file_format(path)) {
    case ParticleFileFormat::gsd: {
        const GsdReader reader(path);
        return reader.frame(frame_index(frame, reader.frames(), path.string(), "GSD")).dimensions;
    }
    case ParticleFileFormat::xyz: {
        const XyzReader reader(path);
        const XyzFrame x = reader.frame(frame_index(frame, reader.frames(), path.string(), "XYZ"));
        if (x.pbc[2]) return 3;
        for (const auto& r : x.position)
            if (r[2] != x.position.front()[2]) return 3;
        return 2;
    }
    case ParticleFileFormat::tutorial_json:
        break;
    }
    return tutorial_json_dimension(path);
}

template ParticleFile<2> read_particle_file<2>(const fs::path&, std::optional<std::int64_t>);
template ParticleFile<3> read_particle_file<3>(const fs::path&, std::optional<std::int64_t>);

} // namespace pedesis
