#include "pedesis/io/xyz_writer.hpp"

#include "pedesis/core/error.hpp"

#include <fmt/format.h>

#include <array>
#include <cctype>
#include <iterator>

namespace pedesis {

namespace {

// A species name is one whitespace-separated column; anything else would shift
// every later column of its rows and make the frame unreadable.
void check_species_names(const std::vector<Species>& table) {
    for (const Species& s : table) {
        bool ok = !s.name.empty();
        for (char c : s.name) ok = ok && std::isgraph(static_cast<unsigned char>(c)) && c != '"';
        if (!ok)
            throw InputError("species '" + s.name +
                             "': name cannot be written to an XYZ file (it must be non-empty, "
                             "without spaces or quotes)");
    }
}

// Every quantity padded to three components: the XYZ format is three-dimensional.
template <int D> std::array<double, 3> as_3d(const Vec<D>& v) {
    std::array<double, 3> out{};
    for (int a = 0; a < D; ++a) out[a] = v[a];
    return out;
}

} // namespace

template <int D> std::string xyz_frame(const Frame<D>& f) {
    const ParticleStore<D>& p = f.particles;
    const Box<D>& box = f.box;
    check_species_names(p.species_table);

    // A 2D box becomes a cell of unit height centred on z = 0, non-periodic in z.
    std::array<double, 3> L{0.0, 0.0, 1.0};
    std::array<char, 3> pbc{'F', 'F', 'F'};
    for (int a = 0; a < D; ++a) {
        L[a] = box.length(a);
        pbc[a] = box.periodic(a) ? 'T' : 'F';
    }

    fmt::memory_buffer buf;
    auto out = std::back_inserter(buf);
    fmt::format_to(out, "{}\n", p.size());
    fmt::format_to(out, "Lattice=\"{} 0 0 0 {} 0 0 0 {}\" Origin=\"{} {} {}\" ", L[0], L[1], L[2],
                   -0.5 * L[0], -0.5 * L[1], -0.5 * L[2]);
    fmt::format_to(out, "Properties=species:S:1:pos:R:3:velo:R:3:radius:R:1:mass:R:1:id:I:1 ");
    fmt::format_to(out, "Time={} pbc=\"{} {} {}\"", f.time, pbc[0], pbc[1], pbc[2]);
    // Lees-Edwards shear: the image above is displaced along x by shear_offset (the cell
    // stays orthorhombic, as the positions are wrapped into it)
    if (box.sheared())
        fmt::format_to(out, " shear_rate={} shear_offset={}", box.shear_rate(), box.shear_offset());
    fmt::format_to(out, "\n");

    const std::vector<std::uint32_t> index = p.index_of_tags();
    for (std::uint32_t i : index) {
        const Species& s = p.species_table[p.species[i]];
        const auto r = as_3d(p.position[i]);
        const auto v = as_3d(f.lab_velocity(i));
        // An infinite mass comes out as "inf", the spelling Python's float() (and so ASE) reads.
        fmt::format_to(out, "{} {} {} {} {} {} {} {} {} {}\n", s.name, r[0], r[1], r[2], v[0], v[1],
                       v[2], s.radius, s.mass, p.tag[i]);
    }
    return fmt::to_string(buf);
}

template std::string xyz_frame(const Frame<2>&);
template std::string xyz_frame(const Frame<3>&);

} // namespace pedesis
