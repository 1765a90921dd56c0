#pragma once
// The neighbour loop of the alignment torques (polar_align.hpp, nematic_align.hpp,
// velocity_align.hpp): over the half list, each pair i-j closer than a adds its share to
// the torques on i and on j, in the list's colour order, so that the torques are
// bit-identical for any thread count. A rule's row(i) says what the pairs of row i
// contribute (it holds what it needs of i, read once a row):
//   Sum share(j)                  what j adds to i's sum over its neighbours;
//   TorqueVec<D> on_neighbour(j)  the torque on j from i;
//   TorqueVec<D> on_row(sum)      the torque on i from that sum.
// The torque on i is then linear in its neighbours' shares: one product per row, however
// many neighbours.
#include "pedesis/core/error.hpp"
#include "pedesis/soft/plugins.hpp"

#include <array>
#include <bit>
#include <cmath>
#include <cstdint>
#include <limits>
#include <span>
#include <string>

namespace pedesis {

template <int D> inline TorqueVec<D> cross(const Vec<D>& a, const Vec<D>& b) {
    if constexpr (D == 2)
        return TorqueVec<D>{{a[0] * b[1] - a[1] * b[0]}};
    else
        return TorqueVec<D>{
            {a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]}};
}

namespace detail {

// sum += v if in, else sum += +0 (which leaves every sum but -0 unchanged). Whether a
// neighbour is in range is a coin toss the branch predictor loses, so its share is masked
// rather than branched on (the compiler turns a multiplication by 0 or 1 back into a
// branch).
template <int K> inline void add_masked(Vec<K>& sum, const Vec<K>& v, bool in) {
    const std::uint64_t mask = 0 - static_cast<std::uint64_t>(in);
    for (int a = 0; a < K; ++a)
        sum[a] += std::bit_cast<double>(std::bit_cast<std::uint64_t>(v[a]) & mask);
}

} // namespace detail

template <int D, class Rule>
void add_alignment_torques(SoftState<D>& s, const NeighborList<D>& nl, double range,
                           const Rule& rule) {
    const double a2 = range * range;
    const Vec<D>* pos = s.p.position.data();
    TorqueVec<D>* torque = s.torque.data();
    const Box<D>& box = s.box;
    // As in the pair loop: rows of particles this far from every periodic face need no
    // minimum image.
    std::array<double, D> inner;
    for (int a = 0; a < D; ++a)
        inner[a] = box.periodic(a) ? box.hi(a) - nl.image_free_margin()
                                   : std::numeric_limits<double>::infinity();
    nl.for_each_chunk([&](std::span<const std::uint32_t> rows) {
        for (const std::uint32_t i : rows) {
            const Vec<D> ri = pos[i];
            bool interior = true;
            for (int a = 0; a < D; ++a) interior = interior && std::abs(ri[a]) < inner[a];
            const auto row = rule.row(i);
            typename Rule::Sum sum{};
            for (const std::uint32_t* it = nl.begin(i); it != nl.end(i); ++it) {
                const Vec<D> d = interior ? ri - pos[*it] : box.minimum_image(ri - pos[*it]);
                const bool in = detail::squared_length(d) <= a2;
                detail::add_masked(sum, row.share(*it), in);
                detail::add_masked(torque[*it], row.on_neighbour(*it), in);
            }
            torque[i] += row.on_row(sum);
        }
    });
}

// What the alignments share besides the loop: a strength J and a range a.
template <int D> class AlignmentTerm : public TorqueTerm<D> {
  public:
    AlignmentTerm(double J, double a) : J_(J), a_(a) {}
    double range(const SoftState<D>&) const override { return a_; }
    double coupling() const { return J_; }
    void set_coupling(double J) {
        if (!std::isfinite(J)) throw InputError(this->name() + ": J must be finite");
        J_ = J;
    }

  protected:
    double J_, a_;
};

} // namespace pedesis
