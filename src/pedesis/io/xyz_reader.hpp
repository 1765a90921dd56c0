#pragma once
// Extended-XYZ trajectories read back frame by frame: what xyz_frame writes, and the
// orthorhombic files of other tools (OVITO, ASE) with any column layout that names
// `species` and `pos`. Every fault is an InputError naming the file and the line.
#include <array>
#include <cstdint>
#include <filesystem>
#include <optional>
#include <string>
#include <utility>
#include <vector>

namespace pedesis {

struct XyzFrame {
    std::array<double, 3> lattice{}; // cell edge lengths (the cell must be orthorhombic)
    std::array<double, 3> origin{};  // the cell's corner (0 when the file has no Origin)
    std::array<bool, 3> pbc{true, true, true};
    bool pbc_stated = false; // whether the comment line has pbc (else the default above)
    std::optional<double> time;
    std::vector<std::string> species_names; // distinct names, in order of first appearance
    std::vector<std::uint16_t> species;     // per row, an index into species_names
    std::vector<std::array<double, 3>> position;
    std::vector<std::array<double, 3>> velocity; // empty without a "velo" column
    std::vector<double> radius;                  // empty without a "radius" column
    std::vector<double> mass;                    // empty without "mass"; +inf: fixed obstacle
    std::vector<std::int64_t> id;                // empty without an "id" column
    // Every other numeric column (R or I), one number per particle each: a column of
    // count 1 under its own name, a wider one as name_0, name_1, ... (name_x, _y, _z for
    // three). NaN is refused; infinities are kept.
    std::vector<std::pair<std::string, std::vector<double>>> extra;

    std::size_t size() const { return position.size(); }
};

class XyzReader {
  public:
    // Indexes the frames in one pass that only counts lines; each frame is parsed and
    // checked when asked for. A frame cut short by the end of the file (lines missing, or
    // a last line without its newline) is an error, unless `allow_torn_tail` (the ".part"
    // file of a killed run, which may end in one torn frame): then that frame is left out
    // and dropped_torn_tail() says so.
    explicit XyzReader(std::filesystem::path path, bool allow_torn_tail = false);

    std::size_t frames() const { return starts_.size(); }
    bool dropped_torn_tail() const { return dropped_torn_tail_; }
    const std::filesystem::path& path() const { return path_; }

    // Frame k (0-based), every value checked: finite positions and velocities, positive
    // radii and masses (mass may be inf), one row per particle with all its columns.
    XyzFrame frame(std::size_t k) const;

  private:
    struct FrameStart {
        std::uint64_t offset; // byte offset of the count line
        std::uint64_t line;   // 1-based line number of the count line
        std::size_t count;    // particle rows
    };

    std::filesystem::path path_;
    std::vector<FrameStart> starts_;
    bool dropped_torn_tail_ = false;
};

} // namespace pedesis
