#pragma once
// Run-and-tumble (Berg's E. coli; LAMMPS' fix tumble): in each step of length dt a
// particle of species s tumbles with probability 1 - exp(-lambda_s dt), the chance of at
// least one event of a Poisson process of rate lambda_s, and a tumble replaces its
// director by one drawn uniformly on the circle (sphere). Between tumbles the director
// keeps its direction, or diffuses if brownian_rotation turns it too. Then <n(t).n(0)> =
// exp(-lambda t) (times exp(-(d-1) D_r t) with rotational diffusion). The draws of
// particle i at step s come from Philox keyed by (seed, tumble, tag, s): the trajectory
// does not depend on thread count or storage order.
#include "pedesis/core/chunk_shares.hpp"
#include "pedesis/core/error.hpp"
#include "pedesis/core/rng.hpp"
#include "pedesis/soft/per_species.hpp"
#include "pedesis/soft/plugins.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <vector>

namespace pedesis {

template <int D> class RunAndTumble final : public Integrator<D> {
  public:
    RunAndTumble(PerSpecies rate, std::uint64_t seed) : rate_(std::move(rate)), seed_(seed) {
        for (double r : rate_.values())
            if (!(r >= 0.0 && std::isfinite(r)))
                throw InputError("run_and_tumble: rate must be a finite number >= 0");
    }
    std::string name() const override { return "run_and_tumble"; }
    const PerSpecies& rate() const { return rate_; }
    std::uint64_t seed() const { return seed_; }

    void poststep(SoftState<D>& s, double dt, double) override {
        rate_.tabulate(s.p.species_table.size(), chance_,
                       [dt](double rate) { return -std::expm1(-rate * dt); });
        const double* chance = chance_.data();
        const std::uint16_t* sp = s.p.species.data();
        const std::uint32_t* tag = s.p.tag.data();
        Vec<D>* director = s.director.data();
        const auto step = static_cast<std::uint32_t>(s.step);
        const std::uint64_t seed = seed_;
        parallel_for_each_index(static_cast<std::int64_t>(s.owned()), s.thread_shares,
                                [&](std::int64_t i) {
                                    CounterRng rng(seed, RngStream::tumble, tag[i], step);
                                    // (uniform() lies in (0, 1]: a rate of 0 never tumbles)
                                    if (rng.uniform() <= chance[sp[i]])
                                        director[i] = uniform_direction(rng);
                                });
    }

  private:
    static Vec<D> uniform_direction(CounterRng& rng) {
        const double phi = 2.0 * std::numbers::pi * rng.uniform();
        if constexpr (D == 2) {
            return Vec<D>{{std::cos(phi), std::sin(phi)}};
        } else {
            // Archimedes: z uniform on [-1, 1] is uniform on the sphere
            const double z = rng.uniform(-1.0, 1.0);
            const double r = std::sqrt(std::max(0.0, 1.0 - z * z));
            return Vec<D>{{r * std::cos(phi), r * std::sin(phi), z}};
        }
    }

    PerSpecies rate_;
    std::uint64_t seed_;
    std::vector<double> chance_; // per species, reused every step
};

} // namespace pedesis
