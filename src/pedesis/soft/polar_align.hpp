#pragma once
// Polar alignment of the ABP tutorial: tau_i = J sum_j n_i x n_j over neighbours closer
// than a; in 2D that is J sum_j sin(theta_j - theta_i), turning n_i towards n_j.
#include "pedesis/soft/plugins.hpp"

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
#pragma omp parallel for schedule(static)
        for (std::int64_t ii = 0; ii < n; ++ii) {
            const auto i = static_cast<std::size_t>(ii);
            const Vec<D> ri = s.p.position[i];
            const Vec<D> ni = s.director[i];
            TorqueVec<D> t{};
            for (const std::uint32_t* it = nl.begin(i); it != nl.end(i); ++it)
                if (norm2(s.box.minimum_image(ri - s.p.position[*it])) <= a2)
                    t += cross(ni, s.director[*it]);
            s.torque[i] += J_ * t;
        }
    }

  private:
    double J_, a_;
};

} // namespace pedesis
