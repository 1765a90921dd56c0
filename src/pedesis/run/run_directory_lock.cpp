#include "pedesis/run/run_directory_lock.hpp"

#include "pedesis/core/error.hpp"
#include "pedesis/core/interrupt.hpp"
#include "pedesis/io/atomic_file.hpp"

#include <fmt/format.h>

#include <cerrno>
#include <fcntl.h>
#include <string>
#include <sys/file.h>
#include <sys/stat.h>
#include <unistd.h>

namespace pedesis {

namespace {

// "process 1234 on node17", from the file's text (at most a line of it).
std::string holder_of(int fd) {
    char text[256] = {};
    const ssize_t n = ::pread(fd, text, sizeof text - 1, 0);
    std::string s(text, n > 0 ? static_cast<std::size_t>(n) : 0);
    s = s.substr(0, s.find('\n'));
    for (char& c : s)
        if (static_cast<unsigned char>(c) < 32 || static_cast<unsigned char>(c) > 126) c = '?';
    return s.empty() ? "another process" : s;
}

} // namespace

RunDirectoryLock::RunDirectoryLock(const std::filesystem::path& dir)
    : dir_(dir), file_(dir / run_directory_lock_file) {
    std::error_code ec;
    made_dir_ = !std::filesystem::exists(dir, ec);
    std::filesystem::create_directories(dir, ec);
    if (ec) throw InputError(dir.string() + ": cannot create output directory: " + ec.message());
    // The holder removes the file as it ends; a run that opened it just before may then
    // hold a lock on a file no longer in the directory, and so it tries again (a few
    // times: each retry needs another run to end in between).
    for (int attempt = 0; attempt < 16; ++attempt) {
        errno = 0;
        const int fd = ::open(file_.c_str(), O_RDWR | O_CREAT | O_CLOEXEC, 0644);
        if (fd < 0)
            throw InputError(file_.string() + ": cannot create the run directory's lock" +
                             errno_text(errno));
        if (::flock(fd, LOCK_EX | LOCK_NB) != 0) {
            const int err = errno;
            const std::string holder = holder_of(fd);
            ::close(fd);
            if (err == EWOULDBLOCK)
                throw InputError(fmt::format(
                    "{}: in use by pedesis {} ({}); one run writes a run directory at a time: "
                    "wait for it to end, stop it, or give another --out",
                    dir.string(), holder, file_.string()));
            throw InputError(file_.string() + ": cannot lock the run directory" + errno_text(err));
        }
        struct stat held {
        }, named{};
        if (::fstat(fd, &held) == 0 && ::stat(file_.c_str(), &named) == 0 &&
            held.st_ino == named.st_ino && held.st_dev == named.st_dev) {
            fd_ = fd;
            remove_on_abrupt_end(file_.c_str(), made_dir_ ? dir_.c_str() : nullptr);
            char host[256] = {};
            ::gethostname(host, sizeof host - 1);
            const std::string me = fmt::format("process {} on {}\n", ::getpid(), host);
            if (::ftruncate(fd_, 0) == 0 && ::pwrite(fd_, me.data(), me.size(), 0) < 0) {
                // (the lock holds without the text; a second run's message says less)
            }
            return;
        }
        ::close(fd); // the file we locked was removed by the run that ended: again
    }
    throw InputError(file_.string() + ": the lock keeps changing hands; try again");
}

RunDirectoryLock::~RunDirectoryLock() {
    if (fd_ < 0) return;
    remove_on_abrupt_end(nullptr, nullptr);
    std::error_code ignored;
    std::filesystem::remove(file_, ignored);
    ::close(fd_);
    if (made_dir_ && std::filesystem::is_empty(dir_, ignored))
        std::filesystem::remove(dir_, ignored);
}

} // namespace pedesis
