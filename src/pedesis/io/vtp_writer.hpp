#pragma once
// VTK XML PolyData snapshots (.vtp), one file per snapshot, for ParaView.
#include "pedesis/core/frame.hpp"

#include <filesystem>
#include <string>

namespace pedesis {

// One snapshot: every particle is a point and a vertex cell (without cells ParaView
// draws nothing), rows in tag order so that point k is the same particle in every
// file. Point arrays: id (the tag), type (species index), radius, director (if the
// frame has one), velocity, mass ("inf" for a fixed obstacle), force (if the frame has
// one); vectors have three components, with z = 0 in 2D. The simulation time is the
// field array TimeValue. Values are ASCII, each the shortest text that reads back to
// the same double: the files stay diffable and exact, at the cost of size.
template <int D> std::string vtp_document(const Frame<D>& s);

// vtp_document written atomically: `path` is either absent, the old file, or complete.
template <int D> void write_vtp(const std::filesystem::path& path, const Frame<D>& s);

} // namespace pedesis
