#pragma once
// What `pedesis run --resume` needs beside a checkpoint to continue a run in its own
// directory: how long each growing output was when the checkpoint was written, so that
// everything written after it (rows, frames, snapshots) is cut away and written again,
// and the finished directory is the one a run that never stopped would have left.
//
// The record, checkpoint.outputs.json, keeps the marks of the newest checkpoint and of the
// one before it: it is written just before checkpoint.bin, so a process killed between
// the two leaves the older checkpoint and its marks. A finished run keeps only its final
// checkpoint's. Times are stored as their bits, so that a mark matches its checkpoint
// exactly.
#include "pedesis/io/frame_writers.hpp"

#include <cstdint>
#include <filesystem>
#include <optional>
#include <vector>

namespace pedesis {

inline constexpr const char* checkpoint_record_file = "checkpoint.outputs.json";

struct OutputMarks {
    std::uint64_t step = 0;
    double time = 0.0;
    std::uintmax_t log_bytes = 0;
    FrameMarks frames;
    bool final = false; // written at the end of a finished run
};

// Whether `m` belongs to a checkpoint at (step, time), to the bit.
bool marks_at(const OutputMarks& m, std::uint64_t step, double time);

// Atomic, and on the disk before it returns (fsync): the checkpoint that follows must not
// reach the disk before its marks.
void write_checkpoint_record(const std::filesystem::path& file,
                             const std::vector<OutputMarks>& marks);

// InputError naming the file for anything but a record this version writes (missing,
// over 1 MiB, not JSON, a field missing or of the wrong type).
std::vector<OutputMarks> read_checkpoint_record(const std::filesystem::path& file);

} // namespace pedesis
