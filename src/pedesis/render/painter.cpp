#include "pedesis/render/painter.hpp"

#include "pedesis/core/error.hpp"
#include "pedesis/core/interrupt.hpp"
#include "pedesis/render/scenery_painter.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <numeric>
#include <string>
#include <vector>

namespace pedesis::render {

namespace {

constexpr double two_pi = 2.0 * std::numbers::pi;
constexpr Rgb ink{0.1, 0.1, 0.1};
constexpr Rgb periodic_edge{0.55, 0.55, 0.55};

void set_colour(cairo_t* cr, const Rgb& c) {
    cairo_set_source_rgb(cr, c.r, c.g, c.b);
}

Rgb darker(const Rgb& c) {
    return {0.55 * c.r, 0.55 * c.g, 0.55 * c.b};
}

void set_font(cairo_t* cr, double size) {
    cairo_select_font_face(cr, "sans-serif", CAIRO_FONT_SLANT_NORMAL, CAIRO_FONT_WEIGHT_NORMAL);
    cairo_set_font_size(cr, size);
}

double text_width(cairo_t* cr, const std::string& text) {
    cairo_text_extents_t e;
    cairo_text_extents(cr, text.c_str(), &e);
    return e.x_advance;
}

void show_text(cairo_t* cr, double x, double baseline, const std::string& text) {
    cairo_move_to(cr, x, baseline);
    cairo_show_text(cr, text.c_str());
}

// A depth cue for 3D: the deepest particles (depth 1) are blended 40% towards the white
// background, the topmost (depth 0) keep their colour.
Rgb faded(const Rgb& c, double depth) {
    const double w = 0.4 * depth;
    return {c.r + w * (1.0 - c.r), c.g + w * (1.0 - c.g), c.b + w * (1.0 - c.b)};
}

// Into [lo, lo + L) on a periodic axis, so images are found from one copy.
double wrapped(double x, double lo, double length) {
    const double u = std::fmod(x - lo, length);
    return lo + (u < 0.0 ? u + length : u);
}

// The arrow sits between 0.3 and 0.95 of the radius, shortened by the director's tilt out of
// the xy plane, and leaves the centre pixel in the particle's colour.
void draw_arrow(cairo_t* cr, double cx, double cy, double r, const Vec3& n, const Rgb& fill) {
    const double len = std::sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
    const double planar = std::hypot(n[0], n[1]);
    if (!(len > 0.0) || planar < 0.15 * len) return;      // seen end-on: no direction to show
    const double ux = n[0] / planar, uy = -n[1] / planar; // canvas y points down
    const double start = 0.3 * r, tip = (0.3 + 0.65 * planar / len) * r;
    const double head = std::min(0.35 * r, tip - start);
    const double half_width = 0.6 * head;
    const double base = tip - head;

    set_colour(cr, luminance(fill) < 0.45 ? Rgb{1.0, 1.0, 1.0} : ink);
    cairo_set_line_width(cr, std::max(1.0, 0.1 * r));
    cairo_set_line_cap(cr, CAIRO_LINE_CAP_BUTT);
    if (base > start) {
        cairo_move_to(cr, cx + start * ux, cy + start * uy);
        cairo_line_to(cr, cx + base * ux, cy + base * uy);
        cairo_stroke(cr);
    }
    cairo_move_to(cr, cx + tip * ux, cy + tip * uy);
    cairo_line_to(cr, cx + base * ux - half_width * uy, cy + base * uy + half_width * ux);
    cairo_line_to(cr, cx + base * ux + half_width * uy, cy + base * uy - half_width * ux);
    cairo_close_path(cr);
    cairo_fill(cr);
}

void draw_disk(cairo_t* cr, double cx, double cy, double r, const Rgb& fill) {
    cairo_new_path(cr);
    cairo_arc(cr, cx, cy, r, 0.0, two_pi);
    set_colour(cr, fill);
    if (r < 2.5) { // an outline would swallow a disk this small
        cairo_fill(cr);
        return;
    }
    cairo_fill_preserve(cr);
    set_colour(cr, darker(fill));
    cairo_set_line_width(cr, std::clamp(0.1 * r, 0.5, 2.0));
    cairo_stroke(cr);
}

// Copies of a coordinate needed to show a disk of radius r that crosses a periodic edge.
std::vector<double> images(double x, double r, double lo, double length, bool periodic) {
    if (!periodic || !(length > 0.0)) return {x};
    x = wrapped(x, lo, length);
    std::vector<double> out{x};
    if (x - lo < r) out.push_back(x + length);
    if (lo + length - x < r) out.push_back(x - length);
    return out;
}

void draw_particles(cairo_t* cr, const Layout& L, const Frame& f, const Style& s) {
    std::vector<std::size_t> order;
    order.reserve(f.size());
    for (std::size_t i = 0; i < f.size(); ++i) {
        const double z = f.position[i][2];
        if (!s.slab || (z >= s.slab->lo && z <= s.slab->hi)) order.push_back(i);
    }
    // Looking down the z axis: the nearest (largest z) are painted last, on top.
    if (f.dimension == 3)
        std::stable_sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) {
            return f.position[a][2] < f.position[b][2];
        });

