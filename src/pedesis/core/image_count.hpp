#pragma once
// Periodic image counts: how many boxes a particle has crossed along each axis, so that
// its unwrapped position is r + image * L (GSD's particles/image, the MSD).
#include "pedesis/core/box.hpp"
#include "pedesis/core/vec.hpp"

#include <array>
#include <cstdint>
#include <vector>

namespace pedesis {

template <int D> using ImageCount = std::array<std::int32_t, D>;

// Box::wrap's shift (whole boxes, as doubles) as counts.
template <int D> ImageCount<D> image_shift(const Vec<D>& shift) {
    ImageCount<D> k{};
    for (int a = 0; a < D; ++a) k[a] = static_cast<std::int32_t>(shift[a]);
    return k;
}

// Wraps r into the box and adds the boxes crossed to `image`.
template <int D> void wrap_counting(const Box<D>& box, Vec<D>& r, ImageCount<D>& image) {
    const Vec<D> shift = box.wrap(r);
    for (int a = 0; a < D; ++a) image[a] += static_cast<std::int32_t>(shift[a]);
}

template <int D> Vec<D> unwrapped(const Box<D>& box, const Vec<D>& r, const ImageCount<D>& image) {
    Vec<D> u = r;
    for (int a = 0; a < D; ++a) u[a] += image[a] * box.length(a);
    return u;
}

template <int D>
std::vector<Vec<D>> unwrapped_positions(const Box<D>& box, const std::vector<Vec<D>>& wrapped,
                                        const std::vector<ImageCount<D>>& images) {
    std::vector<Vec<D>> u(wrapped.size());
    for (std::size_t i = 0; i < wrapped.size(); ++i)
        u[i] = unwrapped<D>(box, wrapped[i], images[i]);
    return u;
}

} // namespace pedesis
