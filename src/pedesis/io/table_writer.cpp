#include "pedesis/io/table_writer.hpp"

#include "pedesis/io/atomic_file.hpp"

#include <fmt/format.h>

#include <cstdint>
#include <iterator>
#include <ostream>
#include <vector>

namespace pedesis {

namespace {

constexpr const char* axis_names[] = {"x", "y", "z"};

template <int D> void put_vec(std::back_insert_iterator<fmt::memory_buffer> out, const Vec<D>& v) {
    for (int a = 0; a < D; ++a) fmt::format_to(out, " {}", v[a]);
}

} // namespace

template <int D> std::string table_frame(const Frame<D>& s) {
    static constexpr const char* box_names[] = {"Lx", "Ly", "Lz"};
    fmt::memory_buffer buf;
    auto out = std::back_inserter(buf);

    fmt::format_to(out, "# time={} step={}", s.time, s.step);
    for (int a = 0; a < D; ++a) fmt::format_to(out, " {}={}", box_names[a], s.box.length(a));
    fmt::format_to(out, "\n# id");
    for (const char* prefix : {"", "n", "v", "f"}) {
        if ((prefix[0] == 'n' && !s.has_director()) || (prefix[0] == 'f' && !s.has_force()))
            continue;
        for (int a = 0; a < D; ++a) fmt::format_to(out, " {}{}", prefix, axis_names[a]);
    }
    fmt::format_to(out, "\n");

    const ParticleStore<D>& p = s.particles;
    for (std::uint32_t i : p.index_of_tags()) {
        fmt::format_to(out, "{}", p.tag[i]);
        put_vec(out, p.position[i]);
        if (s.has_director()) put_vec(out, s.director(i));
        put_vec(out, s.lab_velocity(i));
        if (s.has_force()) put_vec(out, s.force(i));
        fmt::format_to(out, "\n");
    }
    return fmt::to_string(buf);
}

template <int D> void write_table(const std::filesystem::path& path, const Frame<D>& s) {
    const std::string text = table_frame(s);
    write_file_atomically(path, [&](std::ostream& out) { out << text; });
}

template std::string table_frame(const Frame<2>&);
template std::string table_frame(const Frame<3>&);
template void write_table(const std::filesystem::path&, const Frame<2>&);
template void write_table(const std::filesystem::path&, const Frame<3>&);

} // namespace pedesis
