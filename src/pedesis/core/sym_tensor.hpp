#pragma once
// A symmetric d x d tensor (the pressure tensor and its parts) by its independent
// components in a fixed order: xx, yy, zz, xy, xz, yz. In 2D the slots of zz, xz and yz
// stay zero. C++17: the CUDA kernels sum into the same slots.
#include "pedesis/core/host_device.hpp"

#include <array>

namespace pedesis {

using SymTensor = std::array<double, 6>;

// The slot of component (a, b), a, b < 3: the diagonal first, then xy, xz, yz.
PEDESIS_HD constexpr int sym_slot(int a, int b) {
    return a == b ? a : a + b + 2;
}

// The components a d-dimensional tensor has: d diagonal and d (d - 1) / 2 off-diagonal.
constexpr int sym_components(int d) {
    return d * (d + 1) / 2;
}

// "xx", "yy", "zz", "xy", "xz", "yz" by slot.
constexpr const char* sym_suffix(int slot) {
    constexpr const char* names[6] = {"xx", "yy", "zz", "xy", "xz", "yz"};
    return names[slot];
}

// The slots of a d-dimensional tensor in log order (xx, yy, [zz,] xy[, xz, yz]).
template <int D> constexpr std::array<int, sym_components(D)> sym_slots() {
    if constexpr (D == 2)
        return {0, 1, 3};
    else
        return {0, 1, 2, 3, 4, 5};
}

// sum over the diagonal
template <int D> double sym_trace(const SymTensor& t) {
    double s = 0.0;
    for (int a = 0; a < D; ++a) s += t[a];
    return s;
}

// (a + b) / 2 by component: a quantity's mean over an interval from its two ends
inline SymTensor sym_midpoint(const SymTensor& a, const SymTensor& b) {
    SymTensor m;
    for (int c = 0; c < 6; ++c) m[c] = 0.5 * (a[c] + b[c]);
    return m;
}

// t += w x y (symmetrised: (w_a y_b + w_b y_a) / 2 off the diagonal)
template <int D, class V> void add_sym_outer(SymTensor& t, const V& w, const V& y, double k = 1.0) {
    for (int a = 0; a < D; ++a)
        for (int b = a; b < D; ++b)
            t[sym_slot(a, b)] += k * (a == b ? w[a] * y[a] : 0.5 * (w[a] * y[b] + w[b] * y[a]));
}

} // namespace pedesis
