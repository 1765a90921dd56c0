#include "pedesis/io/checkpoint_file.hpp"

#include "pedesis/core/error.hpp"
#include "pedesis/core/stage.hpp"
#include "pedesis/io/atomic_file.hpp"

#include <fmt/format.h>
#include <zlib.h>

#include <algorithm>
#include <array>
#include <cerrno>
#include <cstring>
#include <fcntl.h>
#include <streambuf>
#include <unistd.h>
#include <vector>

namespace pedesis {

namespace {

constexpr std::array<char, 8> magic = {'P', 'E', 'D', 'C', 'K', 'P', 'T', '1'};
constexpr std::size_t head = 16, tail = 4;

std::uint32_t crc_of(const char* data, std::size_t n, std::uint32_t crc) {
    // zlib takes lengths as uInt: feed large pieces in parts
    while (n > 0) {
        const auto piece = static_cast<uInt>(std::min<std::size_t>(n, std::size_t{1} << 30));
        crc = static_cast<std::uint32_t>(::crc32(crc, reinterpret_cast<const Bytef*>(data), piece));
        data += piece;
        n -= piece;
    }
    return crc;
}

// little-endian, as on every machine pedesis builds for
template <class T> void store(char* p, T v) {
    std::memcpy(p, &v, sizeof(T));
}
template <class T> T load(const char* p) {
    T v;
    std::memcpy(&v, p, sizeof(T));
    return v;
}

// write(2) of all of it; the errno of a failure, 0 on success
int write_all(int fd, const char* data, std::size_t n) {
    while (n > 0) {
        const ssize_t w = ::write(fd, data, n);
        if (w < 0 && errno == EINTR) continue;
        if (w <= 0) return errno ? errno : EIO;
        data += w;
        n -= static_cast<std::size_t>(w);
    }
    return 0;
}

} // namespace

// The payload's bytes go to the file in 1 MiB pieces, each added to the CRC on its way.
class CheckpointWriter::Buffer : public std::streambuf {
  public:
    explicit Buffer(int fd) : fd_(fd), buf_(1 << 20) {
        setp(buf_.data(), buf_.data() + buf_.size());
    }
    std::uint64_t bytes() const { return bytes_; }
    std::uint32_t crc() const { return crc_; }
    int error() const { return error_; }

  protected:
    int overflow(int c) override {
        if (!drain()) return traits_type::eof();
        if (c != traits_type::eof()) {
            *pptr() = static_cast<char>(c);
            pbump(1);
        }
        return traits_type::not_eof(c);
    }
    int sync() override { return drain() ? 0 : -1; }

  private:
    bool drain() {
        const auto n = static_cast<std::size_t>(pptr() - pbase());
        if (n > 0 && error_ == 0) {
            crc_ = crc_of(pbase(), n, crc_);
            bytes_ += n;
            error_ = write_all(fd_, pbase(), n);
        }
        setp(buf_.data(), buf_.data() + buf_.size());
        return error_ == 0;
    }

