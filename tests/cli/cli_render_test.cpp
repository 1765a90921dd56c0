// `pedesis render` through the real binary: a small event run drawn to PNG frames of the
// requested size (the pixel at every particle's centre has its species' colour, the
// background does not), to an MP4 and a GIF that ffprobe counts frame by frame, a soft
// run's GSD with directors, the containers, traps and gravity of the run's config, and bad
// input: missing or corrupt run directories, no ffmpeg,
// an ffmpeg that fails (no movie may be left under its name), and bad options.
#include "cli/cli_support.hpp"

#include "pedesis/io/xyz_reader.hpp"
#include "pedesis/render/colormap.hpp"
#include "pedesis/render/layout.hpp"
#include "pedesis/render/run_directory.hpp"

#include <cairo.h>

#include <cmath>
#include <cstring>
#include <regex>

namespace pedesis::test {
namespace {

namespace fs = std::filesystem;

// 20 disks of two species in a 20 x 16 box, walls on x, periodic on y; 5 frames.
const std::string gas_config = R"(dimension = 2
seed = 4
[box]
lengths = [20.0, 16.0]
boundary = ["wall", "periodic"]
[[species]]
name = "A"
count = 14
radius = 0.7
mass = 1.0
[[species]]
name = "B"
count = 6
radius = 1.2
mass = 3.0
[run]
time = 2.0
[output]
log_interval = 0.5
snapshot_interval = 0.5
progress = false
formats = ["xyz"]
)";

const std::string soft_config = R"(dimension = 2
dynamics = "brownian"
seed = 1
[box]
length = 20.0
[[species]]
name = "A"
count = 30
radius = 1.0
[initial]
positions = "random"
[[force]]
name = "harmonic"
k = 10.0
[[force]]
name = "self_propulsion"
alpha = 1.0
[[integrator]]
name = "brownian"
T = 0.0
gamma = 1.0
[[integrator]]
name = "brownian_rotation"
T = 0.1
gamma = 1.0
[run]
steps = 20
dt = 0.01
[output]
snapshot_every = 10
formats = ["gsd"]
progress = false
)";

// pedesis with PATH set to `path` only.
CliResult run_with_path(const std::string& args, const fs::path& path, const fs::path& dir) {
    return shell("PATH='" + path.string() + "' '" + PEDESIS_BINARY + "' " + args, dir);
}

int ffprobe_frames(const fs::path& movie, const fs::path& dir) {
    const auto r = shell("ffprobe -v error -count_frames -select_streams v:0 -show_entries "
                         "stream=nb_read_frames -of csv=p=0 '" +
                             movie.string() + "'",
                         dir);
    EXPECT_EQ(r.exit_code, 0) << r.output;
    return std::atoi(r.output.c_str());
}

std::string ffprobe_size(const fs::path& movie, const fs::path& dir) {
    auto r = shell("ffprobe -v error -select_streams v:0 -show_entries stream=width,height "
                   "-of csv=p=0 '" +
                       movie.string() + "'",
                   dir);
    while (!r.output.empty() && std::isspace(static_cast<unsigned char>(r.output.back())))
        r.output.pop_back();
    return r.output;
}

// Files in `dir` whose name starts with `prefix`: leftovers of an atomic write.
std::vector<std::string> files_starting(const fs::path& dir, const std::string& prefix) {
    std::vector<std::string> found;
    for (const auto& e : fs::directory_iterator(dir))
        if (e.path().filename().string().rfind(prefix, 0) == 0)
            found.push_back(e.path().filename().string());
    return found;
}

struct Image {
    int width = 0, height = 0;
    std::vector<std::uint32_t> pixels; // 0x00RRGGBB

    std::array<int, 3> at(double x, double y) const {
        const std::uint32_t p =
            pixels.at(static_cast<std::size_t>(y) * width + static_cast<std::size_t>(x));
        return {static_cast<int>((p >> 16) & 0xFF), static_cast<int>((p >> 8) & 0xFF),
                static_cast<int>(p & 0xFF)};
    }
};

