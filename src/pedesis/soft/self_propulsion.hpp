#pragma once
// Self-propulsion of the ABP tutorial: F_i = alpha n_i along the particle's polarity.
#include "pedesis/soft/plugins.hpp"

namespace pedesis {

template <int D> class SelfPropulsion final : public ForceTerm<D> {
  public:
    explicit SelfPropulsion(double alpha) : alpha_(alpha) {}
    std::string name() const override { return "self_propulsion"; }
    double alpha() const { return alpha_; }

    void add_forces(SoftState<D>& s, const NeighborList<D>&) const override {
        const auto n = static_cast<std::int64_t>(s.size());
#pragma omp parallel for schedule(static)
        for (std::int64_t i = 0; i < n; ++i) s.force[i] += alpha_ * s.director[i];
    }

  private:
    double alpha_;
};

} // namespace pedesis
