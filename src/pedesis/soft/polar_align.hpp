#pragma once
// Polar alignment of the ABP tutorial: tau_i = J sum_j n_i x n_j over neighbours closer
// than a; in 2D that is J sum_j sin(theta_j - theta_i), turning n_i towards n_j.
#include "pedesis/soft/plugins.hpp"

#include <array>
#include <bit>
#include <cmath>
#include <limits>
#include <span>

namespace pedesis {

template <int D> inline TorqueVec<D> cross(const Vec<D>& a, const Vec<D>& b) {
    if constexpr (D == 2)
        return TorqueVec<D>{{a[0] * b[1] - a[1] * b[0]}};
    else
        return TorqueVec<D>{
            {a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]}};
}

template <int D> class PolarAlign final : public TorqueTerm<D> {
  public:
    PolarAlign(double J, double a) : J_(J), a_(a) {}
    std::string name() const override { return "polar_align"; }
    double range(const SoftState<D>&) const override { return a_; }
    double coupling() const { return J_; }
    void set_coupling(double J) {
        if (!std::isfinite(J)) throw InputError("polar_align: J must be finite");
        J_ = J;
    }

    // Over the half list: n_i x n_j to i and n_j x n_i = -(n_i x n_j) to j, in the list's
    // colour order (bit-identical for any thread count).
    void add_torques(SoftState<D>& s, const NeighborList<D>& nl) const override {
        const double a2 = a_ * a_;
        const Vec<D>* pos = s.p.position.data();
        const Vec<D>* dir = s.director.data();
        TorqueVec<D>* torque = s.torque.data();
        const Box<D>& box = s.box;
        // As in the pair loop: rows of particles this far from every periodic face need
        // no minimum image.
        std::array<double, D> inner;
        for (int a = 0; a < D; ++a)
            inner[a] = box.periodic(a) ? box.hi(a) - nl.image_free_margin()
                                       : std::numeric_limits<double>::infinity();
        const double J = J_;
        nl.for_each_chunk([&](std::span<const std::uint32_t> rows) {
            for (const std::uint32_t i : rows) {
                const Vec<D> ri = pos[i];
                const Vec<D> ni = dir[i];
                bool interior = true;
                for (int a = 0; a < D; ++a) interior = interior && std::abs(ri[a]) < inner[a];
                // The torque on i is linear in n_j: n_i x (sum of the n_j in range), one cross
                // product per row. Whether a neighbour is in range is a coin toss the branch
                // predictor loses, so the neighbour's share is masked rather than branched
                // on (the compiler turns a multiplication by 0 or 1 back into a branch).
                Vec<D> sum{};
                for (const std::uint32_t* it = nl.begin(i); it != nl.end(i); ++it) {
                    const Vec<D> d = interior ? ri - pos[*it] : box.minimum_image(ri - pos[*it]);
                    const bool in = detail::squared_length(d) <= a2;
                    add_masked(sum, dir[*it], in);
                    const TorqueVec<D> tj = J * cross(dir[*it], ni);
                    add_masked(torque[*it], tj, in);
                }
                torque[i] += J * cross(ni, sum);
            }
        });
    }

  private:
    // sum += v if in, else sum += +0 (which leaves every sum but -0 unchanged)
    template <int K> static void add_masked(Vec<K>& sum, const Vec<K>& v, bool in) {
        const std::uint64_t mask = 0 - static_cast<std::uint64_t>(in);
        for (int a = 0; a < K; ++a)
            sum[a] += std::bit_cast<double>(std::bit_cast<std::uint64_t>(v[a]) & mask);
    }

    double J_, a_;
};

} // namespace pedesis