Image read_png(const fs::path& file) {
    Image img;
    cairo_surface_t* s = cairo_image_surface_create_from_png(file.c_str());
    EXPECT_EQ(cairo_surface_status(s), CAIRO_STATUS_SUCCESS) << file;
    if (cairo_surface_status(s) == CAIRO_STATUS_SUCCESS) {
        img.width = cairo_image_surface_get_width(s);
        img.height = cairo_image_surface_get_height(s);
        const int stride = cairo_image_surface_get_stride(s);
        const unsigned char* data = cairo_image_surface_get_data(s);
        for (int y = 0; y < img.height; ++y)
            for (int x = 0; x < img.width; ++x) {
                std::uint32_t p;
                std::memcpy(&p, data + y * stride + 4 * x, 4);
                img.pixels.push_back(p & 0xFFFFFF);
            }
    }
    cairo_surface_destroy(s);
    return img;
}

std::array<int, 3> rgb_of(const render::Rgb& c) {
    return {static_cast<int>(std::lround(255 * c.r)), static_cast<int>(std::lround(255 * c.g)),
            static_cast<int>(std::lround(255 * c.b))};
}

bool close(const std::array<int, 3>& a, const std::array<int, 3>& b, int tolerance = 1) {
    for (int c = 0; c < 3; ++c)
        if (std::abs(a[c] - b[c]) > tolerance) return false;
    return true;
}

class Render : public ScratchDir {
  protected:
    void run_gas() {
        write("gas.toml", gas_config);
        const auto r = run_pedesis("run gas.toml --out gas", dir);
        ASSERT_EQ(r.exit_code, 0) << r.output;
    }
    // The gas run's frame k through the renderer's own layout of a width x height canvas.
    render::Layout layout_of(std::size_t k, int width, int height) {
        const auto run = render::open_run_directory(dir / "gas", render::SourceKind::automatic);
        return render::make_layout(width, height, run.source->frame(k), false);
    }
};

TEST_F(Render, PngFramesHaveTheSizeAndEveryCentreItsSpeciesColour) {
    run_gas();
    const auto r = run_pedesis("render gas --out frames/ --size 320x240", dir);
    ASSERT_EQ(r.exit_code, 0) << r.output;
    EXPECT_NE(r.output.find("5 PNG frames (320x240) of gas/trajectory.xyz"), std::string::npos)
        << r.output;

    const XyzReader xyz(dir / "gas" / "trajectory.xyz");
    ASSERT_EQ(xyz.frames(), 5u); // t = 0, 0.5, ..., 2
    EXPECT_EQ(files_starting(dir / "frames", "frame_").size(), 5u);
    for (std::size_t k = 0; k < xyz.frames(); ++k) {
        const fs::path png = dir / "frames" / ("frame_00000" + std::to_string(k) + ".png");
        const Image img = read_png(png);
        ASSERT_EQ(img.width, 320) << png;
        ASSERT_EQ(img.height, 240) << png;
        const XyzFrame f = xyz.frame(k);
        const render::Layout L = layout_of(k, 320, 240);
        EXPECT_NEAR(L.box_w / L.box_h, 20.0 / 16.0, 1e-12);
        EXPECT_GE(L.left, 0.0);
        EXPECT_LE(L.left + L.box_w, 320.0);
        const std::array<int, 3> colour_a = rgb_of(render::species_colour(0));
        const std::array<int, 3> colour_b = rgb_of(render::species_colour(1));
        for (std::size_t i = 0; i < f.size(); ++i) {
            const auto [cx, cy] = L.to_canvas(f.position[i][0], f.position[i][1]);
            const auto want = f.species_names[f.species[i]] == "A" ? colour_a : colour_b;
            EXPECT_TRUE(close(img.at(cx, cy), want)) << "frame " << k << " particle " << i;
        }
        // Background: points of the box farther than 2 radii from every centre.
        int checked = 0;
        for (double x = -9.5; x < 10.0; x += 1.0)
            for (double y = -7.5; y < 8.0; y += 1.0) {
                bool clear = true;
                for (std::size_t i = 0; i < f.size(); ++i) {
                    double dy = std::abs(y - f.position[i][1]);
                    dy = std::min(dy, 16.0 - dy); // periodic in y
                    clear = clear && std::hypot(x - f.position[i][0], dy) > 2.0 * f.radius[i];
                }
                if (!clear) continue;
                const auto [cx, cy] = L.to_canvas(x, y);
                const auto got = img.at(cx, cy);
                EXPECT_TRUE(close(got, {255, 255, 255})) << x << "," << y;
                EXPECT_FALSE(close(got, colour_a, 40));
                EXPECT_FALSE(close(got, colour_b, 40));
                ++checked;
            }
        EXPECT_GT(checked, 50);
    }
}

