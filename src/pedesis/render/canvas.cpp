#include "pedesis/render/canvas.hpp"

#include "pedesis/core/error.hpp"

#include <cstring>
#include <string>
#include <system_error>
#include <unistd.h>

namespace pedesis::render {

namespace fs = std::filesystem;

Canvas::Canvas(int width, int height) : width_(width), height_(height) {
    surface_ = cairo_image_surface_create(CAIRO_FORMAT_RGB24, width, height);
    if (cairo_surface_status(surface_) != CAIRO_STATUS_SUCCESS) {
        const std::string why = cairo_status_to_string(cairo_surface_status(surface_));
        cairo_surface_destroy(surface_);
        throw InputError("cannot make a " + std::to_string(width) + "x" + std::to_string(height) +
                         " image: " + why);
    }
    cr_ = cairo_create(surface_);
}

Canvas::~Canvas() {
    cairo_destroy(cr_);
    cairo_surface_destroy(surface_);
}

void Canvas::rgb_bytes(std::vector<std::uint8_t>& out) {
    cairo_surface_flush(surface_);
    const unsigned char* data = cairo_image_surface_get_data(surface_);
    const int stride = cairo_image_surface_get_stride(surface_);
    out.resize(static_cast<std::size_t>(width_) * static_cast<std::size_t>(height_) * 3);
    std::uint8_t* o = out.data();
    for (int y = 0; y < height_; ++y) {
        // RGB24 pixels are native-endian 32-bit words 0x00RRGGBB
        const unsigned char* row = data + static_cast<std::ptrdiff_t>(y) * stride;
        for (int x = 0; x < width_; ++x) {
            std::uint32_t px;
            std::memcpy(&px, row + 4 * x, 4);
            *o++ = static_cast<std::uint8_t>(px >> 16);
            *o++ = static_cast<std::uint8_t>(px >> 8);
            *o++ = static_cast<std::uint8_t>(px);
        }
    }
}

void Canvas::write_png(const fs::path& path) {
    fs::path tmp = path;
    tmp += ".tmp." + std::to_string(::getpid());
    cairo_surface_flush(surface_);
    const cairo_status_t status = cairo_surface_write_to_png(surface_, tmp.c_str());
    std::error_code ec;
    if (status != CAIRO_STATUS_SUCCESS) {
        fs::remove(tmp, ec);
        throw InputError(path.string() +
                         ": cannot write the PNG file: " + cairo_status_to_string(status));
    }
    fs::rename(tmp, path, ec);
    if (ec) {
        std::error_code ignored;
        fs::remove(tmp, ignored);
        throw InputError(path.string() + ": cannot replace the file: " + ec.message());
    }
}

} // namespace pedesis::render
