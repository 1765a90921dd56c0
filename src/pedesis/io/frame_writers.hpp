#pragma once
// The frames of a run directory, in every format, for every engine: the one list of
// frame formats and the file each one goes to.
//   gsd    trajectory.gsd (all frames)             xyz    trajectory.xyz (all frames)
//   vtp    snapshots/frame_NNNNNN.vtp              json   snapshots/frame_NNNNNN.json
//   table  snapshots/frame_NNNNNN.txt
// Trajectories grow as ".part" files until commit(); a snapshot file is written whole
// or not at all. Frame numbers are the caller's (a restarted run numbers on).
#include "pedesis/core/frame.hpp"
#include "pedesis/io/atomic_file.hpp"
#include "pedesis/io/gsd_writer.hpp"

#include <array>
#include <cstdint>
#include <filesystem>
#include <memory>
#include <string>
#include <vector>

namespace pedesis {

inline constexpr std::array<const char*, 5> frame_formats = {"gsd", "vtp", "xyz", "json", "table"};

// "gsd", "vtp", ...: the list for messages.
std::string frame_format_list();

// Where the frames stood at a checkpoint: the frame count, the XYZ file's length and
// the GSD file's mark (for the formats the run writes).
struct FrameMarks {
    std::uint64_t frames = 0;
    std::uintmax_t xyz_bytes = 0;
    GsdMark gsd;
};

template <int D> class FrameWriters {
  public:
    // Starts the trajectories of `formats` (each one of frame_formats) in `dir`, removing
    // earlier ones there, and creates dir/snapshots only if a format writes there. Throws
    // InputError for an unknown format.
    FrameWriters(const std::filesystem::path& dir, const std::vector<std::string>& formats);

    // Continues the frames of an unfinished run (--resume) from `marks`: the trajectories
    // cut back to them, and the snapshots numbered `marks.frames` and on removed.
    FrameWriters(const std::filesystem::path& dir, const std::vector<std::string>& formats,
                 const FrameMarks& marks);

    void write(const Frame<D>& f, std::uint64_t frame_number);

    // `frames`: the run's frame count now (the caller's numbering).
    FrameMarks marks(std::uint64_t frames) const;
    // Every trajectory on the disk (a checkpoint must not outlive the frames it counts).
    void sync();

    // Gives the trajectories their final names (also for a stopped run); a second call
    // does nothing.
    void commit();

  private:
    void choose(const std::vector<std::string>& formats);
    void make_snapshot_directory() const;

    std::filesystem::path dir_;
    bool vtp_ = false, json_ = false, table_ = false;
    std::unique_ptr<AtomicAppendFile> xyz_;
    std::unique_ptr<GsdWriter<D>> gsd_;
};

extern template class FrameWriters<2>;
extern template class FrameWriters<3>;

} // namespace pedesis