TEST_F(Render, Mp4AndGifHoldTheExpectedFrameCount) {
    run_gas();
    auto r = run_pedesis("render gas --out movie.mp4 --every 2 --size 320x240 --fps 10", dir);
    ASSERT_EQ(r.exit_code, 0) << r.output;
    EXPECT_EQ(ffprobe_frames(dir / "movie.mp4", dir), 3); // frames 0, 2, 4
    EXPECT_EQ(ffprobe_size(dir / "movie.mp4", dir), "320,240");

    r = run_pedesis("render gas --out movie.gif --color speed", dir);
    ASSERT_EQ(r.exit_code, 0) << r.output;
    EXPECT_EQ(ffprobe_frames(dir / "movie.gif", dir), 5);
    EXPECT_NE(r.output.find("speed colour bar from 0 to"), std::string::npos) << r.output;

    // The default: RUN_DIR/movie.mp4, the box's aspect within 800x800 and even sides.
    r = run_pedesis("render gas", dir);
    ASSERT_EQ(r.exit_code, 0) << r.output;
    EXPECT_EQ(ffprobe_frames(dir / "gas" / "movie.mp4", dir), 5);
    std::smatch m;
    const std::string size = ffprobe_size(dir / "gas" / "movie.mp4", dir);
    ASSERT_TRUE(std::regex_match(size, m, std::regex(R"((\d+),(\d+))"))) << size;
    EXPECT_EQ(std::stoi(m[1]) % 2, 0);
    EXPECT_EQ(std::stoi(m[2]) % 2, 0);
    EXPECT_EQ(std::max(std::stoi(m[1]), std::stoi(m[2])), 800);
    EXPECT_TRUE(files_starting(dir, "movie.mp4.tmp").empty());
    EXPECT_TRUE(files_starting(dir, "movie.gif.tmp").empty());
}

TEST_F(Render, SoftRunGsdWithDirectors) {
    write("soft.toml", soft_config);
    auto r = run_pedesis("run soft.toml --out soft", dir);
    ASSERT_EQ(r.exit_code, 0) << r.output;
    r = run_pedesis("render soft --out frames/ --color angle --size 300x260", dir);
    ASSERT_EQ(r.exit_code, 0) << r.output;
    EXPECT_NE(r.output.find("3 PNG frames (300x260) of soft/trajectory.gsd (GSD)"),
              std::string::npos)
        << r.output;
    EXPECT_EQ(read_png(dir / "frames" / "frame_000002.png").width, 300);
}

// A sheared run's GSD has the tilt xy = offset / L_y (Lees-Edwards): drawn, its positions
// lying in the orthorhombic box as pedesis writes them.
TEST_F(Render, ShearedRunGsdIsDrawn) {
    std::string sheared = soft_config;
    sheared.replace(sheared.find("length = 20.0"), 13, "length = 20.0\nshear_rate = 0.5");
    write("sheared.toml", sheared);
    auto r = run_pedesis("run sheared.toml --out sheared", dir);
    ASSERT_EQ(r.exit_code, 0) << r.output;
    r = run_pedesis("render sheared --out frames/ --size 200x200", dir);
    ASSERT_EQ(r.exit_code, 0) << r.output;
    EXPECT_EQ(read_png(dir / "frames" / "frame_000002.png").width, 200);
}

// A radius of 1e308 made render hang inside Cairo, deaf to SIGINT (issue 14): the disk
// is drawn as one covering the picture, within seconds.
TEST_F(Render, HugeRadiusDrawsInsteadOfHanging) {
    fs::create_directories(dir / "huge");
    write("huge/trajectory.xyz", "2\nLattice=\"10 0 0 0 10 0 0 0 1\" Origin=\"-5 -5 -0.5\" "
                                 "Properties=species:S:1:pos:R:3:radius:R:1 Time=0 pbc=\"T T F\"\n"
                                 "A 0 0 0 1e308\nB 2 2 0 0.5\n");
    const auto r = run_pedesis("render huge --out frames/ --size 64x64", dir, 30);
    EXPECT_EQ(r.exit_code, 0) << r.output;
    EXPECT_TRUE(fs::exists(dir / "frames" / "frame_000000.png")) << r.output;
}

