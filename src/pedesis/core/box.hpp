#pragma once
// The simulation box: orthorhombic, centred at the origin (the convention of the
// tutorial of seed 001 and of HOOMD-blue), each axis periodic or bounded by walls.
// Minimum image and wrapping live here and nowhere else.
#include "pedesis/core/error.hpp"
#include "pedesis/core/vec.hpp"

#include <array>
#include <cmath>
#include <string>

namespace pedesis {

template <int D> class Box {
  public:
    Box() = default;
    Box(const Vec<D>& lengths, const std::array<bool, D>& periodic)
        : L_(lengths), periodic_(periodic) {
        for (int a = 0; a < D; ++a) {
            if (!(std::isfinite(L_[a]) && L_[a] > 0.0))
                throw InputError("box: length along axis " + std::to_string(a) +
                                 " must be a positive finite number");
            half_[a] = 0.5 * L_[a];
        }
    }

    const Vec<D>& lengths() const { return L_; }
    double length(int a) const { return L_[a]; }
    double lo(int a) const { return -half_[a]; }
    double hi(int a) const { return half_[a]; }
    bool periodic(int a) const { return periodic_[a]; }
    bool any_wall() const {
        for (int a = 0; a < D; ++a)
            if (!periodic_[a]) return true;
        return false;
    }
    double volume() const {
        double v = 1.0;
        for (int a = 0; a < D; ++a) v *= L_[a];
        return v;
    }

    // Valid for displacements within (-1.5 L, 1.5 L) on periodic axes, which is all
    // the engines ever produce (positions are kept within a fraction of L of the box).
    Vec<D> minimum_image(Vec<D> d) const {
        for (int a = 0; a < D; ++a) {
            if (!periodic_[a]) continue;
            if (d[a] > half_[a])
                d[a] -= L_[a];
            else if (d[a] < -half_[a])
                d[a] += L_[a];
        }
        return d;
    }

    // Wraps periodic axes into [-L/2, L/2); returns the image shift applied (in units of L).
    Vec<D> wrap(Vec<D>& r) const {
        Vec<D> shift{};
        for (int a = 0; a < D; ++a) {
            if (!periodic_[a] || (r[a] >= -half_[a] && r[a] < half_[a])) continue;
            const double k = std::floor((r[a] + half_[a]) / L_[a]);
            r[a] -= k * L_[a];
            shift[a] = k;
            // rounding can leave r a hair outside; both ends are the same point of the torus
            if (r[a] >= half_[a]) {
                r[a] -= L_[a];
                shift[a] += 1.0;
            }
            if (r[a] < -half_[a]) {
                r[a] += L_[a];
                shift[a] -= 1.0;
            }
            if (r[a] >= half_[a]) r[a] = -half_[a];
        }
        return shift;
    }

    bool contains(const Vec<D>& r, double margin = 0.0) const {
        for (int a = 0; a < D; ++a) {
            if (periodic_[a]) continue;
            if (r[a] < -half_[a] + margin || r[a] > half_[a] - margin) return false;
        }
        return true;
    }

  private:
    Vec<D> L_{};
    Vec<D> half_{};
    std::array<bool, D> periodic_{};
};

} // namespace pedesis
