#pragma once
// Movies through an ffmpeg child process: raw RGB frames go down a pipe, ffmpeg writes
// the movie to a temporary name beside the target, and only a finished, successful
// encode is renamed onto the target. A failure or an interruption removes the temporary,
// so a half-written movie never sits under the name the user asked for.
#include <signal.h>
#include <sys/types.h>

#include <cstdint>
#include <cstdio>
#include <filesystem>
#include <string>
#include <vector>

namespace pedesis::render {

enum class MovieFormat { mp4, gif };

// ffmpeg on PATH; an InputError saying how to get it, or to write PNG frames instead,
// when it is not there. `target` is named in the message.
std::filesystem::path find_ffmpeg(const std::filesystem::path& target);

class FfmpegEncoder {
  public:
    // MP4: H.264 in yuv420p (what browsers and players accept; needs even sizes).
    // GIF: a palette computed from the whole movie.
    FfmpegEncoder(const std::filesystem::path& ffmpeg, const std::filesystem::path& target,
                  MovieFormat format, int width, int height, double fps);
    // Unfinished: stops ffmpeg and removes the temporary file.
    ~FfmpegEncoder();
    FfmpegEncoder(const FfmpegEncoder&) = delete;
    FfmpegEncoder& operator=(const FfmpegEncoder&) = delete;

    // One frame of width * height * 3 bytes (rgb24).
    void write_frame(const std::vector<std::uint8_t>& rgb);

    // Ends the stream, waits for ffmpeg and renames the movie onto the target.
    void finish();

  private:
    [[noreturn]] void fail(const std::string& what);
    int wait_for_child();
    std::string ffmpeg_messages();

    std::filesystem::path target_, temporary_;
    pid_t pid_ = -1;
    int pipe_ = -1;
    std::FILE* log_ = nullptr; // ffmpeg's stderr, for the message when it fails
    std::size_t frame_bytes_ = 0;
    struct sigaction old_sigpipe_ {}; // restored when the encoder goes
};

} // namespace pedesis::render