// A run directory's config.toml with a circular container, a trap and gravity: the PNG
// shows the container's wall line, the trap's marker and the arrow where the same run
// without those forces is background. A config whose scenery values are nonsense renders
// as if it had none.
TEST_F(Render, ContainerTrapAndGravityFromTheConfigAreDrawn) {
    fs::create_directories(dir / "scene");
    write("scene/trajectory.xyz",
          "1\nLattice=\"20 0 0 0 20 0 0 0 1\" Origin=\"-10 -10 -0.5\" "
          "Properties=species:S:1:pos:R:3:radius:R:1 Time=0 pbc=\"F F F\"\nA 0 0 0 0.5\n");
    const std::string plain = "dimension = 2\n[box]\nlength = 20.0\nboundary = \"wall\"\n";
    auto render_with = [&](const std::string& config) {
        write("scene/config.toml", config);
        const auto r = run_pedesis("render scene --out frames/ --size 400x400", dir, 30);
        EXPECT_EQ(r.exit_code, 0) << r.output;
        return read_png(dir / "frames" / "frame_000000.png");
    };
    const Image without = render_with(plain);
    const Image with = render_with(plain + R"([[force]]
name = "wall"
potential = "wca"
shape = "sphere"
radius = 8.0
centre = [1.0, 0.0]
[[force]]
name = "harmonic_trap"
k = 1.0
centre = [-3.0, 4.0]
[[force]]
name = "gravity"
force = 1.0
)");
    const Image nonsense = render_with(plain + R"([[force]]
name = "wall"
shape = "sphere"
radius = -8.0
[[force]]
name = "harmonic_trap"
k = "stiff"
[[force]]
name = "gravity"
force = nan
)");
    const auto run = render::open_run_directory(dir / "scene", render::SourceKind::automatic);
    const render::Layout L = render::make_layout(400, 400, run.source->frame(0), false);
    const auto dark = [](const std::array<int, 3>& p) { return p[0] + p[1] + p[2] < 3 * 80; };
    const std::array<int, 3> white{255, 255, 255};
    // the container's wall line, just outside its radius, on its left and right
    const auto [cx, cy] = L.to_canvas(1.0, 0.0);
    const double ring = 8.0 * L.scale + 0.5 * L.wall;
    // the trap's centre, and the gravity arrow in the box's top right corner
    const auto [tx, ty] = L.to_canvas(-3.0, 4.0);
    const std::vector<std::array<double, 2>> marks = {
        {cx - ring, cy},
        {cx + ring, cy},
        {tx, ty},
        {L.left + L.box_w - 1.6 * L.font, L.top + 1.6 * L.font}};
    for (const auto& [x, y] : marks) {
        EXPECT_TRUE(dark(with.at(x, y))) << x << "," << y;
        EXPECT_TRUE(close(without.at(x, y), white)) << x << "," << y;
    }
    EXPECT_EQ(nonsense.pixels, without.pixels);
}

TEST_F(Render, MissingOrCorruptRunDirectoriesExitWith2) {
    run_gas();
    auto r = run_pedesis("render nowhere --out f/", dir);
    EXPECT_EQ(r.exit_code, 2);
    EXPECT_NE(r.output.find("pedesis: error: nowhere: no such run directory"), std::string::npos)
        << r.output;

    fs::create_directories(dir / "empty");
    r = run_pedesis("render empty --out f/", dir);
    EXPECT_EQ(r.exit_code, 2);
    EXPECT_NE(r.output.find("empty: no trajectory to render"), std::string::npos) << r.output;

    // A trajectory cut in the middle of a frame, and a GSD file that is not one.
    fs::create_directories(dir / "cut");
    const std::string xyz = read("gas/trajectory.xyz");
    write("cut/trajectory.xyz", xyz.substr(0, xyz.size() * 3 / 5));
    r = run_pedesis("render cut --out f/", dir);
    EXPECT_EQ(r.exit_code, 2);
    EXPECT_NE(r.output.find("cut/trajectory.xyz: line"), std::string::npos) << r.output;
    EXPECT_NE(r.output.find("cut short"), std::string::npos) << r.output;

    fs::create_directories(dir / "junk");
    write("junk/trajectory.gsd", std::string(300, 'x'));
    r = run_pedesis("render junk --out f/", dir);
    EXPECT_EQ(r.exit_code, 2);
    EXPECT_NE(r.output.find("junk/trajectory.gsd: not a GSD file"), std::string::npos) << r.output;
    EXPECT_FALSE(fs::exists(dir / "f" / "frame_000000.png"));
}

