#pragma once
// Polar alignment of the ABP tutorial: tau_i = J sum_j n_i x n_j over neighbours closer
// than a; in 2D that is J sum_j sin(theta_j - theta_i), turning n_i towards n_j.
#include "pedesis/soft/plugins.hpp"

#include <array>
#include <bit>
#include <cmath>
#include <limits>

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

    void add_torques(SoftState<D>& s, const NeighborList<D>& nl) const override {
        const auto n = static_cast<std::int64_t>(s.size());
        const double a2 = a_ * a_;
        const Vec<D>* pos = s.p.position.data();
        const Vec<D>* dir = s.director.data();
        const Box<D>& box = s.box;
        // As in the pair loop: rows of particles this far from every periodic face need
        // no minimum image.
        std::array<double, D> inner;
        for (int a = 0; a < D; ++a)
            inner[a] = box.periodic(a) ? box.hi(a) - nl.image_free_margin()
                                       : std::numeric_limits<double>::infinity();
#pragma omp parallel for schedule(static)
        for (std::int64_t ii = 0; ii < n; ++ii) {
            const auto i = static_cast<std::size_t>(ii);
            const Vec<D> ri = pos[i];
            bool interior = true;
            for (int a = 0; a < D; ++a) interior = interior && std::abs(ri[a]) < inner[a];
            // The torque is linear in n_j: n_i x (sum of the n_j in range), one cross
            // product per particle. The sum is masked rather than branched on: whether a
            // neighbour is in range is a coin toss the branch predictor loses (and the
            // compiler turns a multiplication by 0 or 1 back into a branch).
            Vec<D> sum{};
            if (interior)
                for (const std::uint32_t* it = nl.begin(i); it != nl.end(i); ++it)
                    add_masked(sum, dir[*it], detail::squared_length(ri - pos[*it]) <= a2);
            else
                for (const std::uint32_t* it = nl.begin(i); it != nl.end(i); ++it)
                    add_masked(sum, dir[*it],
                               detail::squared_length(box.minimum_image(ri - pos[*it])) <= a2);
            s.torque[i] += J_ * cross(s.director[i], sum);
        }
    }

  private:
    // sum += v if in, else sum += +0 (which leaves every sum but -0 unchanged)
    static void add_masked(Vec<D>& sum, const Vec<D>& v, bool in) {
        const std::uint64_t mask = 0 - static_cast<std::uint64_t>(in);
        for (int a = 0; a < D; ++a)
            sum[a] += std::bit_cast<double>(std::bit_cast<std::uint64_t>(v[a]) & mask);
    }

    double J_, a_;
};

} // namespace pedesis
