#pragma once
// Where things go on the canvas: a band above the box for the time and the legend, a
// panel on the right for the colour bar, and the box in between, to scale (equal pixels
// per unit on both axes, y pointing up).
#include "pedesis/render/frame.hpp"

#include <array>
#include <utility>

namespace pedesis::render {

struct Layout {
    int width = 0, height = 0;
    double font = 0.0;               // text size, pixels
    double margin = 0.0;             // around everything
    double header = 0.0;             // height of the band above the box
    double sidebar = 0.0;            // width of the colour-bar panel; 0 without one
    double wall = 0.0;               // thickness of a wall line
    double scale = 0.0;              // pixels per unit length
    double left = 0.0, top = 0.0;    // canvas point of the box corner (x low, y high)
    double box_w = 0.0, box_h = 0.0; // the box on the canvas, pixels
    double x_lo = 0.0, y_hi = 0.0;   // that corner in simulation units

    std::array<double, 2> to_canvas(double x, double y) const {
        return {left + (x - x_lo) * scale, top + (y_hi - y) * scale};
    }
};

// The layout of a width x height canvas for the frame's box (x and y edges). InputError
// when the canvas leaves no room for the box.
Layout make_layout(int width, int height, const Frame& f, bool sidebar);

// The box's aspect fitted into 800 x 800 with its decorations, each side rounded up to an
// even number of pixels (H.264 in yuv420p needs even sizes).
std::pair<int, int> default_size(const Frame& f, bool sidebar);

} // namespace pedesis::render
