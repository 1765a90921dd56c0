// Painting one frame: the pixel at each particle's centre carries the particle's colour
// (by species, speed or polarity angle), the background does not, periodic images and
// walls show where they should, 3D frames put the nearest particle on top, and a slab
// hides what lies outside it; a run's containers, traps and gravity show where they are.
// Also the PNG written, read back through Cairo.
#include "pedesis/core/error.hpp"
#include "pedesis/render/canvas.hpp"
#include "pedesis/render/colormap.hpp"
#include "pedesis/render/layout.hpp"
#include "pedesis/render/painter.hpp"

#include <cairo.h>
#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <numbers>
#include <tuple>
#include <unistd.h>

using namespace pedesis;
using namespace pedesis::render;
namespace fs = std::filesystem;

namespace {

struct Pixel {
    int r, g, b;
};

Pixel expected(const Rgb& c) {
    return {static_cast<int>(std::lround(255 * c.r)), static_cast<int>(std::lround(255 * c.g)),
            static_cast<int>(std::lround(255 * c.b))};
}

bool close(const Pixel& a, const Pixel& b, int tolerance = 1) {
    return std::abs(a.r - b.r) <= tolerance && std::abs(a.g - b.g) <= tolerance &&
           std::abs(a.b - b.b) <= tolerance;
}

std::ostream& operator<<(std::ostream& os, const Pixel& p) {
    return os << "(" << p.r << ", " << p.g << ", " << p.b << ")";
}

// A 20 x 10 box with walls on x and periodic in y; the last particle crosses the top edge.
Frame sample_frame() {
    Frame f;
    f.dimension = 2;
    f.box_lo = {-10.0, -5.0, 0.0};
    f.box_length = {20.0, 10.0, 0.0};
    f.periodic = {false, true, false};
    f.time = 1.5;
    f.species_names = {"A", "B"};
    f.position = {{-6, 0, 0}, {0, 2, 0}, {5, -2, 0}, {8.5, 4.6, 0}};
    f.radius = {1.0, 1.5, 0.8, 1.0};
    f.species = {0, 1, 0, 1};
    f.velocity = {{1, 0, 0}, {0, 2, 0}, {0.5, 0.5, 0}, {0, 0, 0}};
    f.director = {{1, 0, 0}, {0, 1, 0}, {-1, 0, 0}, {-0.96, -0.28, 0}};
    return f;
}

class Painted {
  public:
    Painted(const Frame& f, const Style& style, int width = 400, int height = 240,
            const Scenery& scenery = {})
        : canvas(width, height),
          layout(make_layout(width, height, f, style.colour != ColourBy::species)) {
        paint_frame(canvas, layout, f, style, 0, scenery);
        canvas.rgb_bytes(rgb);
    }
    Pixel at_canvas(double x, double y) const {
        const std::size_t i =
            3 * (static_cast<std::size_t>(y) * static_cast<std::size_t>(canvas.width()) +
                 static_cast<std::size_t>(x));
        return {rgb[i], rgb[i + 1], rgb[i + 2]};
    }
    Pixel at(double x, double y) const {
        const auto [cx, cy] = layout.to_canvas(x, y);
        return at_canvas(cx, cy);
    }

