#include "pedesis/render/render_movie.hpp"

#include "pedesis/core/error.hpp"
#include "pedesis/core/interrupt.hpp"
#include "pedesis/core/stage.hpp"
#include "pedesis/render/canvas.hpp"
#include "pedesis/render/ffmpeg_encoder.hpp"
#include "pedesis/render/layout.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <memory>
#include <regex>
#include <system_error>

namespace pedesis::render {

namespace {

namespace fs = std::filesystem;

constexpr int min_side = 64, max_side = 8192;
// GIF delays are whole hundredths of a second, and players stretch delays under 0.02 s.
constexpr double max_gif_fps = 50.0;

std::string lowercase(std::string s) {
    for (char& c : s) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
    return s;
}

void check_request(const RenderRequest& r, OutputKind kind) {
    if (!(std::isfinite(r.fps) && r.fps > 0.0 && r.fps <= 1000.0))
        throw InputError(fmt::format("--fps {}: give frames per second in (0, 1000]", r.fps));
    if (kind == OutputKind::gif && r.fps > max_gif_fps)
        throw InputError(fmt::format("--fps {}: a GIF plays at most {} frames per second (its "
                                     "delays are hundredths of a second); lower --fps or write "
                                     "an MP4",
                                     r.fps, max_gif_fps));
    if (r.every < 1) throw InputError("--every 0: the frame stride must be at least 1");
    if (r.size) {
        const auto [w, h] = *r.size;
        if (w < min_side || h < min_side || w > max_side || h > max_side)
            throw InputError(fmt::format("--size {}x{}: each side must be from {} to {} pixels", w,
                                         h, min_side, max_side));
        if (kind == OutputKind::mp4 && (w % 2 != 0 || h % 2 != 0))
            throw InputError(fmt::format("--size {}x{}: an MP4 (H.264, yuv420p) needs an even "
                                         "width and height",
                                         w, h));
    }
    if (r.speed_max && !(std::isfinite(*r.speed_max) && *r.speed_max > 0.0))
        throw InputError(fmt::format("--speed-max {}: must be a positive speed", *r.speed_max));
    if (r.speed_max && r.colour != ColourBy::speed)
        throw InputError("--speed-max sets the speed colour bar; it needs --color speed");
    if (r.slab &&
        !(std::isfinite(r.slab->lo) && std::isfinite(r.slab->hi) && r.slab->lo < r.slab->hi))
        throw InputError(
            fmt::format("--slab {}:{}: give zmin:zmax with zmin < zmax", r.slab->lo, r.slab->hi));
}

void check_frame(const Frame& f, const Style& s, const std::string& where) {
    if (s.colour == ColourBy::speed && f.velocity.empty())
        throw InputError(where + ": the frame has no velocities, which --color speed needs");
    if (s.colour == ColourBy::angle && f.director.empty())
        throw InputError(where + ": the frame has no directors (polarities), which --color angle "
                                 "needs; soft runs store them in trajectory.gsd and "
                                 "snapshots/frame_*.json");
    if (s.slab && f.dimension != 3)
        throw InputError(where + ": a 2D run; --slab selects a layer of a 3D run");
}

// The 99th percentile of each frame's speeds, the largest over the frames drawn: a few
// fast outliers do not wash out everyone else's colour, and the bar is the same all movie.
double speed_scale(FrameSource& source, const std::vector<std::size_t>& picks) {
    double top = 0.0;
    std::vector<double> speeds;
    for (std::size_t k : picks) {
        const Frame f = source.frame(k);
        if (f.velocity.empty()) continue; // check_frame reports it when the frame is drawn
        speeds.clear();
        for (const Vec3& v : f.velocity)
            speeds.push_back(std::sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]));
        if (speeds.empty()) continue;
        const auto at = static_cast<std::ptrdiff_t>(0.99 * static_cast<double>(speeds.size() - 1));
        std::nth_element(speeds.begin(), speeds.begin() + at, speeds.end());
        top = std::max(top, speeds[static_cast<std::size_t>(at)]);
    }
    return top > 0.0 ? top : 1.0;
}

// frame_NNNNNN.png files numbered `from` or above: left by an earlier, longer render.
std::size_t stale_frames(const fs::path& dir, std::size_t from) {
    static const std::regex name(R"(frame_(\d{1,18})\.png)"); // fits stoull
    std::size_t stale = 0;
    std::error_code ec;
    for (const auto& entry : fs::directory_iterator(dir, ec)) {
        std::smatch m;
        const std::string file = entry.path().filename().string();
        if (std::regex_match(file, m, name) && std::stoull(m[1].str()) >= from) ++stale;
    }
    return stale;
}

