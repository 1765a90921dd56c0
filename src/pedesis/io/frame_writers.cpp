#include "pedesis/io/frame_writers.hpp"

#include "pedesis/core/error.hpp"
#include "pedesis/io/table_writer.hpp"
#include "pedesis/io/tutorial_json.hpp"
#include "pedesis/io/vtp_writer.hpp"
#include "pedesis/io/xyz_writer.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <ostream>

namespace pedesis {

std::string frame_format_list() {
    std::string s;
    for (const char* f : frame_formats) s += fmt::format("{}\"{}\"", s.empty() ? "" : ", ", f);
    return s;
}

template <int D> void FrameWriters<D>::choose(const std::vector<std::string>& formats) {
    for (const std::string& f : formats) {
        if (std::find(frame_formats.begin(), frame_formats.end(), f) == frame_formats.end())
            throw InputError("unknown frame format \"" + f + "\" (known: " + frame_format_list() +
                             ")");
        vtp_ = vtp_ || f == "vtp";
        json_ = json_ || f == "json";
        table_ = table_ || f == "table";
    }
}

// snapshots/ only for the formats that write there: an empty folder in a run directory
// looks like frames that went missing (issue 28)
template <int D> void FrameWriters<D>::make_snapshot_directory() const {
    if (!(vtp_ || json_ || table_)) return;
    std::error_code ec;
    std::filesystem::create_directories(dir_ / "snapshots", ec);
    if (ec)
        throw InputError((dir_ / "snapshots").string() +
                         ": cannot create the snapshot directory: " + ec.message());
}

template <int D>
FrameWriters<D>::FrameWriters(const std::filesystem::path& dir,
                              const std::vector<std::string>& formats)
    : dir_(dir) {
    choose(formats);
    const auto has = [&](const char* f) {
        return std::find(formats.begin(), formats.end(), f) != formats.end();
    };
    if (has("xyz")) xyz_ = std::make_unique<AtomicAppendFile>(dir / "trajectory.xyz");
    if (has("gsd")) gsd_ = std::make_unique<GsdWriter<D>>(dir / "trajectory.gsd");
    make_snapshot_directory();
}

template <int D>
FrameWriters<D>::FrameWriters(const std::filesystem::path& dir,
                              const std::vector<std::string>& formats, const FrameMarks& marks)
    : dir_(dir) {
    choose(formats);
    const auto has = [&](const char* f) {
        return std::find(formats.begin(), formats.end(), f) != formats.end();
    };
    if (has("xyz"))
        xyz_ = std::make_unique<AtomicAppendFile>(dir / "trajectory.xyz", marks.xyz_bytes);
    if (has("gsd")) gsd_ = std::make_unique<GsdWriter<D>>(dir / "trajectory.gsd", marks.gsd);
    make_snapshot_directory();
    // the snapshots written after the checkpoint (frame_NNNNNN.*, NNNNNN >= marks.frames)
    std::error_code ec;
    if (!std::filesystem::is_directory(dir / "snapshots", ec)) return;
    std::vector<std::filesystem::path> later;
    for (const auto& entry : std::filesystem::directory_iterator(dir / "snapshots", ec)) {
        const std::string name = entry.path().filename().string();
        if (name.rfind("frame_", 0) != 0) continue;
        const std::size_t dot = name.find('.');
        const std::string digits = name.substr(6, dot == std::string::npos ? 0 : dot - 6);
        if (digits.empty() || digits.size() > 19 ||
            digits.find_first_not_of("0123456789") != std::string::npos)
            continue;
        if (std::stoull(digits) >= marks.frames) later.push_back(entry.path());
    }
    for (const auto& p : later) std::filesystem::remove(p, ec);
}

template <int D> FrameMarks FrameWriters<D>::marks(std::uint64_t frames) const {
    FrameMarks m;
    m.frames = frames;
    if (xyz_) m.xyz_bytes = xyz_->bytes();
    if (gsd_) m.gsd = gsd_->mark();
    return m;
}

template <int D> void FrameWriters<D>::sync() {
    if (xyz_) xyz_->sync();
    if (gsd_) gsd_->sync();
}

template <int D> void FrameWriters<D>::write(const Frame<D>& f, std::uint64_t frame_number) {
    const auto snapshot = [&](const char* ext) {
        return dir_ / "snapshots" / fmt::format("frame_{:06d}.{}", frame_number, ext);
    };
    if (vtp_) write_vtp(snapshot("vtp"), f);
    if (json_) {
        const std::string text = to_tutorial_json(f).dump() + "\n";
        write_file_atomically(snapshot("json"), [&](std::ostream& out) { out << text; });
    }
    if (table_) write_table(snapshot("txt"), f);
    if (xyz_) xyz_->append(xyz_frame(f));
    if (gsd_) gsd_->append(f);
}

template <int D> void FrameWriters<D>::commit() {
    if (xyz_) xyz_->commit();
    if (gsd_) gsd_->commit();
}

template class FrameWriters<2>;
template class FrameWriters<3>;

} // namespace pedesis
