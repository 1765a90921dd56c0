#include "pedesis/render/colormap.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <numbers>

namespace pedesis::render {

namespace {

constexpr Rgb from_hex(unsigned hex) {
    return {((hex >> 16) & 0xFF) / 255.0, ((hex >> 8) & 0xFF) / 255.0, (hex & 0xFF) / 255.0};
}

constexpr std::array<Rgb, 10> tableau10 = {
    from_hex(0x4E79A7), from_hex(0xF28E2B), from_hex(0xE15759), from_hex(0x76B7B2),
    from_hex(0x59A14F), from_hex(0xEDC948), from_hex(0xB07AA1), from_hex(0xFF9DA7),
    from_hex(0x9C755F), from_hex(0xBAB0AC),
};

// Viridis sampled at 0, 0.1, ..., 1; linear in between is indistinguishable from the full map.
constexpr std::array<Rgb, 11> viridis = {
    from_hex(0x440154), from_hex(0x482475), from_hex(0x414487), from_hex(0x355F8D),
    from_hex(0x2A788E), from_hex(0x21918C), from_hex(0x22A884), from_hex(0x44BF70),
    from_hex(0x7AD151), from_hex(0xBDDF26), from_hex(0xFDE725),
};

} // namespace

Rgb species_colour(std::size_t index) {
    return tableau10[index % tableau10.size()];
}

Rgb speed_colour(double fraction) {
    if (!(fraction > 0.0)) return viridis.front(); // NaN too
    if (fraction >= 1.0) return viridis.back();
    const double x = fraction * static_cast<double>(viridis.size() - 1);
    const auto k = static_cast<std::size_t>(x);
    const double w = x - static_cast<double>(k);
    const Rgb& a = viridis[k];
    const Rgb& b = viridis[std::min(k + 1, viridis.size() - 1)];
    return {a.r + w * (b.r - a.r), a.g + w * (b.g - a.g), a.b + w * (b.b - a.b)};
}

Rgb angle_colour(double radians) {
    const double t = radians / (2.0 * std::numbers::pi);
    auto channel = [t](double phase) {
        const double s = std::sin(std::numbers::pi * (t + phase));
        return 0.1 + 0.8 * s * s; // kept off pure black and white
    };
    return {channel(0.0), channel(1.0 / 3.0), channel(2.0 / 3.0)};
}

double luminance(const Rgb& c) {
    return 0.2126 * c.r + 0.7152 * c.g + 0.0722 * c.b;
}

} // namespace pedesis::render
