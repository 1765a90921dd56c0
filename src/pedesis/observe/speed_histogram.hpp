#pragma once
// Histogram of particle speeds per species, accumulated over samples, written with
// the equilibrium curve (Rayleigh in 2D, Maxwell in 3D) at the sampled temperature.
#include "pedesis/core/particles.hpp"

#include <cstdint>
#include <iosfwd>
#include <vector>

namespace pedesis {

class SpeedHistogram {
  public:
    SpeedHistogram() = default;
    SpeedHistogram(std::size_t species, int bins) : bins_(bins), per_species_(species) {}

    template <int D> void add(const ParticleStore<D>& p);

    bool empty() const { return samples_ == 0; }
    // CSV: v_lo, v_hi, then per species density_<name> (normalised) and theory_<name>.
    void write_csv(std::ostream& out, int dim, const std::vector<std::string>& names,
                   const std::vector<double>& masses) const;

    void save(std::ostream& out) const;
    void load(std::istream& in);

  private:
    struct Bins {
        double v_max = 0.0;
        std::vector<std::uint64_t> count;
        std::uint64_t total = 0;     // including speeds beyond v_max
        double sum_v2_times_m = 0.0; // for the sampled temperature
        std::uint64_t mobile = 0;
    };
    int bins_ = 50;
    std::uint64_t samples_ = 0;
    std::vector<Bins> per_species_;
};

} // namespace pedesis
