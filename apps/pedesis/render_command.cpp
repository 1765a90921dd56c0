#include "render_command.hpp"

#include "pedesis/core/error.hpp"
#include "pedesis/render/render_movie.hpp"
#include "pedesis/run/analysis_outputs.hpp"

#include <fmt/core.h>

#include <charconv>
#include <map>
#include <memory>
#include <optional>
#include <string>

namespace pedesis::cli {

namespace {

struct RenderArgs {
    std::string run_dir;
    std::string out;
    std::string colour = "species";
    std::string size;
    std::string slab;
    std::string source = "auto";
    std::optional<double> speed_max;
    double fps = 30.0;
    std::size_t every = 1;
    bool no_arrows = false;
};

template <class T> std::optional<T> number(std::string_view text) {
    T v{};
    const auto [end, ec] = std::from_chars(text.data(), text.data() + text.size(), v);
    if (ec != std::errc{} || end != text.data() + text.size() || text.empty()) return std::nullopt;
    return v;
}

std::pair<int, int> parse_size(const std::string& text) {
    const std::size_t x = text.find('x');
    const auto w = x == std::string::npos ? std::nullopt : number<int>(text.substr(0, x));
    const auto h = x == std::string::npos ? std::nullopt : number<int>(text.substr(x + 1));
    if (!w || !h)
        throw InputError("--size " + text + ": give WIDTHxHEIGHT in pixels, e.g. 800x600");
    return {*w, *h};
}

render::Slab parse_slab(const std::string& text) {
    // The separator is the first ':' after the first character, so zmin may be negative.
    const std::size_t colon = text.find(':', 1);
    const auto lo =
        colon == std::string::npos ? std::nullopt : number<double>(text.substr(0, colon));
    const auto hi =
        colon == std::string::npos ? std::nullopt : number<double>(text.substr(colon + 1));
    if (!lo || !hi) throw InputError("--slab " + text + ": give zmin:zmax, e.g. --slab -2.5:2.5");
    return {*lo, *hi};
}

void run_render(const RenderArgs& a) {
    static const std::map<std::string, render::ColourBy> colours = {
        {"species", render::ColourBy::species},
        {"speed", render::ColourBy::speed},
        {"angle", render::ColourBy::angle}};
    static const std::map<std::string, render::SourceKind> sources = {
        {"auto", render::SourceKind::automatic},
        {"gsd", render::SourceKind::gsd},
        {"xyz", render::SourceKind::xyz},
        {"json", render::SourceKind::json}};

    render::RenderRequest r;
    r.run_dir = a.run_dir;
    r.out = a.out.empty() ? (r.run_dir / default_movie).string() : a.out;
    r.source = sources.at(a.source);
    r.colour = colours.at(a.colour);
    if (!a.size.empty()) r.size = parse_size(a.size);
    if (!a.slab.empty()) r.slab = parse_slab(a.slab);
    r.speed_max = a.speed_max;
    r.fps = a.fps;
    r.every = a.every;
    r.arrows = !a.no_arrows;

    const render::RenderReport report = render::render(r);
    for (const std::string& note : report.notes) fmt::print("render: note: {}\n", note);
    const std::string what = report.kind == render::OutputKind::png_directory
                                 ? "PNG frames"
                                 : fmt::format("frames at {} fps", r.fps);
    fmt::print("render: {} {} ({}x{}) of {} written to {}\n", report.frames, what, report.width,
               report.height, report.source, report.out.string());
    if (r.colour == render::ColourBy::speed)
        fmt::print("render: speed colour bar from 0 to {:.6g}\n", report.speed_max);
}

} // namespace

void add_render_command(CLI::App& app) {
    auto a = std::make_shared<RenderArgs>();
    auto* cmd = app.add_subcommand(
        "render",
        "Draw a run directory's trajectory as an MP4, a GIF or PNG frames (docs/render.md)");
    cmd->add_option("run_dir", a->run_dir, "Run directory (the --out of pedesis run)")->required();
    cmd->add_option("--out", a->out,
                    "movie.mp4, movie.gif, or a directory for PNG frames (end it with '/'); "
                    "default RUN_DIR/movie.mp4");
    cmd->add_option("--color", a->colour, "Colour particles by species, speed or angle (polarity)")
        ->check(CLI::IsMember({"species", "speed", "angle"}));
    cmd->add_option("--size", a->size,
                    "Image size WIDTHxHEIGHT in pixels (default: the box's aspect within 800x800)");
    cmd->add_option("--fps", a->fps, "Frames per second of the movie (default 30)");
    cmd->add_option("--every", a->every, "Draw every K-th frame (default 1: all)");
    cmd->add_option("--slab", a->slab,
                    "3D runs: draw only centres with zmin <= z <= zmax, given as zmin:zmax "
                    "(default: project the whole box onto xy)");
    cmd->add_option("--speed-max", a->speed_max,
                    "Top of the speed colour bar (default: the 99th percentile of the speeds, "
                    "largest over the frames)");
    cmd->add_option("--source", a->source,
                    "Trajectory to read: auto (trajectory.gsd, else trajectory.xyz, else "
                    "snapshots/frame_*.json), gsd, xyz or json")
        ->check(CLI::IsMember({"auto", "gsd", "xyz", "json"}));
    cmd->add_flag("--no-arrows", a->no_arrows, "Do not draw director arrows");
    cmd->callback([a] { run_render(*a); });
}

} // namespace pedesis::cli