void prepare_output(const fs::path& out, OutputKind kind) {
    std::error_code ec;
    if (kind == OutputKind::png_directory) {
        fs::create_directories(out, ec);
        if (ec || !fs::is_directory(out))
            throw InputError(out.string() + ": cannot create the directory for the PNG frames" +
                             (ec ? ": " + ec.message() : std::string()));
        return;
    }
    const fs::path parent = out.parent_path().empty() ? fs::path(".") : out.parent_path();
    if (!fs::is_directory(parent, ec))
        throw InputError(out.string() + ": the directory " + parent.string() + " does not exist");
}

RenderReport render_frames(const RenderRequest& r, const InterruptGuard& guard) {
    enter_stage("reading the frames");
    const OutputKind kind = output_kind(r.out);
    check_request(r, kind);
    const fs::path out = r.out;
    fs::path ffmpeg;
    if (kind != OutputKind::png_directory) ffmpeg = find_ffmpeg(out);

    OpenedRun run = open_run_directory(r.run_dir, r.source);
    FrameSource& source = *run.source;
    std::vector<std::size_t> picks;
    for (std::size_t k = 0; k < source.frames(); k += r.every) picks.push_back(k);

    Style style;
    style.colour = r.colour;
    style.slab = r.slab;
    style.arrows = r.arrows;
    auto where = [&](std::size_t k) {
        return fmt::format("{}: frame {}", source.description(), k);
    };
    Frame first = source.frame(0);
    check_frame(first, style, where(0));
    if (style.colour == ColourBy::speed)
        style.speed_max = r.speed_max ? *r.speed_max : speed_scale(source, picks);

    const bool sidebar = style.colour != ColourBy::species;
    const auto [width, height] = r.size ? *r.size : default_size(first, sidebar);
    Canvas canvas(width, height);
    // From the first output on, a signal stops between frames and the encoder's temporary
    // file goes; before it (reading the source, scaling speeds) it ends the process at once.
    const CleanStopWindow window;
    enter_stage("drawing the frames");
    prepare_output(out, kind);
    std::unique_ptr<FfmpegEncoder> encoder;
    if (kind != OutputKind::png_directory)
        encoder = std::make_unique<FfmpegEncoder>(
            ffmpeg, out, kind == OutputKind::mp4 ? MovieFormat::mp4 : MovieFormat::gif, width,
            height, r.fps);

    std::vector<std::uint8_t> rgb;
    std::size_t written = 0;
    for (std::size_t k : picks) {
        if (guard.signal() != 0) throw InputError("render interrupted");
        const Frame f = k == 0 ? std::move(first) : source.frame(k);
        check_frame(f, style, where(k));
        // Laid out per frame: a box that changes size is drawn to scale in every frame.
        const Layout layout = make_layout(width, height, f, sidebar);
        paint_frame(canvas, layout, f, style, k, run.scenery);
        if (encoder) {
            canvas.rgb_bytes(rgb);
            encoder->write_frame(rgb);
        } else {
            canvas.write_png(out / fmt::format("frame_{:06d}.png", written));
        }
        ++written;
    }
    if (guard.signal() != 0) throw InputError("render interrupted");
    if (encoder) encoder->finish();

    RenderReport report;
    report.frames = written;
    report.source = source.description();
    report.out = out;
    report.kind = kind;
    report.width = width;
    report.height = height;
    report.speed_max = style.speed_max;
    report.notes = std::move(run.notes);
    if (kind == OutputKind::png_directory) {
        if (const std::size_t stale = stale_frames(out, written); stale > 0)
            report.notes.push_back(fmt::format(
                "{} also holds {} frame_*.png from an earlier render, numbered after this "
                "render's last frame; remove them before making a movie of the folder",
                out.string(), stale));
    }
    return report;
}

} // namespace

OutputKind output_kind(const std::string& out) {
    if (out.empty()) throw InputError("--out: give a .mp4 or .gif file, or a directory");
    std::error_code ec;
    if (out.back() == '/' || fs::is_directory(out, ec)) return OutputKind::png_directory;
    const std::string ext = lowercase(fs::path(out).extension().string());
    if (ext == ".mp4") return OutputKind::mp4;
    if (ext == ".gif") return OutputKind::gif;
    throw InputError("--out " + out +
                     ": name a .mp4 or .gif file, or a directory for PNG frames (end it with '/')");
}

RenderReport render(const RenderRequest& request) {
    InterruptGuard guard(OutsideCleanStops::end_process);
    try {
        return render_frames(request, guard);
    } catch (...) {
        // Everything render_frames made (the encoder and its temporary file) is gone by now.
        if (guard.signal() != 0) guard.reraise();
        throw;
    }
}

} // namespace pedesis::render
