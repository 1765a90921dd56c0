#pragma once
// GSD trajectories (HOOMD-blue's binary format, "hoomd" schema 1.4), read by OVITO,
// freud and the gsd Python package. Written from the GSD file layer 2.0
// specification; no gsd library is needed.
//
// Each frame holds configuration/step, configuration/dimensions, configuration/box,
// and particles/N, typeid, mass, diameter, position, orientation, velocity, image,
// in tag order and as float32 where the schema says float, the simulation time as
// log/time (float64) and the boundaries as log/pedesis/periodic (uint8, one per axis:
// 1 periodic, 0 walls; gsd.hoomd gives frame.log["pedesis/periodic"]). particles/types
// is written
// in frame 0 and in every frame whose species table differs from frame 0's: a reader
// takes a chunk missing from a frame from frame 0, not from the previous frame.
//
// Conventions:
// - A 2D box is stored as (Lx, Ly, 0, 0, 0, 0) with dimensions = 2, as HOOMD-blue 3+
//   writes it; gsd, freud and HOOMD take Lz = 0 to mean a 2D box.
// - The schema's box is periodic on every axis; a walled axis is written as a box edge
//   like any other, and only log/pedesis/periodic says it is a wall (readers that do
//   not know the chunk, OVITO or HOOMD-blue, take the box as periodic).
// - The orientation is the unit quaternion of the shortest rotation taking the x axis
//   onto the director (in 2D a rotation about z by the director's angle); a zero
//   director gives the identity. A frame without directors (hard particles) has no
//   orientation chunk, and one without image counts writes image 0.
// - A position that rounds to +L/2 in float32 on a periodic axis is written as -L/2
//   with its image count raised by one (the same unwrapped point), because a position
//   must lie in [-L/2, L/2) for HOOMD to accept the frame.
#include "pedesis/core/frame.hpp"

#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

namespace pedesis {

// Where a GSD trajectory stood when a checkpoint was written: what a writer needs to
// continue the file from there, leaving it byte for byte as if it had never gone further.
struct GsdMark {
    std::uint64_t frames = 0;
    std::uint64_t file_end = 0;
    std::uint64_t index_location = 0;
    std::uint64_t index_capacity = 0; // entries
    std::uint64_t index_entries = 0;  // used
    std::vector<std::string> first_types;
};

template <int D> class GsdWriter {
  public:
    // Creates `path` + ".part" (truncating an earlier one) and removes an earlier file at
    // `path`, like AtomicAppendFile: a stale complete trajectory must not pass for this
    // run's. The new file is already a valid GSD file with no frames.
    explicit GsdWriter(const std::filesystem::path& path);
    // Continues the file of an unfinished run (--resume) from `mark`: its ".part" file (or
    // the published file, renamed back) is cut to the mark's length, its index block and
    // header as they were then. InputError naming the file if it does not fit the mark.
    GsdWriter(const std::filesystem::path& path, const GsdMark& mark);
    // Leaves the ".part" file, which holds every frame appended so far.
    ~GsdWriter();

    GsdWriter(const GsdWriter&) = delete;
    GsdWriter& operator=(const GsdWriter&) = delete;

    // Appends one frame. When it returns the ".part" file is a valid GSD file that
    // includes the frame; if the process dies inside, the file stays valid without it.
    void append(const Frame<D>& s);

    // Closes the file and renames it onto the final path; a second call does nothing.
    void commit();

    const std::filesystem::path& path() const { return path_; }
    const std::filesystem::path& part_path() const { return part_; }
    std::uint64_t frames() const { return frames_; }
    GsdMark mark() const;
    // Everything appended so far on the disk; nothing to do once committed.
    void sync();

  private:
    void write_at(std::uint64_t offset, const std::string& bytes);
    void write_header();

    std::filesystem::path path_;
    std::filesystem::path part_;
    int fd_ = -1;
    bool committed_ = false;
    std::uint64_t frames_ = 0;
    std::uint64_t file_end_ = 0;
    std::uint64_t index_location_ = 0;
    std::uint64_t index_capacity_ = 0; // entries
    std::uint64_t namelist_location_ = 0;
    std::uint64_t namelist_bytes_ = 0;
    std::string index_;                    // every entry written so far, as stored in the file
    std::vector<std::string> first_types_; // the type names of frame 0
};

} // namespace pedesis
