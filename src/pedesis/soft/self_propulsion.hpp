#pragma once
// Self-propulsion of the ABP tutorial: F_i = alpha n_i along the particle's polarity.
#include "pedesis/soft/per_species.hpp"
#include "pedesis/soft/plugins.hpp"

namespace pedesis {

template <int D> class SelfPropulsion final : public ForceTerm<D> {
  public:
    explicit SelfPropulsion(PerSpecies alpha) : alpha_(std::move(alpha)) {}
    std::string name() const override { return "self_propulsion"; }
    const PerSpecies& alpha() const { return alpha_; }

    void add_forces(SoftState<D>& s, const NeighborList<D>&) const override {
        alpha_.tabulate(s.p.species_table.size(), table_, [](double a) { return a; });
        const double* alpha = table_.data();
        const std::uint16_t* sp = s.p.species.data();
        const auto n = static_cast<std::int64_t>(s.size());
#pragma omp parallel for schedule(static)
        for (std::int64_t i = 0; i < n; ++i) s.force[i] += alpha[sp[i]] * s.director[i];
    }

  private:
    PerSpecies alpha_;
    mutable std::vector<double> table_; // per-species alpha, reused every step
};

} // namespace pedesis
