#include "pedesis/io/atomic_file.hpp"

#include "pedesis/core/error.hpp"

#include <cerrno>
#include <exception>
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

AtomicAppendFile::~AtomicAppendFile() = default; // the ofstream closes itself; .part stays

void AtomicAppendFile::append(const std::string& frame) {
    if (committed_) throw std::logic_error("AtomicAppendFile::append after commit");
    errno = 0;
    out_.write(frame.data(), static_cast<std::streamsize>(frame.size()));
    out_.flush();
    if (!out_) throw InputError(part_.string() + ": write error" + errno_text(errno));
}

void AtomicAppendFile::commit() {
    if (committed_) return;
    errno = 0;
    out_.close();
    if (out_.fail()) throw InputError(part_.string() + ": write error" + errno_text(errno));
    publish_part_file(part_, path_);
    committed_ = true;
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
