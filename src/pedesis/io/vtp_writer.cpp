#include "pedesis/io/vtp_writer.hpp"

#include "pedesis/io/atomic_file.hpp"

#include <fmt/format.h>

#include <array>
#include <cstdint>
#include <iterator>
#include <ostream>
#include <vector>

namespace pedesis {

namespace {

using Out = std::back_insert_iterator<fmt::memory_buffer>;

// VTK points and vectors are three-dimensional whatever the simulation.
template <int N> std::array<double, 3> as_3d(const Vec<N>& v) {
    std::array<double, 3> out{};
    for (int a = 0; a < N && a < 3; ++a) out[a] = v[a];
    return out;
}

// One DataArray, one line per point; `row` writes the components of point k.
template <class Row>
void data_array(Out out, const char* type, const char* name, int components, std::size_t n,
                Row row) {
    fmt::format_to(out, "        <DataArray type=\"{}\"", type);
    if (name != nullptr) fmt::format_to(out, " Name=\"{}\"", name);
    fmt::format_to(out, " NumberOfComponents=\"{}\" format=\"ascii\">\n", components);
    for (std::size_t k = 0; k < n; ++k) {
        row(out, k);
        fmt::format_to(out, "\n");
    }
    fmt::format_to(out, "        </DataArray>\n");
}

void vector_row(Out out, const std::array<double, 3>& v) {
    fmt::format_to(out, "{} {} {}", v[0], v[1], v[2]);
}

} // namespace

template <int D> std::string vtp_document(const Frame<D>& s) {
    const ParticleStore<D>& p = s.particles;
    const std::vector<std::uint32_t> index = p.index_of_tags();
    const std::size_t n = index.size();

    fmt::memory_buffer buf;
    auto out = std::back_inserter(buf);
    fmt::format_to(out, "<?xml version=\"1.0\"?>\n");
    // Version 0.1: cell offsets are the end of each cell (no leading 0), which every
    // VTK reader accepts; the header type only matters for binary data.
    fmt::format_to(out,
                   "<VTKFile type=\"PolyData\" version=\"0.1\" byte_order=\"LittleEndian\">\n");
    fmt::format_to(out, "  <PolyData>\n");
    // ParaView takes the time of a file series from this field array.
    fmt::format_to(out, "    <FieldData>\n");
    fmt::format_to(out,
                   "      <DataArray type=\"Float64\" Name=\"TimeValue\" NumberOfTuples=\"1\" "
                   "format=\"ascii\">{}</DataArray>\n",
                   s.time);
    // The box of this frame (a barostat changes it): its lengths, z = 0 in 2D.
    std::array<double, 3> box{0.0, 0.0, 0.0};
    for (int a = 0; a < D; ++a) box[static_cast<std::size_t>(a)] = s.box.length(a);
    fmt::format_to(out,
                   "      <DataArray type=\"Float64\" Name=\"BoxLengths\" NumberOfTuples=\"1\" "
                   "NumberOfComponents=\"3\" format=\"ascii\">{} {} {}</DataArray>\n",
                   box[0], box[1], box[2]);
    fmt::format_to(out, "    </FieldData>\n");
    fmt::format_to(out,
                   "    <Piece NumberOfPoints=\"{}\" NumberOfVerts=\"{}\" NumberOfLines=\"0\" "
                   "NumberOfStrips=\"0\" NumberOfPolys=\"0\">\n",
                   n, n);

    fmt::format_to(out, "      <PointData Scalars=\"radius\" Vectors=\"velocity\">\n");
    data_array(out, "Int32", "id", 1, n,
               [&](Out o, std::size_t k) { fmt::format_to(o, "{}", p.tag[index[k]]); });
    data_array(out, "Int32", "type", 1, n,
               [&](Out o, std::size_t k) { fmt::format_to(o, "{}", p.species[index[k]]); });
    data_array(out, "Float64", "radius", 1, n,
               [&](Out o, std::size_t k) { fmt::format_to(o, "{}", p.radius(index[k])); });
    if (s.has_director())
        data_array(out, "Float64", "director", 3, n,
                   [&](Out o, std::size_t k) { vector_row(o, as_3d(s.director(index[k]))); });
    data_array(out, "Float64", "velocity", 3, n,
               [&](Out o, std::size_t k) { vector_row(o, as_3d(s.lab_velocity(index[k]))); });
    data_array(out, "Float64", "mass", 1, n,
               [&](Out o, std::size_t k) { fmt::format_to(o, "{}", p.mass(index[k])); });
    if (s.has_force())
        data_array(out, "Float64", "force", 3, n,
                   [&](Out o, std::size_t k) { vector_row(o, as_3d(s.force(index[k]))); });
    fmt::format_to(out, "      </PointData>\n");

    fmt::format_to(out, "      <Points>\n");
    data_array(out, "Float64", "Points", 3, n,
               [&](Out o, std::size_t k) { vector_row(o, as_3d(p.position[index[k]])); });
    fmt::format_to(out, "      </Points>\n");

    // One vertex cell per point, so that single particles can be picked in ParaView.
    fmt::format_to(out, "      <Verts>\n");
    data_array(out, "Int64", "connectivity", 1, n,
               [](Out o, std::size_t k) { fmt::format_to(o, "{}", k); });
    data_array(out, "Int64", "offsets", 1, n,
               [](Out o, std::size_t k) { fmt::format_to(o, "{}", k + 1); });
    fmt::format_to(out, "      </Verts>\n");

    fmt::format_to(out, "    </Piece>\n");
    fmt::format_to(out, "  </PolyData>\n");
    fmt::format_to(out, "</VTKFile>\n");
    return fmt::to_string(buf);
}

template <int D> void write_vtp(const std::filesystem::path& path, const Frame<D>& s) {
    const std::string doc = vtp_document(s);
    write_file_atomically(path, [&](std::ostream& out) { out << doc; });
}

template std::string vtp_document(const Frame<2>&);
template std::string vtp_document(const Frame<3>&);
template void write_vtp(const std::filesystem::path&, const Frame<2>&);
template void write_vtp(const std::filesystem::path&, const Frame<3>&);

} // namespace pedesis
