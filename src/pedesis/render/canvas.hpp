#pragma once
// An RGB image in memory with its Cairo context: what a frame is painted on, and what
// becomes a PNG file or the raw RGB bytes ffmpeg reads.
#include <cairo.h>

#include <cstdint>
#include <filesystem>
#include <vector>

namespace pedesis::render {

class Canvas {
  public:
    Canvas(int width, int height);
    ~Canvas();
    Canvas(const Canvas&) = delete;
    Canvas& operator=(const Canvas&) = delete;

    int width() const { return width_; }
    int height() const { return height_; }
    cairo_t* context() { return cr_; }

    // Packed 8-bit R, G, B per pixel, rows top to bottom (ffmpeg's rgb24).
    void rgb_bytes(std::vector<std::uint8_t>& out);

    // Writes a PNG to a temporary file beside `path` and renames it into place, so a
    // frame file is complete or absent. InputError naming `path` on failure.
    void write_png(const std::filesystem::path& path);

  private:
    int width_, height_;
    cairo_surface_t* surface_ = nullptr;
    cairo_t* cr_ = nullptr;
};

} // namespace pedesis::render
