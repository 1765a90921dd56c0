#include "pedesis/render/ffmpeg_encoder.hpp"

#include "pedesis/core/error.hpp"
#include "pedesis/io/atomic_file.hpp"

#include <fmt/format.h>

#include <cerrno>
#include <cstdlib>
#include <fcntl.h>
#include <spawn.h>
#include <string>
#include <sys/stat.h>
#include <sys/wait.h>
#include <system_error>
#include <unistd.h>

extern char** environ;

namespace pedesis::render {

namespace fs = std::filesystem;

namespace {

void remove_quietly(const fs::path& p) {
    std::error_code ignored;
    fs::remove(p, ignored);
}

std::vector<std::string> ffmpeg_arguments(const fs::path& ffmpeg, const fs::path& output,
                                          MovieFormat format, int width, int height, double fps) {
    std::vector<std::string> args = {ffmpeg.string(),
                                     "-hide_banner",
                                     "-loglevel",
                                     "error",
                                     "-y",
                                     "-f",
                                     "rawvideo",
                                     "-pix_fmt",
                                     "rgb24",
                                     "-video_size",
                                     fmt::format("{}x{}", width, height),
                                     "-framerate",
                                     fmt::format("{}", fps),
                                     "-i",
                                     "pipe:0"};
    if (format == MovieFormat::mp4) {
        // +faststart puts the index first, so a browser starts playing before the end arrives.
        args.insert(args.end(), {"-c:v", "libx264", "-crf", "20", "-pix_fmt", "yuv420p",
                                 "-movflags", "+faststart", "-f", "mp4"});
    } else {
        // One palette for the whole movie keeps colours steady from frame to frame.
        args.insert(args.end(), {"-vf",
                                 "split[a][b];[a]palettegen=stats_mode=full[p];[b][p]paletteuse="
                                 "dither=bayer:bayer_scale=4",
                                 "-loop", "0", "-f", "gif"});
    }
    // The temporary name has no movie extension, hence the explicit -f above.
    args.push_back(output.string());
    return args;
}

} // namespace

fs::path find_ffmpeg(const fs::path& target) {
    const char* env = std::getenv("PATH");
    const std::string path = env ? env : "/usr/local/bin:/usr/bin:/bin";
    std::size_t start = 0;
    while (start <= path.size()) {
        std::size_t end = path.find(':', start);
        if (end == std::string::npos) end = path.size();
        const std::string dir = path.substr(start, end - start);
        const fs::path candidate = fs::path(dir.empty() ? "." : dir) / "ffmpeg";
        struct stat st {};
        if (::stat(candidate.c_str(), &st) == 0 && S_ISREG(st.st_mode) &&
            ::access(candidate.c_str(), X_OK) == 0)
            return candidate;
        start = end + 1;
    }
    throw InputError(target.string() +
                     ": ffmpeg not found; install Debian's ffmpeg or render PNG frames with "
                     "--out DIR/");
}

FfmpegEncoder::FfmpegEncoder(const fs::path& ffmpeg, const fs::path& target, MovieFormat format,
                             int width, int height, double fps)
    : target_(target), temporary_(target),
      frame_bytes_(static_cast<std::size_t>(width) * static_cast<std::size_t>(height) * 3) {
    temporary_ += ".tmp." + std::to_string(::getpid());
    const std::vector<std::string> args =
        ffmpeg_arguments(ffmpeg, temporary_, format, width, height, fps);
    std::vector<char*> argv;
    for (const std::string& a : args) argv.push_back(const_cast<char*>(a.c_str()));
    argv.push_back(nullptr);

    log_ = std::tmpfile();
    if (!log_) throw InputError(target_.string() + ": cannot make a temporary file for ffmpeg");
    int fds[2];
    if (::pipe2(fds, O_CLOEXEC) != 0) {
        const int err = errno;
        std::fclose(log_);
        throw InputError(target_.string() + ": cannot make a pipe to ffmpeg" + errno_text(err));
    }

    posix_spawn_file_actions_t actions;
    posix_spawn_file_actions_init(&actions);
    posix_spawn_file_actions_adddup2(&actions, fds[0], STDIN_FILENO);
    posix_spawn_file_actions_addopen(&actions, STDOUT_FILENO, "/dev/null", O_WRONLY, 0);
    posix_spawn_file_actions_adddup2(&actions, fileno(log_), STDERR_FILENO);
    // The parent ignores SIGPIPE (below); ffmpeg must not inherit that.
    posix_spawnattr_t attributes;
    posix_spawnattr_init(&attributes);
    sigset_t defaults;
    sigemptyset(&defaults);
    sigaddset(&defaults, SIGPIPE);
    posix_spawnattr_setsigdefault(&attributes, &defaults);
    posix_spawnattr_setflags(&attributes, POSIX_SPAWN_SETSIGDEF);
    const int rc = ::posix_spawn(&pid_, argv[0], &actions, &attributes, argv.data(), environ);
    posix_spawn_file_actions_destroy(&actions);
    posix_spawnattr_destroy(&attributes);
    ::close(fds[0]);
    if (rc != 0) {
        pid_ = -1;
        ::close(fds[1]);
        std::fclose(log_);
        throw InputError(target_.string() + ": cannot start " + ffmpeg.string() + errno_text(rc));
    }
    pipe_ = fds[1];

    // A dead ffmpeg must show up as a failed write (EPIPE) that we can report and clean
    // up after, not as a signal that kills pedesis and leaves the temporary behind.
    struct sigaction ignore {};
    ignore.sa_handler = SIG_IGN;
    sigemptyset(&ignore.sa_mask);
    ::sigaction(SIGPIPE, &ignore, &old_sigpipe_);
}

FfmpegEncoder::~FfmpegEncoder() {
    if (pipe_ >= 0) ::close(pipe_);
    if (pid_ > 0) {
        ::kill(pid_, SIGTERM);
        wait_for_child();
    }
    remove_quietly(temporary_);
    if (log_) std::fclose(log_);
    ::sigaction(SIGPIPE, &old_sigpipe_, nullptr);
}

void FfmpegEncoder::write_frame(const std::vector<std::uint8_t>& rgb) {
    if (rgb.size() != frame_bytes_)
        throw std::logic_error("FfmpegEncoder::write_frame: wrong frame size");
    std::size_t done = 0;
    while (done < rgb.size()) {
        const ssize_t w = ::write(pipe_, rgb.data() + done, rgb.size() - done);
        if (w < 0 && errno == EINTR) continue;
        if (w <= 0) fail("ffmpeg stopped reading frames");
        done += static_cast<std::size_t>(w);
    }
}

void FfmpegEncoder::finish() {
    ::close(pipe_);
    pipe_ = -1;
    const int status = wait_for_child();
    if (status != 0) {
        remove_quietly(temporary_);
        throw InputError(fmt::format("{}: ffmpeg failed (exit status {}): {}", target_.string(),
                                     status, ffmpeg_messages()));
    }
    std::error_code ec;
    fs::rename(temporary_, target_, ec);
    if (ec) {
        remove_quietly(temporary_);
        throw InputError(target_.string() + ": cannot replace the file: " + ec.message());
    }
}

void FfmpegEncoder::fail(const std::string& what) {
    ::close(pipe_);
    pipe_ = -1;
    const int status = pid_ > 0 ? wait_for_child() : -1;
    remove_quietly(temporary_);
    throw InputError(fmt::format("{}: {} (ffmpeg exit status {}): {}", target_.string(), what,
                                 status, ffmpeg_messages()));
}

// The exit status, or 128 + the signal that ended ffmpeg, as a shell reports it.
int FfmpegEncoder::wait_for_child() {
    int status = 0;
    while (::waitpid(pid_, &status, 0) < 0 && errno == EINTR) {
    }
    pid_ = -1;
    if (WIFEXITED(status)) return WEXITSTATUS(status);
    return WIFSIGNALED(status) ? 128 + WTERMSIG(status) : 1;
}

// The last lines ffmpeg wrote to its stderr.
std::string FfmpegEncoder::ffmpeg_messages() {
    if (!log_) return "";
    std::fflush(log_);
    std::rewind(log_);
    std::string text;
    char buf[4096];
    std::size_t n;
    while ((n = std::fread(buf, 1, sizeof buf, log_)) > 0) text.append(buf, n);
    while (!text.empty() && (text.back() == '\n' || text.back() == '\r')) text.pop_back();
    if (text.size() > 600) text = "..." + text.substr(text.size() - 600);
    return text.empty() ? "(ffmpeg printed nothing)" : text;
}

} // namespace pedesis::render
