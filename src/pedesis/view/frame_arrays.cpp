#include "pedesis/view/frame_arrays.hpp"

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <stdexcept>
#include <vector>

namespace pedesis::view {

static_assert(std::endian::native == std::endian::little,
              "the page reads the arrays as little-endian typed arrays");

namespace {

template <class T> std::string bytes_of(const std::vector<T>& values) {
    std::string out(values.size() * sizeof(T), '\0');
    if (!values.empty()) std::memcpy(out.data(), values.data(), out.size());
    return out;
}

std::string vectors(const std::vector<render::Vec3>& v) {
    std::vector<float> out;
    out.reserve(3 * v.size());
    for (const render::Vec3& x : v)
        for (double c : x) out.push_back(static_cast<float>(c));
    return bytes_of(out);
}

constexpr Field every_field[] = {Field::position, Field::radius, Field::species, Field::director};

// The file's own numbers of that name (render::Frame::scalars), or null.
const std::vector<double>* stored(const render::Frame& f, std::string_view name) {
    for (const auto& [n, values] : f.scalars)
        if (n == name && values.size() == f.size()) return &values;
    return nullptr;
}

bool has_velocities(const render::Frame& f) {
    return f.velocity.size() == f.size();
}
bool has_directors(const render::Frame& f) {
    return f.director.size() == f.size();
}

// A number per particle computed from the frame: whether the frame has what it is made
// of, and the numbers (one call per request, a plain loop each).
struct Derived {
    const char* name;
    bool (*has)(const render::Frame&);
    void (*values)(const render::Frame&, std::vector<float>&);
};

template <int axis> void component(const render::Frame& f, std::vector<float>& out) {
    for (const render::Vec3& v : f.velocity) out.push_back(static_cast<float>(v[axis]));
}

const Derived derived[] = {
    {"speed", has_velocities,
     [](const render::Frame& f, std::vector<float>& out) {
         for (const render::Vec3& v : f.velocity)
             out.push_back(static_cast<float>(std::sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2])));
     }},
    {"vx", has_velocities, component<0>},
    {"vy", has_velocities, component<1>},
    {"vz", [](const render::Frame& f) { return f.dimension == 3 && has_velocities(f); },
     component<2>},
    {"kinetic_energy",
     [](const render::Frame& f) { return has_velocities(f) && stored(f, "mass") != nullptr; },
     [](const render::Frame& f, std::vector<float>& out) {
         const std::vector<double>& m = *stored(f, "mass");
         for (std::size_t i = 0; i < f.size(); ++i) {
             const render::Vec3& v = f.velocity[i];
             out.push_back(
                 static_cast<float>(0.5 * m[i] * (v[0] * v[0] + v[1] * v[1] + v[2] * v[2])));
         }
     }},
    {"angle", has_directors,
     [](const render::Frame& f, std::vector<float>& out) {
         for (const render::Vec3& n : f.director)
             out.push_back(static_cast<float>(std::atan2(n[1], n[0])));
     }},
    {"radius", [](const render::Frame&) { return true; },
     [](const render::Frame& f, std::vector<float>& out) {
         for (double r : f.radius) out.push_back(static_cast<float>(r));
     }},
};

} // namespace

std::string_view field_name(Field field) {
    switch (field) {
    case Field::position:
        return "position";
    case Field::radius:
        return "radius";
    case Field::species:
        return "species";
    case Field::director:
        return "director";
    }
    return "";
}

std::optional<Field> field_named(std::string_view name) {
    for (const Field f : every_field)
        if (field_name(f) == name) return f;
    return std::nullopt;
}

bool frame_has(const render::Frame& frame, Field field) {
    return field != Field::director || has_directors(frame);
}

std::string frame_bytes(const render::Frame& f, Field field) {
    if (!frame_has(f, field)) throw std::logic_error("frame_bytes: the frame lacks the field");
    switch (field) {
    case Field::position:
        return vectors(f.position);
    case Field::director:
        return vectors(f.director);
    case Field::species:
        return bytes_of(f.species);
    case Field::radius:
        break;
    }
    return *colour_field_bytes(f, "radius");
}

std::vector<std::string> colour_fields(const render::Frame& frame) {
    std::vector<std::string> names;
    for (const Derived& d : derived)
        if (d.has(frame)) names.emplace_back(d.name);
    for (const auto& [name, values] : frame.scalars)
        if (values.size() == frame.size() &&
            std::find(names.begin(), names.end(), name) == names.end())
            names.push_back(name);
    return names;
}

std::optional<std::string> colour_field_bytes(const render::Frame& frame, std::string_view name) {
    std::vector<float> out;
    out.reserve(frame.size());
    for (const Derived& d : derived)
        if (d.name == name) {
            if (!d.has(frame)) return std::nullopt;
            d.values(frame, out);
            return bytes_of(out);
        }
    const std::vector<double>* values = stored(frame, name);
    if (!values) return std::nullopt;
    for (double v : *values) out.push_back(static_cast<float>(v));
    return bytes_of(out);
}

} // namespace pedesis::view
