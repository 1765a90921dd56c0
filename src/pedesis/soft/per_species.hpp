#pragma once
// A parameter that may differ between species: one value for all, or one per species in
// the order of the species table. Plug-ins turn it into per-species coefficients once per
// step, so the particle loops read a small table indexed by species and never branch.
#include "pedesis/core/error.hpp"

#include <string>
#include <vector>

namespace pedesis {

class PerSpecies {
  public:
    PerSpecies(double v) : values_{v} {} // NOLINT: a plain number means "every species"
    explicit PerSpecies(std::vector<double> v) : values_(std::move(v)) {
        if (values_.empty()) throw InputError("a per-species parameter needs at least one value");
    }

    // The value for species s of a table with n species.
    double at(std::size_t s, std::size_t n) const {
        if (values_.size() == 1) return values_[0];
        if (values_.size() != n)
            throw InputError("a per-species parameter has " + std::to_string(values_.size()) +
                             " values for " + std::to_string(n) + " species");
        return values_[s];
    }
    const std::vector<double>& values() const { return values_; }
    bool uniform() const { return values_.size() == 1; }

    // out[s] = f(value of species s) for the n species; reuses out's storage.
    template <class F> void tabulate(std::size_t n, std::vector<double>& out, F&& f) const {
        out.resize(n);
        for (std::size_t s = 0; s < n; ++s) out[s] = f(at(s, n));
    }

  private:
    std::vector<double> values_;
};

} // namespace pedesis