    cairo_save(cr);
    cairo_rectangle(cr, L.left, L.top, L.box_w, L.box_h);
    cairo_clip(cr);
    const bool arrows = s.arrows && !f.director.empty();
    const double z_lo = s.slab ? s.slab->lo : f.box_lo[2];
    const double z_range = s.slab ? s.slab->hi - s.slab->lo : f.box_length[2];
    // A disk wider than the whole picture looks the same as one just covering it; Cairo
    // would approximate a huge one with ever more segments (a radius of 1e308 never ended).
    const double widest = 2.0 * (L.box_w + L.box_h);
    std::size_t drawn = 0;
    for (std::size_t i : order) {
        // a frame of 10^5 disks takes seconds: a signal must not wait for its end (the
        // render's close removes the half-made movie; core/interrupt.hpp)
        if ((++drawn & 1023u) == 0 && interrupt_requested())
            throw InputError("render interrupted while drawing a frame");
        const double r = std::min(f.radius[i] * L.scale, widest);
        if (!(r > 0.0)) continue;
        Rgb fill = particle_colour(f, i, s);
        if (f.dimension == 3 && z_range > 0.0)
            fill = faded(fill, 1.0 - std::clamp((f.position[i][2] - z_lo) / z_range, 0.0, 1.0));
        const auto& p = f.position[i];
        for (double x : images(p[0], f.radius[i], f.box_lo[0], f.box_length[0], f.periodic[0]))
            for (double y :
                 images(p[1], f.radius[i], f.box_lo[1], f.box_length[1], f.periodic[1])) {
                const auto [cx, cy] = L.to_canvas(x, y);
                draw_disk(cr, cx, cy, r, fill);
                if (arrows && r >= 3.0) draw_arrow(cr, cx, cy, r, f.director[i], fill);
            }
    }
    cairo_restore(cr);
}

// Periodic edges thin and dashed; walls thick and solid, just outside the box so they
// hide no particle touching them.
void draw_box(cairo_t* cr, const Layout& L, const Frame& f) {
    const double x0 = L.left, y0 = L.top, x1 = L.left + L.box_w, y1 = L.top + L.box_h;
    const bool wall_x = !f.periodic[0], wall_y = !f.periodic[1];

    cairo_save(cr);
    set_colour(cr, periodic_edge);
    cairo_set_line_width(cr, 1.0);
    const double dash[] = {4.0, 3.0};
    cairo_set_dash(cr, dash, 2, 0.0);
    if (!wall_x) {
        cairo_move_to(cr, x0, y0);
        cairo_line_to(cr, x0, y1);
        cairo_move_to(cr, x1, y0);
        cairo_line_to(cr, x1, y1);
    }
    if (!wall_y) {
        cairo_move_to(cr, x0, y0);
        cairo_line_to(cr, x1, y0);
        cairo_move_to(cr, x0, y1);
        cairo_line_to(cr, x1, y1);
    }
    cairo_stroke(cr);
    cairo_restore(cr);

    const double w = L.wall, h = 0.5 * L.wall;
    set_colour(cr, ink);
    cairo_set_line_width(cr, w);
    cairo_set_line_cap(cr, CAIRO_LINE_CAP_BUTT);
    // Wall lines run on past the corners when the neighbouring edge is a wall too, so
    // corners are closed.
    const double ex = wall_y ? w : 0.0, ey = wall_x ? w : 0.0;
    if (wall_x) {
        cairo_move_to(cr, x0 - h, y0 - ex);
        cairo_line_to(cr, x0 - h, y1 + ex);
        cairo_move_to(cr, x1 + h, y0 - ex);
        cairo_line_to(cr, x1 + h, y1 + ex);
    }
    if (wall_y) {
        cairo_move_to(cr, x0 - ey, y0 - h);
        cairo_line_to(cr, x1 + ey, y0 - h);
        cairo_move_to(cr, x0 - ey, y1 + h);
        cairo_line_to(cr, x1 + ey, y1 + h);
    }
    cairo_stroke(cr);
}

std::string caption(const Frame& f, const Style& s, std::size_t frame_index) {
    std::string text;
    if (f.time) text = fmt::format("t = {:.6g}", *f.time);
    if (f.step) text += fmt::format("{}step {}", text.empty() ? "" : "   ", *f.step);
    if (text.empty()) text = fmt::format("frame {}", frame_index);
    if (f.dimension == 3)
        text += s.slab
                    ? fmt::format("   slab {:.4g} \u2264 z \u2264 {:.4g}", s.slab->lo, s.slab->hi)
                    : std::string("   projection onto xy");
    return text;
}

