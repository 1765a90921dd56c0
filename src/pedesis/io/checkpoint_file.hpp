#pragma once
// The envelope of every checkpoint.bin: what makes a corrupt or foreign file an error
// with a message instead of a crash, a hang or a silently wrong state.
//
//   "PEDCKPT1"  8 bytes   magic and envelope version
//   n           8 bytes   payload length, little-endian
//   payload     n bytes   the engine's own format (its magic, version, state)
//   crc         4 bytes   CRC-32 (zlib's) of the payload, then of the first 16 bytes
//
// A file is accepted only if its length is exactly 20 + n and the CRC matches: one flipped
// bit anywhere, a truncation or an appended byte is caught before the payload is parsed,
// and the payload's readers then check every length against the bytes left
// (binary_stream.hpp), so no allocation is larger than the file. Both directions stream:
// a checkpoint of 10^7 particles is never held in memory twice.
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <istream>
#include <memory>
#include <ostream>

namespace pedesis {

// Writes a checkpoint: the payload goes to out(); commit() completes the envelope, flushes
// the file to the disk (fsync) and renames it onto `path`, so `path` is the old complete
// file or the new one. Without commit() (an exception) the temporary file is removed.
class CheckpointWriter {
  public:
    explicit CheckpointWriter(const std::filesystem::path& path);
    ~CheckpointWriter();
    CheckpointWriter(const CheckpointWriter&) = delete;
    CheckpointWriter& operator=(const CheckpointWriter&) = delete;

    std::ostream& out() { return *out_; }
    void commit();

  private:
    class Buffer;
    std::filesystem::path path_, tmp_;
    int fd_ = -1;
    std::unique_ptr<Buffer> buffer_;
    std::unique_ptr<std::ostream> out_;
    bool committed_ = false;
};

// Opens a checkpoint, checks its envelope and CRC in one pass over the file, and leaves
// in() at the start of the payload. InputError naming the file and what is wrong: missing,
// too short, not a pedesis checkpoint, truncated or extended, checksum mismatch.
class CheckpointReader {
  public:
    explicit CheckpointReader(const std::filesystem::path& path);
    std::istream& in() { return in_; }
    // InputError unless the payload was read exactly to its end.
    void finish();
    // Whether the payload goes on: a later version's fields after the ones read so far.
    bool has_more();

  private:
    std::string name_;
    std::ifstream in_;
    std::uint64_t end_ = 0; // offset of the end of the payload
};

} // namespace pedesis
