#pragma once
// GSD trajectories read back, after the GSD file layer specification (versions 1.x and
// 2.x; 2.0 is what GsdWriter and the gsd Python package write), with the "hoomd"
// schema's rule for missing chunks: a chunk absent from frame k is taken from frame 0,
// and from the schema's default when frame 0 lacks it too. No gsd library is needed.
//
// The whole index is checked when the file is opened (every chunk inside the file, of a
// known type and name, frames in order), so a truncated or corrupt file is refused at
// once with an InputError naming it; chunk shapes and values are checked per frame.
#include <array>
#include <cstdint>
#include <filesystem>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace pedesis {

// One frame of the hoomd schema, values widened to double.
struct GsdFrame {
    std::uint64_t step = 0;
    int dimensions = 3;
    std::array<double, 6> box{1.0, 1.0, 1.0, 0.0, 0.0, 0.0}; // Lx, Ly, Lz, xy, xz, yz
    std::vector<std::string> types;                          // particles/types
    std::vector<std::uint32_t> type_id;                      // each < types.size()
    std::vector<double> mass;
    std::vector<double> diameter;
    std::vector<std::array<double, 3>> position;
    std::vector<std::array<double, 3>> velocity;
    std::vector<std::array<double, 4>> orientation; // unit quaternions (w, x, y, z)
    std::optional<double> time;                     // log/time of this frame, if written
    // log/pedesis/periodic (pedesis' own chunk: per axis 1 periodic, 0 walls; z is not
    // periodic in 2D), where the file has it; the hoomd schema itself has no walls.
    std::optional<std::array<bool, 3>> periodic;
    // Whether the file stores them (in this frame or frame 0), or they are the schema's
    // defaults (zero velocities, identity orientations).
    bool velocity_stored = false;
    bool orientation_stored = false;

    std::size_t size() const { return position.size(); }
};

class GsdReader {
  public:
    explicit GsdReader(std::filesystem::path path);
    ~GsdReader();
    GsdReader(const GsdReader&) = delete;
    GsdReader& operator=(const GsdReader&) = delete;

    std::uint64_t frames() const { return frames_; }
    const std::string& application() const { return application_; }
    const std::string& schema() const { return schema_; }
    std::uint32_t gsd_version() const { return gsd_version_; } // 0xaaaabbbb: aaaa.bbbb
    const std::filesystem::path& path() const { return path_; }

    // Whether frame k itself stores the named chunk.
    bool has_chunk(std::uint64_t frame, std::string_view name) const;

    // Frame k (0-based) of the hoomd schema.
    GsdFrame frame(std::uint64_t k) const;

    struct Entry {
        std::uint64_t frame;
        std::uint64_t n;
        std::int64_t location;
        std::uint32_t m;
        std::uint16_t id;
        std::uint8_t type;
    };

  private:
    const Entry* find(std::uint64_t frame, std::string_view name) const;
    // The entry of frame k, else of frame 0, else null (the hoomd schema's fallback).
    const Entry* find_with_fallback(std::uint64_t frame, std::string_view name) const;
    std::vector<double> reals(const Entry& e, std::uint64_t frame) const;
    std::vector<std::int64_t> integers(const Entry& e, std::uint64_t frame) const;
    std::string bytes(const Entry& e) const;
    void read_at(std::uint64_t offset, char* out, std::uint64_t size) const;

    std::filesystem::path path_;
    int fd_ = -1;
    std::uint64_t file_size_ = 0;
    std::uint64_t frames_ = 0;
    std::uint32_t gsd_version_ = 0;
    std::string application_, schema_;
    std::vector<std::string> names_;
    std::vector<Entry> entries_; // in file order: sorted by frame
};

} // namespace pedesis
