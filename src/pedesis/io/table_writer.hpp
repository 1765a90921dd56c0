#pragma once
// Plain-text table of a frame, the layout of the ABP tutorial's
// Dump.dump_data ("# id x y nx ny vx vy fx fy"), for numpy.loadtxt, awk and gnuplot.
#include "pedesis/core/frame.hpp"

#include <filesystem>
#include <string>

namespace pedesis {

// Two comment lines, then one row per particle in tag order:
//   # time=T step=S Lx=.. Ly=.. [Lz=..]
//   # id x y nx ny vx vy fx fy            (3D: id x y z nx ny nz vx vy vz fx fy fz)
//   0 -3.25 1.5 0.6 0.8 0 0 0 0
// A frame without directors or forces (hard particles) leaves out those columns:
//   # id x y vx vy
// Columns are separated by one space; every value is the shortest text that reads
// back to the same double, so the table is exact and diffable.
template <int D> std::string table_frame(const Frame<D>& s);

// table_frame written atomically: `path` is either absent, the old file, or complete.
template <int D> void write_table(const std::filesystem::path& path, const Frame<D>& s);

} // namespace pedesis