void draw_header(cairo_t* cr, const Layout& L, const Frame& f, const Style& s,
                 std::size_t frame_index) {
    set_font(cr, L.font);
    const double baseline = L.margin + 1.15 * L.font;
    const std::string text = caption(f, s, frame_index);
    set_colour(cr, ink);
    show_text(cr, L.margin, baseline, text);
    const double used = L.margin + text_width(cr, text) + 2.0 * L.font;

    if (s.colour != ColourBy::species) {
        const std::string title = s.colour == ColourBy::speed ? "speed" : "angle";
        show_text(cr, L.width - L.margin - L.sidebar + 1.2 * L.font, baseline, title);
        return;
    }
    // The species legend, right-aligned, when it fits beside the caption.
    const double dot = 0.35 * L.font, gap = 0.4 * L.font, spacing = 1.0 * L.font;
    double total = 0.0;
    for (const std::string& name : f.species_names)
        total += 2.0 * dot + gap + text_width(cr, name) + spacing;
    if (f.species_names.empty() || L.width - L.margin - total < used) return;
    double x = L.width - L.margin - total + spacing;
    for (std::size_t k = 0; k < f.species_names.size(); ++k) {
        cairo_new_path(cr);
        cairo_arc(cr, x + dot, baseline - 0.35 * L.font, dot, 0.0, two_pi);
        set_colour(cr, species_colour(k));
        cairo_fill(cr);
        x += 2.0 * dot + gap;
        set_colour(cr, ink);
        show_text(cr, x, baseline, f.species_names[k]);
        x += text_width(cr, f.species_names[k]) + spacing;
    }
}

// A round step giving three to six ticks from 0 to `top`: 1, 2, 2.5 or 5 times a power of ten.
double tick_step(double top) {
    const double raw = top / 5.0;
    const double magnitude = std::pow(10.0, std::floor(std::log10(raw)));
    for (double m : {1.0, 2.0, 2.5, 5.0})
        if (m * magnitude >= raw) return m * magnitude;
    return 10.0 * magnitude;
}

void draw_colour_bar(cairo_t* cr, const Layout& L, const Style& s) {
    const double x = L.width - L.margin - L.sidebar + 1.2 * L.font, w = 0.9 * L.font;
    const double top = L.top, height = L.box_h;
    const int stripes = 256;
    for (int k = 0; k < stripes; ++k) {
        const double fraction = (k + 0.5) / stripes;
        set_colour(cr, s.colour == ColourBy::speed ? speed_colour(fraction)
                                                   : angle_colour(two_pi * fraction));
        const double y = top + height * (1.0 - static_cast<double>(k + 1) / stripes);
        cairo_rectangle(cr, x, y, w, height / stripes + 0.5);
        cairo_fill(cr);
    }
    set_colour(cr, periodic_edge);
    cairo_set_line_width(cr, 1.0);
    cairo_rectangle(cr, x, top, w, height);
    cairo_stroke(cr);

    set_font(cr, 0.8 * L.font);
    set_colour(cr, ink);
    const bool speed = s.colour == ColourBy::speed;
    const double top_value = speed ? s.speed_max : 360.0;
    const double step = speed ? tick_step(s.speed_max) : 90.0;
    for (int k = 0; k * step <= top_value * (1.0 + 1e-9); ++k) {
        const double value = k * step;
        const std::string label =
            speed ? fmt::format("{:.4g}", value) : fmt::format("{:g}\u00b0", value);
        const double y = top + height * (1.0 - value / top_value);
        cairo_move_to(cr, x + w, y);
        cairo_line_to(cr, x + w + 0.25 * L.font, y);
        cairo_stroke(cr);
        show_text(cr, x + w + 0.4 * L.font, y + 0.3 * L.font, label);
    }
}

} // namespace

Rgb particle_colour(const Frame& f, std::size_t i, const Style& style) {
    switch (style.colour) {
    case ColourBy::speed: {
        const Vec3& v = f.velocity[i];
        return speed_colour(std::sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]) / style.speed_max);
    }
    case ColourBy::angle:
        return angle_colour(std::atan2(f.director[i][1], f.director[i][0]));
    case ColourBy::species:
        break;
    }
    return species_colour(f.species[i]);
}

void paint_frame(Canvas& canvas, const Layout& layout, const Frame& f, const Style& style,
                 std::size_t frame_index, const Scenery& scenery) {
    cairo_t* cr = canvas.context();
    cairo_save(cr);
    cairo_set_source_rgb(cr, 1.0, 1.0, 1.0);
    cairo_paint(cr);
    draw_particles(cr, layout, f, style);
    draw_box(cr, layout, f);
    draw_scenery(cr, layout, f, scenery, style);
    draw_header(cr, layout, f, style, frame_index);
    if (style.colour != ColourBy::species) draw_colour_bar(cr, layout, style);
    cairo_restore(cr);
}

} // namespace pedesis::render
