// The arrays `pedesis view` sends: exact float32/uint32 images of a frame's fields.
#include "pedesis/view/frame_arrays.hpp"

#include <gtest/gtest.h>

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

TEST(ViewFrameArrays, FieldsAreTheFrameInParticleOrder) {
    const render::Frame f = two_particles();
    EXPECT_EQ(decode<float>(frame_bytes(f, Field::position)),
              (std::vector<float>{1.5f, -2.25f, 0.0f, 0.1f, 0.2f, 0.3f}));
    EXPECT_EQ(decode<float>(frame_bytes(f, Field::radius)), (std::vector<float>{0.5f, 0.7f}));
    EXPECT_EQ(decode<std::uint32_t>(frame_bytes(f, Field::species)),
              (std::vector<std::uint32_t>{0, 1}));
    // |(3, 4, 0)| = 5 exactly; |(0, 0, -2)| = 2
    EXPECT_EQ(decode<float>(frame_bytes(f, Field::speed)), (std::vector<float>{5.0f, 2.0f}));
    // (0, 1) points at +pi/2, (-1, 0) at pi
    const std::vector<float> angle = decode<float>(frame_bytes(f, Field::angle));
    EXPECT_FLOAT_EQ(angle[0], static_cast<float>(std::numbers::pi / 2));
    EXPECT_FLOAT_EQ(angle[1], static_cast<float>(std::numbers::pi));
}

TEST(ViewFrameArrays, FieldNamesAndWhatAFrameLacks) {
    EXPECT_EQ(field_named("speed"), Field::speed);
    EXPECT_FALSE(field_named("colour").has_value());
    render::Frame f = two_particles();
    f.velocity.clear();
    f.director.clear();
    EXPECT_FALSE(frame_has(f, Field::speed));
    EXPECT_FALSE(frame_has(f, Field::angle));
    EXPECT_FALSE(frame_has(f, Field::director));
    EXPECT_TRUE(frame_has(f, Field::position));
    EXPECT_THROW(frame_bytes(f, Field::speed), std::logic_error);
}

} // namespace
} // namespace pedesis::view
