#include "pedesis/view/frame_arrays.hpp"

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

} // namespace

namespace {
constexpr Field every_field[] = {Field::position, Field::radius, Field::species,
                                 Field::speed,    Field::angle,  Field::director};
}

std::string_view field_name(Field field) {
    switch (field) {
    case Field::position:
        return "position";
    case Field::radius:
        return "radius";
    case Field::species:
        return "species";
    case Field::speed:
        return "speed";
    case Field::angle:
        return "angle";
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
    switch (field) {
    case Field::speed:
        return frame.velocity.size() == frame.size();
    case Field::angle:
    case Field::director:
        return frame.director.size() == frame.size();
    default:
        return true;
    }
}

std::string frame_bytes(const render::Frame& f, Field field) {
    if (!frame_has(f, field)) throw std::logic_error("frame_bytes: the frame lacks the field");
    std::vector<float> out;
    switch (field) {
    case Field::position:
        return vectors(f.position);
    case Field::director:
        return vectors(f.director);
    case Field::species:
        return bytes_of(f.species);
    case Field::radius:
        for (double r : f.radius) out.push_back(static_cast<float>(r));
        break;
    case Field::speed:
        for (const render::Vec3& v : f.velocity)
            out.push_back(static_cast<float>(std::sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2])));
        break;
    case Field::angle:
        for (const render::Vec3& n : f.director)
            out.push_back(static_cast<float>(std::atan2(n[1], n[0])));
        break;
    }
    return bytes_of(out);
}

} // namespace pedesis::view
