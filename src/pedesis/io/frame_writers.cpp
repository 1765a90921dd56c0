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

template <int D>
FrameWriters<D>::FrameWriters(const std::filesystem::path& dir,
                              const std::vector<std::string>& formats)
    : dir_(dir) {
    for (const std::string& f : formats) {
        if (std::find(frame_formats.begin(), frame_formats.end(), f) == frame_formats.end())
            throw InputError("unknown frame format \"" + f + "\" (known: " + frame_format_list() +
                             ")");
        vtp_ = vtp_ || f == "vtp";
        json_ = json_ || f == "json";
        table_ = table_ || f == "table";
        if (f == "xyz" && !xyz_) xyz_ = std::make_unique<AtomicAppendFile>(dir / "trajectory.xyz");
        if (f == "gsd" && !gsd_) gsd_ = std::make_unique<GsdWriter<D>>(dir / "trajectory.gsd");
    }
    // snapshots/ only for the formats that write there: an empty folder in a run
    // directory looks like frames that went missing (issue 28)
    if (vtp_ || json_ || table_) {
        std::error_code ec;
        std::filesystem::create_directories(dir / "snapshots", ec);
        if (ec)
            throw InputError((dir / "snapshots").string() +
                             ": cannot create the snapshot directory: " + ec.message());
    }
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
