#pragma once
// Output files that are either complete or absent. A reader (a person, a plotting
// script, a restart) must never mistake a half-written file for a finished one,
// whether the run failed, was stopped, or was killed.
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <functional>
#include <ostream>
#include <string>

namespace pedesis {

// Writes `body`'s output to a temporary file beside `path` and renames it onto
// `path` only if everything succeeded; rename within one directory is atomic on
// POSIX, so `path` holds either the old contents or the complete new ones.
// On failure the temporary is removed and an InputError naming `path` is thrown;
// an InputError or RunError thrown by `body` itself passes through unchanged.
// ": <strerror>" for a non-zero errno, "" otherwise: the tail of I/O error messages.
std::string errno_text(int err);

// Renames a finished ".part" file onto its final name; InputError naming both on failure.
void publish_part_file(const std::filesystem::path& part, const std::filesystem::path& path);

// For a run that continues in place (--resume): gives back the ".part" file `part` of the
// output `path` (renaming `path` onto it where a stopped run had published it) cut to its
// first `keep` bytes, the length it had at the checkpoint. InputError naming the file if
// neither exists or it is shorter than `keep` (then it is not the file the checkpoint
// knew).
void cut_back_part_file(const std::filesystem::path& path, const std::filesystem::path& part,
                        std::uintmax_t keep);

// Makes what was written to `file` survive a crash of the machine (fsync); InputError
// naming it if the disk refuses.
void sync_file(const std::filesystem::path& file);

void write_file_atomically(const std::filesystem::path& path,
                           const std::function<void(std::ostream&)>& body, bool binary = false);

// A trajectory that grows frame by frame. Frames go to `path` + ".part"; only
// commit() gives the file its final name, so a run that dies leaves a ".part"
// file (useful for salvage) and nothing that looks complete.
class AtomicAppendFile {
  public:
    // Truncates any earlier ".part" and removes an earlier file at `path`: a stale
    // complete file from a previous run must not pass for this run's output.
    explicit AtomicAppendFile(std::filesystem::path path);
    // Continues the file of an unfinished run from its first `keep` bytes
    // (cut_back_part_file).
    AtomicAppendFile(std::filesystem::path path, std::uintmax_t keep);
    ~AtomicAppendFile();

    AtomicAppendFile(const AtomicAppendFile&) = delete;
    AtomicAppendFile& operator=(const AtomicAppendFile&) = delete;

    // One write per frame, then a flush, so a kill leaves whole frames plus at
    // most one torn frame at the end of the ".part" file.
    void append(const std::string& frame);

    // Renames the ".part" file onto the final path. Call it on a normal end and on
    // a stopped run; a second call does nothing.
    void commit();

    const std::filesystem::path& path() const { return path_; }
    const std::filesystem::path& part_path() const { return part_; }
    bool committed() const { return committed_; }
    // The file's length: what a checkpoint records to cut it back to.
    std::uintmax_t bytes() const { return bytes_; }
    // Every byte appended so far on the disk (sync_file); nothing to do once committed.
    void sync();

  private:
    std::filesystem::path path_;
    std::filesystem::path part_;
    std::ofstream out_;
    std::uintmax_t bytes_ = 0;
    bool committed_ = false;
};

} // namespace pedesis
