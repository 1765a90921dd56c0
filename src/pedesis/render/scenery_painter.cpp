#include "pedesis/render/scenery_painter.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <optional>

namespace pedesis::render {

namespace {

constexpr double two_pi = 2.0 * std::numbers::pi;
constexpr Rgb ink{0.1, 0.1, 0.1};

// The half-width of a round cross-section of radius R, centred at c along the depth axis,
// seen through [lo, hi] of that axis: its widest slice there, or none.
std::optional<double> seen_radius(double R, double c, const Slab* slab) {
    if (!slab) return R;
    const double d = c < slab->lo ? slab->lo - c : (c > slab->hi ? c - slab->hi : 0.0);
    if (d >= R) return std::nullopt;
    return std::sqrt(R * R - d * d);
}

// A stroke in ink over a white halo, so that it stands out over particles of any colour.
void stroke_with_halo(cairo_t* cr, double width) {
    cairo_set_source_rgb(cr, 1.0, 1.0, 1.0);
    cairo_set_line_width(cr, width + 2.0);
    cairo_stroke_preserve(cr);
    cairo_set_source_rgb(cr, ink.r, ink.g, ink.b);
    cairo_set_line_width(cr, width);
    cairo_stroke(cr);
}

// Outlines as the box's walls are drawn: thick, just outside the container, so they hide no
// particle touching it. On the xy picture a cylinder along z (and a sphere) is a circle, a
// cylinder along x or y a channel between two lines.
void draw_container(cairo_t* cr, const Layout& L, const Frame& f, const Container& c,
                    const Style& s, double far) {
    const Slab* slab = f.dimension == 3 && s.slab ? &*s.slab : nullptr;
    const bool round = c.shape == ContainerShape::sphere || c.axis == 2;
    // a slab cuts a sphere, or a channel's round section across z, to its widest slice
    const auto r = c.shape == ContainerShape::cylinder && c.axis == 2
                       ? std::optional<double>(c.radius)
                       : seen_radius(c.radius, c.centre[2], slab);
    if (!r) return;
    const double pixels = *r * L.scale + 0.5 * L.wall;
    const auto [cx, cy] = L.to_canvas(c.centre[0], c.centre[1]);
    // Cairo approximates a huge arc with ever more segments: what is that far off is not
    // in the picture anyway
    if (!(pixels < far && std::abs(cx) < far && std::abs(cy) < far)) return;
    cairo_new_path(cr);
    if (round) {
        cairo_arc(cr, cx, cy, pixels, 0.0, two_pi);
    } else if (c.axis == 0) { // along x: walls at y = centre +- r
        for (double y : {cy - pixels, cy + pixels}) {
            cairo_move_to(cr, L.left - L.wall, y);
            cairo_line_to(cr, L.left + L.box_w + L.wall, y);
        }
    } else {
        for (double x : {cx - pixels, cx + pixels}) {
            cairo_move_to(cr, x, L.top - L.wall);
            cairo_line_to(cr, x, L.top + L.box_h + L.wall);
        }
    }
    cairo_set_source_rgb(cr, ink.r, ink.g, ink.b);
    cairo_set_line_width(cr, L.wall);
    cairo_stroke(cr);
}

// A ring with a cross through it, a font size across.
void draw_trap(cairo_t* cr, const Layout& L, const Vec3& centre, double far) {
    const auto [cx, cy] = L.to_canvas(centre[0], centre[1]);
    if (!(std::abs(cx) < far && std::abs(cy) < far)) return;
    const double ring = 0.45 * L.font, arm = 0.8 * L.font;
    cairo_new_path(cr);
    cairo_arc(cr, cx, cy, ring, 0.0, two_pi);
    cairo_move_to(cr, cx - arm, cy);
    cairo_line_to(cr, cx + arm, cy);
    cairo_move_to(cr, cx, cy - arm);
    cairo_line_to(cr, cx, cy + arm);
    stroke_with_halo(cr, std::max(1.5, 0.15 * L.font));
}

// An arrow two font sizes long centred on (x, y); along z (seen end-on) a circle holding a
// cross (pointing away from the viewer, who looks down from +z) or a dot (towards).
void draw_pull(cairo_t* cr, const Layout& L, const Vec3& pull, double x, double y) {
    const double width = std::max(1.5, 0.15 * L.font);
    cairo_new_path(cr);
    if (pull[2] != 0.0) {
        const double r = 0.6 * L.font, a = r / std::numbers::sqrt2;
        cairo_arc(cr, x, y, r, 0.0, two_pi);
        if (pull[2] < 0.0) {
            cairo_move_to(cr, x - a, y - a);
            cairo_line_to(cr, x + a, y + a);
            cairo_move_to(cr, x - a, y + a);
            cairo_line_to(cr, x + a, y - a);
            stroke_with_halo(cr, width);
        } else {
            stroke_with_halo(cr, width);
            cairo_arc(cr, x, y, 0.2 * r + 1.0, 0.0, two_pi);
            cairo_fill(cr);
        }
        return;
    }
    const double ux = pull[0], uy = -pull[1]; // canvas y points down
    const double half = L.font, head = 0.6 * L.font;
    const double tx = x + half * ux, ty = y + half * uy;
    cairo_move_to(cr, x - half * ux, y - half * uy);
    cairo_line_to(cr, tx - head * ux, ty - head * uy);
    stroke_with_halo(cr, width);
    cairo_move_to(cr, tx, ty);
    cairo_line_to(cr, tx - head * ux - 0.5 * head * uy, ty - head * uy + 0.5 * head * ux);
    cairo_line_to(cr, tx - head * ux + 0.5 * head * uy, ty - head * uy - 0.5 * head * ux);
    cairo_close_path(cr);
    cairo_set_source_rgb(cr, 1.0, 1.0, 1.0);
    cairo_set_line_width(cr, 2.0);
    cairo_stroke_preserve(cr);
    cairo_set_source_rgb(cr, ink.r, ink.g, ink.b);
    cairo_fill(cr);
}

} // namespace

void draw_scenery(cairo_t* cr, const Layout& L, const Frame& f, const Scenery& scenery,
                  const Style& style) {
    if (scenery.empty()) return;
    cairo_save(cr);
    cairo_rectangle(cr, L.left - 2.0 * L.wall, L.top - 2.0 * L.wall, L.box_w + 4.0 * L.wall,
                    L.box_h + 4.0 * L.wall);
    cairo_clip(cr);
    cairo_set_line_cap(cr, CAIRO_LINE_CAP_BUTT);
    const double far = 4.0 * (L.width + L.height);
    for (const Container& c : scenery.containers) draw_container(cr, L, f, c, style, far);
    for (const Vec3& t : scenery.traps) draw_trap(cr, L, t, far);
    double x = L.left + L.box_w - 1.6 * L.font;
    const double y = L.top + 1.6 * L.font;
    for (const Vec3& pull : scenery.pulls) {
        draw_pull(cr, L, pull, x, y);
        x -= 2.6 * L.font;
    }
    cairo_restore(cr);
}

} // namespace pedesis::render
