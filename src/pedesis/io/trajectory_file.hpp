#pragma once
// A trajectory a script asked for, in GSD or extended XYZ: frames appended as they come,
// the file renamed onto its final name at commit (until then it is `path` + ".part",
// complete up to its last frame).
#include "pedesis/core/error.hpp"
#include "pedesis/core/frame.hpp"
#include "pedesis/io/atomic_file.hpp"
#include "pedesis/io/gsd_writer.hpp"
#include "pedesis/io/xyz_writer.hpp"

#include <filesystem>
#include <memory>
#include <string>

namespace pedesis {

template <int D> class TrajectoryFile {
  public:
    // format: "gsd" or "xyz"; anything else is an InputError.
    TrajectoryFile(const std::filesystem::path& path, const std::string& format) {
        if (format == "gsd")
            gsd_ = std::make_unique<GsdWriter<D>>(path);
        else if (format == "xyz")
            xyz_ = std::make_unique<AtomicAppendFile>(path);
        else
            throw InputError("trajectory format '" + format + "' (known: gsd, xyz)");
    }
    void append(const Frame<D>& f) {
        if (gsd_) gsd_->append(f);
        if (xyz_) xyz_->append(xyz_frame(f));
    }
    void commit() {
        if (gsd_) gsd_->commit();
        if (xyz_) xyz_->commit();
    }

  private:
    std::unique_ptr<GsdWriter<D>> gsd_;
    std::unique_ptr<AtomicAppendFile> xyz_;
};

} // namespace pedesis
