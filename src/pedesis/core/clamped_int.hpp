#pragma once
// A double turned into an int within [lo, hi]. A plain cast of a value outside int's range
// (or of NaN) is undefined behaviour, and crafted files or blow-ups can make such values
// where a grid index is computed; NaN goes to lo.
namespace pedesis {

inline int clamped_int(double x, int lo, int hi) {
    if (!(x >= lo)) return lo; // also NaN
    if (x >= hi) return hi;
    return static_cast<int>(x);
}

} // namespace pedesis
