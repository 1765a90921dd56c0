#include "pedesis/io/atomic_file.hpp"

#include "pedesis/core/error.hpp"

#include <cerrno>
#include <exception>
#include <fcntl.h>
#include <stdexcept>
#include <system_error>
#include <unistd.h>
#include <utility>

namespace pedesis {

namespace {

namespace fs = std::filesystem;

void remove_quietly(const fs::path& p) {
    std::error_code ignored;
    fs::remove(p, ignored);
}

// A name unique per process, in the same directory so that the rename cannot
// cross file systems (which would make it a copy, and not atomic).
fs::path temporary_for(const fs::path& path) {
    fs::path tmp = path;
    tmp += ".tmp." + std::to_string(::getpid());
    return tmp;
}

void rename_onto(const fs::path& from, const fs::path& to) {
    std::error_code ec;
    fs::rename(from, to, ec);
    if (ec) {
        remove_quietly(from);
        throw InputError(to.string() + ": cannot replace the file: " + ec.message());
    }
}

} // namespace

void write_file_atomically(const fs::path& path, const std::function<void(std::ostream&)>& body,
                           bool binary) {
    const fs::path tmp = temporary_for(path);
    const auto mode =
        std::ios::out | std::ios::trunc | (binary ? std::ios::binary : std::ios::openmode{});
    errno = 0;
    std::ofstream out(tmp, mode);
    if (!out) throw InputError(path.string() + ": cannot open for writing" + errno_text(errno));

    try {
        body(out);
    } catch (const InputError&) {
        out.close();
        remove_quietly(tmp);
        throw;
    } catch (const RunError&) {
        out.close();
        remove_quietly(tmp);
        throw;
    } catch (const std::exception& e) {
        out.close();
        remove_quietly(tmp);
        throw InputError(path.string() + ": writing failed: " + e.what());
    } catch (...) {
        out.close();
        remove_quietly(tmp);
        throw InputError(path.string() + ": writing failed");
    }

    errno = 0;
    out.flush();
    out.close(); // close() flushes the last buffer; only then is the stream state final
    if (out.fail()) {
        const int err = errno;
        remove_quietly(tmp);
        throw InputError(path.string() + ": write error" + errno_text(err));
    }
    rename_onto(tmp, path);
}

AtomicAppendFile::AtomicAppendFile(fs::path path) : path_(std::move(path)), part_(path_) {
    part_ += ".part";
    errno = 0;
    out_.open(part_, std::ios::out | std::ios::trunc | std::ios::binary);
    if (!out_) throw InputError(part_.string() + ": cannot open for writing" + errno_text(errno));
    std::error_code ec;
    fs::remove(path_, ec);
    if (ec) throw InputError(path_.string() + ": cannot remove the old file: " + ec.message());
}

AtomicAppendFile::AtomicAppendFile(fs::path path, std::uintmax_t keep)
    : path_(std::move(path)), part_(path_) {
    part_ += ".part";
    cut_back_part_file(path_, part_, keep);
    errno = 0;
    out_.open(part_, std::ios::out | std::ios::app | std::ios::binary);
    if (!out_) throw InputError(part_.string() + ": cannot open for writing" + errno_text(errno));
    bytes_ = keep;
}

AtomicAppendFile::~AtomicAppendFile() = default; // the ofstream closes itself; .part stays

void AtomicAppendFile::append(const std::string& frame) {
    if (committed_) throw std::logic_error("AtomicAppendFile::append after commit");
    errno = 0;
    out_.write(frame.data(), static_cast<std::streamsize>(frame.size()));
    out_.flush();
    if (!out_) throw InputError(part_.string() + ": write error" + errno_text(errno));
    bytes_ += frame.size();
}

void AtomicAppendFile::sync() {
    if (!committed_) sync_file(part_);
}

void AtomicAppendFile::commit() {
    if (committed_) return;
    errno = 0;
    out_.close();
    if (out_.fail()) throw InputError(part_.string() + ": write error" + errno_text(errno));
    publish_part_file(part_, path_);
    committed_ = true;
}

void cut_back_part_file(const fs::path& path, const fs::path& part, std::uintmax_t keep) {
    std::error_code ec;
    if (!fs::exists(part, ec) && fs::exists(path, ec)) {
        fs::rename(path, part, ec);
        if (ec)
            throw InputError(path.string() + ": cannot rename it back to " + part.string() +
                             " to continue it: " + ec.message());
    }
    const std::uintmax_t size = fs::file_size(part, ec);
    if (ec)
        throw InputError(part.string() + ": missing, so the run cannot continue in place (" +
                         ec.message() + ")");
    if (size < keep)
        throw InputError(part.string() + ": " + std::to_string(size) + " bytes, shorter than the " +
                         std::to_string(keep) +
                         " the checkpoint recorded: not the file the checkpoint knew");
    fs::resize_file(part, keep, ec);
    if (ec) throw InputError(part.string() + ": cannot cut it back: " + ec.message());
}

void sync_file(const fs::path& file) {
    errno = 0;
    const int fd = ::open(file.c_str(), O_RDONLY | O_CLOEXEC);
    int err = fd < 0 ? errno : 0;
    if (fd >= 0) {
        if (::fsync(fd) != 0) err = errno;
        ::close(fd);
    }
    if (err != 0)
        throw InputError(file.string() + ": cannot write it to the disk" + errno_text(err));
}

std::string errno_text(int err) {
    return err != 0 ? ": " + std::generic_category().message(err) : std::string{};
}

void publish_part_file(const fs::path& part, const fs::path& path) {
    std::error_code ec;
    fs::rename(part, path, ec);
    if (ec)
        throw InputError(path.string() + ": cannot rename " + part.string() + ": " + ec.message());
}

} // namespace pedesis
