#pragma once
// The simulation box: orthorhombic, centred at the origin (the convention of the
// tutorial of seed 001 and of HOOMD-blue), each axis periodic or bounded by walls.
// Minimum image and wrapping live here and nowhere else.
//
// Lees-Edwards shear ([box] shear_rate, the soft engine): the flow runs along x with
// velocity rate * y, so the periodic images across the y faces slide. The image above
// (y + L_y) is displaced along x by the offset, rate L_y t (mod L_x), kept in
// [-L_x/2, L_x/2) so that a difference of two positions in the box, less the offset,
// stays within the +-1.5 L_x that one correction along x handles. Crossing the y faces
// by k images shifts x by -k offset before x itself is wrapped. Without shear (rate 0)
// every path is the plain one: one branch on a flag.
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

    // Lees-Edwards shear (above): rate > 0 turns it on, 0 off. InputError for a rate that
    // is negative or not finite, or a walled x or y axis.
    void set_shear_rate(double rate) {
        if (!(std::isfinite(rate) && rate >= 0.0))
            throw InputError("box: the shear rate must be a finite number >= 0");
        if (rate > 0.0 && !(periodic_[0] && periodic_[1]))
            throw InputError("box: Lees-Edwards shear needs periodic x (the flow) and y (the "
                             "gradient) axes");
        rate_ = rate;
        sheared_ = rate > 0.0;
        offset_ = 0.0;
    }
    bool sheared() const { return sheared_; }
    double shear_rate() const { return rate_; }
    // The x displacement of the image above, in [-L_x/2, L_x/2).
    double shear_offset() const { return offset_; }
    // Any offset, brought into [-L_x/2, L_x/2); InputError if it is not finite.
    void set_shear_offset(double offset) {
        if (!std::isfinite(offset)) throw InputError("box: the shear offset must be finite");
        double o = std::fmod(offset, L_[0]);
        if (o >= half_[0])
            o -= L_[0];
        else if (o < -half_[0])
            o += L_[0];
        // (rounding can land on +L_x/2, the same image as -L_x/2)
        offset_ = o >= half_[0] ? -half_[0] : o;
    }
    // The offset at time t: rate L_y t (mod L_x).
    void shear_to_time(double t) { set_shear_offset(rate_ * L_[1] * t); }
    // The velocity in the laboratory frame of a particle at r with peculiar velocity v
    // (v itself without shear).
    Vec<D> lab_velocity(const Vec<D>& r, Vec<D> v) const {
        if (sheared_) v[0] += rate_ * r[1];
        return v;
    }

    // Valid for displacements within (-1.5 L, 1.5 L) on periodic axes, which is all
    // the engines ever produce (positions are kept within a fraction of L of the box);
    // under shear, for differences of positions within the box.
    Vec<D> minimum_image(Vec<D> d) const {
        if (sheared_) [[unlikely]] {
            if (d[1] > half_[1]) {
                d[1] -= L_[1];
                d[0] -= offset_;
            } else if (d[1] < -half_[1]) {
                d[1] += L_[1];
                d[0] += offset_;
            }
        }
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
    // Under shear y goes first, and its crossings shift x by -k offset.
    Vec<D> wrap(Vec<D>& r) const {
        Vec<D> shift{};
        if (sheared_) [[unlikely]] {
            shift[1] = wrap_axis(r, 1);
            r[0] -= shift[1] * offset_;
        }
        for (int a = 0; a < D; ++a) shift[a] += wrap_axis(r, a);
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
    // Wraps axis a; returns the images crossed (0 inside the box or on a wall axis).
    double wrap_axis(Vec<D>& r, int a) const {
        if (!periodic_[a] || (r[a] >= -half_[a] && r[a] < half_[a])) return 0.0;
        double k = std::floor((r[a] + half_[a]) / L_[a]);
        r[a] -= k * L_[a];
        // rounding can leave r a hair outside; both ends are the same point of the torus
        if (r[a] >= half_[a]) {
            r[a] -= L_[a];
            k += 1.0;
        }
        if (r[a] < -half_[a]) {
            r[a] += L_[a];
            k -= 1.0;
        }
        if (r[a] >= half_[a]) r[a] = -half_[a];
        return k;
    }

    Vec<D> L_{};
    Vec<D> half_{};
    std::array<bool, D> periodic_{};
    bool sheared_ = false;
    double rate_ = 0.0, offset_ = 0.0;
};

} // namespace pedesis
