// The arrays `pedesis view` sends: exact float32/uint32 images of a frame's fields.
#include "pedesis/view/frame_arrays.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <numbers>
#include <vector>

namespace pedesis::view {
namespace {

template <class T> std::vector<T> decode(const std::string& bytes) {
    std::vector<T> v(bytes.size() / sizeof(T));
    std::memcpy(v.data(), bytes.data(), bytes.size());
    return v;
}

render::Frame two_particles() {
    render::Frame f;
    f.position = {{1.5, -2.25, 0.0}, {0.1, 0.2, 0.3}};
    f.radius = {0.5, 0.7};
    f.species = {0, 1};
    f.species_names = {"A", "B"};
    f.velocity = {{3.0, 4.0, 0.0}, {0.0, 0.0, -2.0}};
    f.director = {{0.0, 1.0, 0.0}, {-1.0, 0.0, 0.0}};
    return f;
}

std::vector<float> colour(const render::Frame& f, std::string_view name) {
    const std::optional<std::string> bytes = colour_field_bytes(f, name);
    EXPECT_TRUE(bytes.has_value()) << name;
    return bytes ? decode<float>(*bytes) : std::vector<float>{};
}

TEST(ViewFrameArrays, FieldsAreTheFrameInParticleOrder) {
    const render::Frame f = two_particles();
    EXPECT_EQ(decode<float>(frame_bytes(f, Field::position)),
              (std::vector<float>{1.5f, -2.25f, 0.0f, 0.1f, 0.2f, 0.3f}));
    EXPECT_EQ(decode<float>(frame_bytes(f, Field::radius)), (std::vector<float>{0.5f, 0.7f}));
    EXPECT_EQ(decode<std::uint32_t>(frame_bytes(f, Field::species)),
              (std::vector<std::uint32_t>{0, 1}));
    EXPECT_EQ(decode<float>(frame_bytes(f, Field::director)),
              (std::vector<float>{0.0f, 1.0f, 0.0f, -1.0f, 0.0f, 0.0f}));
}

// The numbers to colour by, against values worked out by hand.
TEST(ViewFrameArrays, ColourFieldsAreDerivedExactly) {
    render::Frame f = two_particles();
    f.dimension = 3;
    f.scalars = {{"mass", {2.0, 0.5}}, {"c_pe", {-1.25, 3.0}}};
    EXPECT_EQ(colour_fields(f),
              (std::vector<std::string>{"speed", "vx", "vy", "vz", "kinetic_energy", "angle",
                                        "radius", "mass", "c_pe"}));
    // |(3, 4, 0)| = 5 exactly; |(0, 0, -2)| = 2
    EXPECT_EQ(colour(f, "speed"), (std::vector<float>{5.0f, 2.0f}));
    EXPECT_EQ(colour(f, "vx"), (std::vector<float>{3.0f, 0.0f}));
    EXPECT_EQ(colour(f, "vz"), (std::vector<float>{0.0f, -2.0f}));
    // m v^2 / 2: 2 * 25 / 2 = 25 and 0.5 * 4 / 2 = 1
    EXPECT_EQ(colour(f, "kinetic_energy"), (std::vector<float>{25.0f, 1.0f}));
    // (0, 1) points at +pi/2, (-1, 0) at pi
    const std::vector<float> angle = colour(f, "angle");
    EXPECT_FLOAT_EQ(angle[0], static_cast<float>(std::numbers::pi / 2));
    EXPECT_FLOAT_EQ(angle[1], static_cast<float>(std::numbers::pi));
    EXPECT_EQ(colour(f, "radius"), (std::vector<float>{0.5f, 0.7f}));
    EXPECT_EQ(colour(f, "c_pe"), (std::vector<float>{-1.25f, 3.0f}));
}

TEST(ViewFrameArrays, FieldNamesAndWhatAFrameLacks) {
    EXPECT_EQ(field_named("director"), Field::director);
    EXPECT_FALSE(field_named("speed").has_value()); // a number to colour by, not a field
    render::Frame f = two_particles();
    f.velocity.clear();
    f.director.clear();
    EXPECT_FALSE(frame_has(f, Field::director));
    EXPECT_TRUE(frame_has(f, Field::position));
    EXPECT_THROW(frame_bytes(f, Field::director), std::logic_error);
    // without velocities, directors, masses or columns of its own: radius only
    EXPECT_EQ(colour_fields(f), (std::vector<std::string>{"radius"}));
    EXPECT_FALSE(colour_field_bytes(f, "speed").has_value());
    EXPECT_FALSE(colour_field_bytes(f, "angle").has_value());
    EXPECT_FALSE(colour_field_bytes(f, "colour").has_value());
    // 2D: no vz; a stored array of the wrong length is not offered
    f = two_particles();
    f.scalars = {{"short", {1.0}}};
    const std::vector<std::string> names = colour_fields(f);
    EXPECT_EQ(std::count(names.begin(), names.end(), "vz"), 0);
    EXPECT_EQ(std::count(names.begin(), names.end(), "kinetic_energy"), 0); // no masses
    EXPECT_EQ(std::count(names.begin(), names.end(), "short"), 0);
}

} // namespace
} // namespace pedesis::view