    Canvas canvas;
    Layout layout;
    std::vector<std::uint8_t> rgb;
};

const Pixel white{255, 255, 255};

TEST(RenderPainter, CentresCarryTheSpeciesColourAndTheBackgroundDoesNot) {
    const Frame f = sample_frame();
    const Painted p(f, Style{});
    for (std::size_t i = 0; i < f.size(); ++i) {
        const Pixel got = p.at(f.position[i][0], f.position[i][1]);
        EXPECT_TRUE(close(got, expected(species_colour(f.species[i])))) << i << ": " << got;
        EXPECT_FALSE(close(got, white, 40)) << i;
    }
    // Far from every particle, inside the box, and in the margin outside it.
    for (const auto& [x, y] : std::vector<std::array<double, 2>>{{-2, -3}, {-8, -4}, {3, 4}}) {
        const Pixel got = p.at(x, y);
        EXPECT_TRUE(close(got, white)) << x << "," << y << ": " << got;
        for (std::size_t k = 0; k < 2; ++k)
            EXPECT_FALSE(close(got, expected(species_colour(k)), 40));
    }
    EXPECT_TRUE(close(p.at_canvas(p.canvas.width() - 2, p.canvas.height() - 2), white));
}

TEST(RenderPainter, BoxIsDrawnToScaleInsideTheCanvas) {
    const Frame f = sample_frame();
    const Painted p(f, Style{}, 400, 240);
    EXPECT_NEAR(p.layout.box_w / p.layout.box_h, 2.0, 1e-12);
    EXPECT_GE(p.layout.left - p.layout.wall, 0.0);
    EXPECT_LE(p.layout.left + p.layout.box_w + p.layout.wall, 400.0);
    EXPECT_GE(p.layout.top, p.layout.header); // the time sits above the box
    EXPECT_LE(p.layout.top + p.layout.box_h, 240.0);
    // y points up: the box's top-left corner is (x lo, y hi), and (0, 2) is above the middle.
    EXPECT_EQ(p.layout.to_canvas(-10, 5), (std::array<double, 2>{p.layout.left, p.layout.top}));
    EXPECT_EQ(p.layout.to_canvas(10, -5), (std::array<double, 2>{p.layout.left + p.layout.box_w,
                                                                 p.layout.top + p.layout.box_h}));
    EXPECT_TRUE(close(
        p.at_canvas(p.layout.left + 0.5 * p.layout.box_w, p.layout.top + 0.3 * p.layout.box_h),
        expected(species_colour(1))));
    // A radius of 1.5 is 1.5 box units across on the canvas: the disk edge is there.
    const double r = 1.5 * p.layout.scale;
    const auto [cx, cy] = p.layout.to_canvas(0, 2);
    EXPECT_TRUE(close(p.at_canvas(cx + r - 3, cy), expected(species_colour(1)), 40));
    EXPECT_TRUE(close(p.at_canvas(cx + r + 3, cy), white));
}

TEST(RenderPainter, PeriodicImagesAndWalls) {
    const Frame f = sample_frame();
    const Painted p(f, Style{});
    // The disk at y = 4.6 (radius 1) reaches 0.6 past the top edge: its image shows at the
    // bottom edge, the periodic one; nothing wraps across the walled x edges.
    EXPECT_TRUE(close(p.at(8.5, -4.8), expected(species_colour(1))));
    EXPECT_TRUE(close(p.at(8.5, -4.2), white));
    const Layout& L = p.layout;
    const double mid_y = L.top + 0.5 * L.box_h, mid_x = L.left + 0.5 * L.box_w;
    // Walls (x): a thick dark line just outside the box on both sides.
    for (double x : {L.left - 0.5 * L.wall, L.left + L.box_w + 0.5 * L.wall}) {
        const Pixel wall = p.at_canvas(x, mid_y);
        EXPECT_LT(wall.r + wall.g + wall.b, 3 * 60) << wall;
    }
    // Periodic edges (y): only a thin line on the edge, white just beyond it.
    EXPECT_TRUE(close(p.at_canvas(mid_x, L.top - 3), white));
    EXPECT_TRUE(close(p.at_canvas(mid_x, L.top + L.box_h + 3), white));
}

TEST(RenderPainter, SpeedColoursFollowTheBar) {
    const Frame f = sample_frame();
    Style style;
    style.colour = ColourBy::speed;
    style.speed_max = 2.0;
    const Painted p(f, style);
    for (std::size_t i = 0; i < f.size(); ++i) {
        const auto& v = f.velocity[i];
        const Rgb c = speed_colour(std::sqrt(v[0] * v[0] + v[1] * v[1]) / 2.0);
        EXPECT_TRUE(close(p.at(f.position[i][0], f.position[i][1]), expected(c))) << i;
    }
    EXPECT_TRUE(close(expected(particle_colour(f, 1, style)), expected(speed_colour(1.0))));
}

TEST(RenderPainter, AngleColoursAndDirectorArrows) {
    const Frame f = sample_frame();
    Style style;
    style.colour = ColourBy::angle;
    const Painted with_arrows(f, style);
    style.arrows = false;
    const Painted without(f, style);
    for (std::size_t i = 0; i < f.size(); ++i) {
        const auto& n = f.director[i];
        const Pixel fill = expected(angle_colour(std::atan2(n[1], n[0])));
        const double x = f.position[i][0], y = f.position[i][1];
        // The arrow leaves the centre in the particle's colour...
        EXPECT_TRUE(close(with_arrows.at(x, y), fill)) << i;
        // ... and covers a point along the director, which is plain fill without arrows.
        const double d = 0.7 * f.radius[i]; // inside the arrow head
        EXPECT_FALSE(close(with_arrows.at(x + d * n[0], y + d * n[1]), fill, 20)) << i;
        EXPECT_TRUE(close(without.at(x + d * n[0], y + d * n[1]), fill)) << i;
        // Behind the centre there is no arrow.
        EXPECT_TRUE(close(with_arrows.at(x - d * n[0], y - d * n[1]), fill)) << i;
    }
}

Frame stacked_3d() {
    Frame f;
    f.dimension = 3;
    f.box_lo = {-5, -5, -5};
    f.box_length = {10, 10, 10};
    f.periodic = {true, true, true};
    f.species_names = {"low", "high"};
    f.position = {{0, 0, 1}, {0, 0, -1}}; // the higher one first in storage
    f.radius = {2, 2};
    f.species = {1, 0};
    return f;
}

double distance(const Pixel& a, const Rgb& c) {
    const Pixel b = expected(c);
    return std::hypot(a.r - b.r, a.g - b.g, a.b - b.b);
}

TEST(RenderPainter, ThreeDimensionsDrawTheNearestOnTopAndSlabsHideTheRest) {
    const Frame f = stacked_3d();
    const Painted projected(f, Style{});
    const Pixel top = projected.at(0, 0);
    EXPECT_LT(distance(top, species_colour(1)), distance(top, species_colour(0))) << top;

    Style slab;
    slab.slab = Slab{-2.0, 0.0};
    const Painted sliced(f, slab);
    const Pixel low = sliced.at(0, 0);
    EXPECT_LT(distance(low, species_colour(0)), distance(low, species_colour(1))) << low;
    slab.slab = Slab{2.0, 4.0};
    EXPECT_TRUE(close(Painted(f, slab).at(0, 0), white));
}

// Dark enough to be ink (the scenery's lines), not a particle's fill nor the background.
bool dark(const Pixel& p) {
    return p.r + p.g + p.b < 3 * 80;
}

// Particles only far from where the scenery goes: the pixels tested are the scenery's.
Frame open_box_2d() {
    Frame f;
    f.dimension = 2;
    f.box_lo = {-10.0, -10.0, 0.0};
    f.box_length = {20.0, 20.0, 0.0};
    f.species_names = {"A"};
    f.position = {{-8.5, -8.5, 0}};
    f.radius = {0.5};
    f.species = {0};
    return f;
}

TEST(RenderScenery, ContainerTrapAndGravityAreDrawnWhereTheyAre) {
    const Frame f = open_box_2d();
    Scenery scenery;
    scenery.containers.push_back({ContainerShape::sphere, 6.0, {1.0, -1.0, 0.0}, 2});
    scenery.traps.push_back({-4.0, 3.0, 0.0});
    scenery.pulls.push_back({0.0, -1.0, 0.0});
    Canvas with_canvas(800, 800), without_canvas(800, 800);
    const Layout L = make_layout(800, 800, f, false);
    paint_frame(with_canvas, L, f, Style{}, 0, scenery);
    paint_frame(without_canvas, L, f, Style{}, 0);
    std::vector<std::uint8_t> with, without;
    with_canvas.rgb_bytes(with);
    without_canvas.rgb_bytes(without);
    auto at = [&](const std::vector<std::uint8_t>& rgb, double x, double y) {
        const std::size_t i = 3 * (static_cast<std::size_t>(y) * 800 + static_cast<std::size_t>(x));
        return Pixel{rgb[i], rgb[i + 1], rgb[i + 2]};
    };

    // The container: a wall line just outside its radius, all round; inside and outside it
    // the background.
    const auto [cx, cy] = L.to_canvas(1.0, -1.0);
    const double ring = 6.0 * L.scale + 0.5 * L.wall;
    for (double angle = 0.1; angle < 6.2; angle += 0.7) {
        const double x = cx + ring * std::cos(angle), y = cy + ring * std::sin(angle);
        EXPECT_TRUE(dark(at(with, x, y))) << angle << ": " << at(with, x, y);
        EXPECT_TRUE(close(at(without, x, y), white)) << angle;
        for (double off : {-3.0 * L.wall, 3.0 * L.wall}) {
            const double xo = cx + (ring + off) * std::cos(angle);
            const double yo = cy + (ring + off) * std::sin(angle);
            EXPECT_TRUE(close(at(with, xo, yo), white)) << angle << " " << off;
        }
    }

    // The trap: a cross through its centre, nothing a few font sizes away.
    const auto [tx, ty] = L.to_canvas(-4.0, 3.0);
    for (const auto& [dx, dy] : std::vector<std::array<double, 2>>{{0, 0}, {0.6, 0}, {0, -0.6}})
        EXPECT_TRUE(dark(at(with, tx + dx * L.font, ty + dy * L.font))) << dx << "," << dy;
    EXPECT_TRUE(close(at(without, tx, ty), white));
    EXPECT_TRUE(close(at(with, tx + 2.0 * L.font, ty + 2.0 * L.font), white));

    // Gravity along -y: an arrow in the top right corner of the box, its head down.
    const double gx = L.left + L.box_w - 1.6 * L.font, gy = L.top + 1.6 * L.font;
    EXPECT_TRUE(dark(at(with, gx, gy)));
    EXPECT_TRUE(dark(at(with, gx + 0.15 * L.font, gy + 0.5 * L.font)));  // the head, wide
    EXPECT_FALSE(dark(at(with, gx + 0.15 * L.font, gy - 0.5 * L.font))); // the tail, thin
    EXPECT_TRUE(close(at(without, gx, gy), white));
}

TEST(RenderScenery, GravityAlongXPointsAlongXAndAlongZIsSeenEndOn) {
    const Frame f = open_box_2d();
    for (const Vec3& pull : std::vector<Vec3>{{1, 0, 0}, {-1, 0, 0}, {0, 0, -1}, {0, 0, 1}}) {
        Scenery scenery;
        scenery.pulls.push_back(pull);
        const Painted p(f, Style{}, 800, 800, scenery);
        const double font = p.layout.font;
        const double gx = p.layout.left + p.layout.box_w - 1.6 * font;
        const double gy = p.layout.top + 1.6 * font;
        if (pull[2] == 0.0) {
            // the head lies on the side the pull points to
            const double s = pull[0];
            EXPECT_TRUE(dark(p.at_canvas(gx + s * 0.5 * font, gy + 0.15 * font))) << pull[0];
            EXPECT_FALSE(dark(p.at_canvas(gx - s * 0.5 * font, gy + 0.15 * font))) << pull[0];
        } else {
            // into the picture (-z): a cross, dark at the middle's diagonal; out of it: a dot
            EXPECT_TRUE(dark(p.at_canvas(gx, gy))) << pull[2];
            EXPECT_EQ(dark(p.at_canvas(gx + 0.25 * font, gy + 0.25 * font)), pull[2] < 0.0)
                << pull[2];
        }
    }
}

TEST(RenderScenery, ThreeDimensionalContainersAreSeenThroughTheSlab) {
    Frame f = stacked_3d();
    f.position = {{-4.5, -4.5, 0}};
    f.radius = {0.2};
    f.species = {0};
    Scenery sphere;
    sphere.containers.push_back({ContainerShape::sphere, 4.0, {0.0, 0.0, 0.0}, 2});
    // Projected: the sphere's outline is a circle of radius 4; in the slab 3 <= z <= 5 its
    // widest slice is at z = 3, of radius sqrt(16 - 9).
    const Painted whole(f, Style{}, 600, 600, sphere);
    Style slab;
    slab.slab = Slab{3.0, 5.0};
    const Painted sliced(f, slab, 600, 600, sphere);
    const double w = whole.layout.wall;
    for (const auto& [p, radius, other] : std::vector<std::tuple<const Painted*, double, double>>{
             {&whole, 4.0, std::sqrt(7.0)}, {&sliced, std::sqrt(7.0), 4.0}}) {
        const auto [cx, cy] = p->layout.to_canvas(0, 0);
        EXPECT_TRUE(dark(p->at_canvas(cx + radius * p->layout.scale + 0.5 * w, cy))) << radius;
        EXPECT_TRUE(close(p->at_canvas(cx + other * p->layout.scale + 0.5 * w, cy), white))
            << radius;
    }
    slab.slab = Slab{4.5, 5.0}; // above the sphere: nothing of it
    const Painted above(f, slab, 600, 600, sphere);
    const auto [cx, cy] = above.layout.to_canvas(0, 0);
    EXPECT_TRUE(close(above.at_canvas(cx + 4.0 * above.layout.scale + 0.5 * w, cy), white));

    // A cylinder along x: a channel between two lines y = +-3 (from above, the whole width).
    Scenery channel;
    channel.containers.push_back({ContainerShape::cylinder, 3.0, {0.0, 0.0, 0.0}, 0});
    const Painted seen(f, Style{}, 600, 600, channel);
    for (double x : {-3.0, 0.0, 3.0})
        for (double side : {-1.0, 1.0}) {
            const auto [px, py] = seen.layout.to_canvas(x, side * 3.0);
            EXPECT_TRUE(dark(seen.at_canvas(px, py - side * 0.5 * w))) << x << " " << side;
        }
    EXPECT_TRUE(close(seen.at(0.0, 0.0), white));
}

TEST(RenderScenery, FarAwayOrHugeContainersDrawNothingAndDoNotHang) {
    const Frame f = open_box_2d();
    Scenery scenery;
    scenery.containers.push_back({ContainerShape::sphere, 1e300, {0.0, 0.0, 0.0}, 2});
    scenery.containers.push_back({ContainerShape::sphere, 1.0, {1e300, -1e300, 0.0}, 2});
    scenery.traps.push_back({1e300, 0.0, 0.0});
    const Painted p(f, Style{}, 400, 400, scenery);
    const Painted plain(f, Style{}, 400, 400);
    EXPECT_EQ(p.rgb, plain.rgb);
}

TEST(RenderPainter, PngWrittenHasTheSizeAndColours) {
    const Frame f = sample_frame();
    Painted p(f, Style{}, 320, 200);
    const fs::path png =
        fs::temp_directory_path() / ("pedesis_painter_" + std::to_string(::getpid()) + ".png");
    p.canvas.write_png(png);
    cairo_surface_t* s = cairo_image_surface_create_from_png(png.c_str());
    ASSERT_EQ(cairo_surface_status(s), CAIRO_STATUS_SUCCESS);
    EXPECT_EQ(cairo_image_surface_get_width(s), 320);
    EXPECT_EQ(cairo_image_surface_get_height(s), 200);
    const auto [cx, cy] = p.layout.to_canvas(f.position[1][0], f.position[1][1]);
    const unsigned char* row = cairo_image_surface_get_data(s) +
                               static_cast<std::ptrdiff_t>(cy) * cairo_image_surface_get_stride(s);
    std::uint32_t px;
    std::memcpy(&px, row + 4 * static_cast<int>(cx), 4);
    const Pixel got{static_cast<int>((px >> 16) & 0xFF), static_cast<int>((px >> 8) & 0xFF),
                    static_cast<int>(px & 0xFF)};
    EXPECT_TRUE(close(got, expected(species_colour(1)))) << got;
    cairo_surface_destroy(s);
    fs::remove(png);
    EXPECT_FALSE(fs::exists(png.string() + ".tmp." + std::to_string(::getpid())));
}

TEST(RenderLayout, DefaultSizeKeepsTheAspectWithEvenSides) {
    Frame f = sample_frame();
    for (bool sidebar : {false, true}) {
        for (const auto& [lx, ly] :
             std::vector<std::array<double, 2>>{{20, 10}, {10, 20}, {7, 7}, {1000, 3}}) {
            f.box_length = {lx, ly, 0};
            const auto [w, h] = default_size(f, sidebar);
            EXPECT_EQ(w % 2, 0);
            EXPECT_EQ(h % 2, 0);
            EXPECT_LE(std::max(w, h), 800);
            EXPECT_EQ(std::max(w, h), 800) << lx << "x" << ly;
            const Layout L = make_layout(w, h, f, sidebar);
            EXPECT_NEAR(L.box_w / L.box_h, lx / ly, 1e-9);
            // along the side that is 800 pixels long, the box fills what the decorations leave
            if (w == 800)
                EXPECT_NEAR(L.box_w, w - 2 * L.margin - L.sidebar, 1e-9) << lx << "x" << ly;
            else
                EXPECT_NEAR(L.box_h, h - 2 * L.margin - L.header, 1e-9) << lx << "x" << ly;
        }
    }
    EXPECT_THROW(make_layout(64, 64, sample_frame(), true), InputError);
}

TEST(RenderColourMaps, EndsAndCycles) {
    EXPECT_TRUE(close(expected(speed_colour(0.0)), Pixel{0x44, 0x01, 0x54}));
    EXPECT_TRUE(close(expected(speed_colour(1.0)), Pixel{0xFD, 0xE7, 0x25}));
    EXPECT_TRUE(close(expected(speed_colour(7.0)), expected(speed_colour(1.0))));
    for (double a : {0.0, 1.0, 2.5})
        EXPECT_TRUE(
            close(expected(angle_colour(a)), expected(angle_colour(a + 2.0 * std::numbers::pi))));
    EXPECT_FALSE(close(expected(angle_colour(0.0)), expected(angle_colour(std::numbers::pi)), 40));
    for (std::size_t k = 0; k < 10; ++k) {
        EXPECT_FALSE(close(expected(species_colour(k)), white, 40)) << k;
        for (std::size_t j = 0; j < k; ++j)
            EXPECT_FALSE(close(expected(species_colour(k)), expected(species_colour(j)), 20));
    }
}

} // namespace