TEST_F(Render, NoFfmpegExitsWith2AndSaysWhatToDo) {
    run_gas();
    fs::create_directories(dir / "no_ffmpeg_here");
    const auto r = run_with_path("render gas --out movie.mp4", dir / "no_ffmpeg_here", dir);
    EXPECT_EQ(r.exit_code, 2) << r.output;
    EXPECT_NE(r.output.find("pedesis: error: movie.mp4: ffmpeg not found; install Debian's "
                            "ffmpeg or render PNG frames with --out DIR/"),
              std::string::npos)
        << r.output;
    EXPECT_TRUE(files_starting(dir, "movie").empty());
    // PNG frames need no ffmpeg.
    const auto png = run_with_path("render gas --out frames/", dir / "no_ffmpeg_here", dir);
    EXPECT_EQ(png.exit_code, 0) << png.output;
}

TEST_F(Render, AFailingFfmpegLeavesNoMovieBehind) {
    run_gas();
    // An ffmpeg that reads some frames, writes half a movie where it was told, and fails.
    fs::create_directories(dir / "fake");
    write("fake/ffmpeg", "#!/bin/sh\n"
                         "for last; do :; done\n"
                         "/usr/bin/head -c 1000 > /dev/null\n"
                         "echo half a movie > \"$last\"\n"
                         "echo 'fake ffmpeg: encoder exploded' >&2\n"
                         "exit 1\n");
    fs::permissions(dir / "fake" / "ffmpeg", fs::perms::owner_all);
    write("movie.mp4", "an older movie");
    const auto r = run_with_path("render gas --out movie.mp4", dir / "fake", dir);
    EXPECT_EQ(r.exit_code, 2) << r.output;
    EXPECT_NE(r.output.find("movie.mp4: ffmpeg"), std::string::npos) << r.output;
    EXPECT_NE(r.output.find("fake ffmpeg: encoder exploded"), std::string::npos) << r.output;
    EXPECT_EQ(read("movie.mp4"), "an older movie"); // the old movie untouched, nothing half-made
    EXPECT_TRUE(files_starting(dir, "movie.mp4.tmp").empty());
}

TEST_F(Render, BadOptionsExitWith2NamingTheOption) {
    run_gas();
    const std::vector<std::pair<std::string, std::string>> cases = {
        {"--out movie.avi", "--out movie.avi: name a .mp4 or .gif file"},
        {"--out m.mp4 --size 321x240", "--size 321x240: an MP4 (H.264, yuv420p) needs an even"},
        {"--out f/ --size big", "--size big: give WIDTHxHEIGHT"},
        {"--out f/ --size 20x20", "--size 20x20: each side must be from 64 to 8192"},
        {"--out f/ --every 0", "--every 0"},
        {"--out f/ --fps 0", "--fps 0"},
        {"--out m.gif --fps 60", "--fps 60: a GIF plays at most 50"},
        {"--out f/ --color angle", "no directors (polarities), which --color angle needs"},
        {"--out f/ --slab=0:1", "a 2D run; --slab selects a layer of a 3D run"},
        {"--out f/ --slab=1:0", "--slab 1:0: give zmin:zmax with zmin < zmax"},
        {"--out f/ --speed-max 2", "--speed-max sets the speed colour bar; it needs --color speed"},
        {"--out f/ --color purple", "--color: purple not in"},
        {"--out f/ --source gsd", "gas/trajectory.gsd: not found (--source gsd)"},
    };
    for (const auto& [args, message] : cases) {
        const auto r = run_pedesis("render gas " + args, dir);
        EXPECT_EQ(r.exit_code, 2) << args << "\n" << r.output;
        EXPECT_NE(r.output.find(message), std::string::npos) << args << "\n" << r.output;
    }
    EXPECT_FALSE(fs::exists(dir / "movie.avi"));
    EXPECT_FALSE(fs::exists(dir / "m.mp4"));
}

} // namespace
} // namespace pedesis::test
