#include "pedesis/render/layout.hpp"

#include "pedesis/core/error.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>

namespace pedesis::render {

namespace {

constexpr int default_extent = 800;

// Decorations scale with the larger side, so a canvas of any shape has readable text.
struct Decor {
    double font, margin, header, sidebar, wall;
};

Decor decor_for(int width, int height, bool sidebar) {
    Decor d{};
    d.font = std::clamp(std::max(width, height) / 45.0, 9.0, 48.0);
    d.margin = std::max(4.0, 0.6 * d.font);
    d.header = 1.8 * d.font;
    d.sidebar = sidebar ? 5.5 * d.font : 0.0;
    d.wall = std::max(2.0, 0.22 * d.font);
    return d;
}

int even_up(double pixels) {
    const int n = static_cast<int>(std::ceil(pixels - 1e-9));
    return std::max(2, n + (n % 2));
}

} // namespace

Layout make_layout(int width, int height, const Frame& f, bool sidebar) {
    const Decor d = decor_for(width, height, sidebar);
    Layout L;
    L.width = width;
    L.height = height;
    L.font = d.font;
    L.margin = d.margin;
    L.header = d.header;
    L.sidebar = d.sidebar;
    L.wall = d.wall;

    const double area_x = d.margin, area_y = d.margin + d.header;
    const double area_w = width - 2.0 * d.margin - d.sidebar;
    const double area_h = height - 2.0 * d.margin - d.header;
    if (!(area_w >= 8.0 && area_h >= 8.0))
        throw InputError(fmt::format("--size {}x{} leaves no room for the box next to the time "
                                     "and colour bar; give a larger size",
                                     width, height));
    const double lx = f.box_length[0], ly = f.box_length[1];
    L.scale = std::min(area_w / lx, area_h / ly);
    L.box_w = lx * L.scale;
    L.box_h = ly * L.scale;
    L.left = area_x + 0.5 * (area_w - L.box_w);
    L.top = area_y + 0.5 * (area_h - L.box_h);
    L.x_lo = f.box_lo[0];
    L.y_hi = f.box_lo[1] + ly;
    return L;
}

std::pair<int, int> default_size(const Frame& f, bool sidebar) {
    const Decor d = decor_for(default_extent, default_extent, sidebar);
    const double aspect = f.box_length[0] / f.box_length[1];
    const double frame_w = 2.0 * d.margin + d.sidebar, frame_h = 2.0 * d.margin + d.header;
    double w = default_extent, h = default_extent;
    // The longer box side fills its direction; the other follows the aspect.
    if ((w - frame_w) / aspect <= h - frame_h)
        h = (w - frame_w) / aspect + frame_h;
    else
        w = (h - frame_h) * aspect + frame_w;
    // An extreme aspect still gets room for the decorations and at least a sliver of box.
    return {even_up(std::max(w, frame_w + 16.0)), even_up(std::max(h, frame_h + 16.0))};
}

} // namespace pedesis::render