    int fd_;
    std::vector<char> buf_;
    std::uint64_t bytes_ = 0;
    std::uint32_t crc_ = 0;
    int error_ = 0;
};

CheckpointWriter::CheckpointWriter(const std::filesystem::path& path) : path_(path), tmp_(path) {
    tmp_ += ".tmp." + std::to_string(::getpid());
    fd_ = ::open(tmp_.c_str(), O_WRONLY | O_CREAT | O_TRUNC | O_CLOEXEC, 0644);
    if (fd_ < 0) throw InputError(path.string() + ": cannot open for writing" + errno_text(errno));
    // the head is written last, when the payload's length is known
    const char zeros[head] = {};
    if (const int err = write_all(fd_, zeros, head)) {
        ::close(fd_);
        fd_ = -1;
        throw InputError(path.string() + ": cannot write the checkpoint" + errno_text(err));
    }
    buffer_ = std::make_unique<Buffer>(fd_);
    out_ = std::make_unique<std::ostream>(buffer_.get());
}

CheckpointWriter::~CheckpointWriter() {
    if (fd_ >= 0) ::close(fd_);
    if (!committed_) {
        std::error_code ignored;
        std::filesystem::remove(tmp_, ignored);
    }
}

void CheckpointWriter::commit() {
    out_->flush();
    int err = buffer_->error();
    char front[head];
    std::memcpy(front, magic.data(), magic.size());
    store<std::uint64_t>(front + magic.size(), buffer_->bytes());
    char back[tail];
    store<std::uint32_t>(back, crc_of(front, head, buffer_->crc()));
    if (err == 0) err = write_all(fd_, back, tail);
    if (err == 0 && ::pwrite(fd_, front, head, 0) != static_cast<ssize_t>(head)) err = errno;
    // a checkpoint must survive a crash of the machine, not only of the process
    if (err == 0 && ::fsync(fd_) != 0) err = errno;
    if (::close(fd_) != 0 && err == 0) err = errno;
    fd_ = -1;
    if (err != 0)
        throw InputError(path_.string() + ": cannot write the checkpoint" + errno_text(err));
    publish_part_file(tmp_, path_);
    committed_ = true;
}

CheckpointReader::CheckpointReader(const std::filesystem::path& path) : name_(path.string()) {
    enter_stage("reading a checkpoint");
    std::error_code ec;
    if (!std::filesystem::is_regular_file(path, ec))
        throw InputError(name_ + ": no such checkpoint file");
    const std::uintmax_t size = std::filesystem::file_size(path, ec);
    if (ec) throw InputError(name_ + ": cannot read the checkpoint: " + ec.message());
    in_.open(path, std::ios::binary);
    if (!in_) throw InputError(name_ + ": cannot open the checkpoint");
    if (size < head + tail)
        throw InputError(
            fmt::format("{}: {} bytes is too short for a pedesis checkpoint", name_, size));
    char front[head];
    in_.read(front, head);
    if (!in_ || std::memcmp(front, magic.data(), magic.size()) != 0)
        throw InputError(name_ + ": not a pedesis checkpoint (it does not begin with PEDCKPT1; "
                                 "checkpoints of a pedesis before 2026-11-24 have no checksum "
                                 "and must be written again)");
    const auto n = load<std::uint64_t>(front + magic.size());
    if (n != size - head - tail)
        throw InputError(fmt::format("{}: the checkpoint says it holds {} bytes of state but the "
                                     "file has room for {} (truncated, extended or corrupt)",
                                     name_, n, size - head - tail));
    std::vector<char> piece(1 << 20);
    std::uint32_t crc = 0;
    for (std::uint64_t left = n; left > 0;) {
        const auto k = static_cast<std::size_t>(std::min<std::uint64_t>(left, piece.size()));
        in_.read(piece.data(), static_cast<std::streamsize>(k));
        if (!in_) throw InputError(name_ + ": the checkpoint could not be read to its end");
        crc = crc_of(piece.data(), k, crc);
        left -= k;
    }
    char back[tail];
    in_.read(back, tail);
    if (!in_) throw InputError(name_ + ": the checkpoint could not be read to its end");
    crc = crc_of(front, head, crc);
    if (crc != load<std::uint32_t>(back))
        throw InputError(fmt::format("{}: checksum mismatch (stored {:08x}, computed {:08x}): "
                                     "the file is corrupt",
                                     name_, load<std::uint32_t>(back), crc));
    end_ = head + n;
    in_.clear();
    in_.seekg(static_cast<std::streamoff>(head));
}

bool CheckpointReader::has_more() {
    const auto at = in_.tellg();
    return at >= 0 && static_cast<std::uint64_t>(at) < end_;
}

void CheckpointReader::finish() {
    const auto at = in_.tellg();
    if (at < 0 || static_cast<std::uint64_t>(at) != end_)
        throw InputError(name_ + ": the state ends before the end of the checkpoint (corrupt)");
}

} // namespace pedesis
