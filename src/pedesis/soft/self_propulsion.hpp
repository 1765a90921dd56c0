#pragma once
// Self-propulsion of the ABP tutorial: F_i = alpha n_i along the particle's polarity.
#include "pedesis/core/chunk_shares.hpp"
#include "pedesis/soft/active_virial.hpp"
#include "pedesis/soft/per_species.hpp"
#include "pedesis/soft/plugins.hpp"

namespace pedesis {

// Swim pressure of self-propulsion, F_i = alpha_i n_i (soft/active_virial.hpp). In steady
// state for free ABPs it tends to n alpha^2 / (gamma d (d-1) D_r) (Takatori, Yan & Brady
// 2014). alpha[s] is the active force of species s.
template <int D>
double active_pressure(const SoftState<D>& s, const std::vector<Vec<D>>& start,
                       const std::vector<double>& alpha) {
    return active_virial(s, start, [&](std::size_t i, const Vec<D>& d) {
        return alpha[s.p.species[i]] * dot(s.director[i], d);
    });
}

template <int D> class SelfPropulsion final : public ForceTerm<D> {
  public:
    explicit SelfPropulsion(PerSpecies alpha) : alpha_(std::move(alpha)) {}
    std::string name() const override { return "self_propulsion"; }
    const PerSpecies& alpha() const { return alpha_; }
    void set_alpha(PerSpecies alpha) {
        for (double a : alpha.values())
            if (!std::isfinite(a)) throw InputError("self_propulsion: alpha must be finite");
        alpha_ = std::move(alpha);
    }

    double swim_pressure(const SoftState<D>& s, const std::vector<Vec<D>>& start) const override {
        alpha_.tabulate(s.p.species_table.size(), table_, [](double a) { return a; });
        return active_pressure(s, start, table_);
    }

    double swim_force(std::size_t s, std::size_t count) const override {
        return alpha_.at(s, count);
    }

    void add_forces(SoftState<D>& s, const NeighborList<D>&) const override {
        alpha_.tabulate(s.p.species_table.size(), table_, [](double a) { return a; });
        const double* alpha = table_.data();
        const std::uint16_t* sp = s.p.species.data();
        const auto n = static_cast<std::int64_t>(s.owned());
        parallel_for_each_index(n, s.thread_shares, [&](std::int64_t i) {
            s.force[i] += alpha[sp[i]] * s.director[i];
        });
    }

  private:
    PerSpecies alpha_;
    mutable std::vector<double> table_; // per-species alpha, reused every step
};

} // namespace pedesis
