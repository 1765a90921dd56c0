#pragma once
// Paints one frame: disks to scale in their colours (with their periodic images across
// periodic edges), director arrows, the box with its walls drawn thick, the run's
// containers, traps and gravity, the time, and a legend or colour bar.
#include "pedesis/render/canvas.hpp"
#include "pedesis/render/colormap.hpp"
#include "pedesis/render/frame.hpp"
#include "pedesis/render/layout.hpp"
#include "pedesis/render/scenery.hpp"

#include <cstddef>
#include <optional>

namespace pedesis::render {

enum class ColourBy { species, speed, angle };

struct Slab {
    double lo = 0.0, hi = 0.0; // centres with lo <= z <= hi are drawn
};

struct Style {
    ColourBy colour = ColourBy::species;
    double speed_max = 1.0; // the top of the speed colour bar
    std::optional<Slab> slab;
    bool arrows = true;
};

// The fill of particle i. Speed needs the frame's velocities, angle its directors.
Rgb particle_colour(const Frame& f, std::size_t i, const Style& style);

// `frame_index` labels frames that carry neither a time nor a step; `scenery` (the run's
// containers, traps and gravity: scenery.hpp) is drawn over the particles.
void paint_frame(Canvas& canvas, const Layout& layout, const Frame& f, const Style& style,
                 std::size_t frame_index, const Scenery& scenery = {});

} // namespace pedesis::render
