#pragma once
// Draws a run's scenery (scenery.hpp) over its particles: each container's outline as a
// wall line, each trap's centre as a marker, and an arrow in the box's top right corner
// for each direction gravity pulls in.
#include "pedesis/render/layout.hpp"
#include "pedesis/render/painter.hpp"
#include "pedesis/render/scenery.hpp"

#include <cairo.h>

namespace pedesis::render {

void draw_scenery(cairo_t* cr, const Layout& L, const Frame& f, const Scenery& scenery,
                  const Style& style);

} // namespace pedesis::render
