#pragma once
// The one pair loop of the soft engine. It runs over the half neighbour list: each
// pair is evaluated once and added to both particles, in the list's colour order
// (NeighborList::for_each_chunk), so forces are bit-identical whatever the number of
// threads.
//
// Parameters may differ per pair of species (epsilon_AB, sigma_AB): the force holds one
// evaluator per species pair, a symmetric table. When all entries are equal and all
// radii too (one species, the common case) the loop takes one evaluator and never reads
// a neighbour's species.
#include "pedesis/soft/pair_rows.hpp"
#include "pedesis/soft/pair_rows_mixed.hpp"
#include "pedesis/soft/plugins.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <span>
#include <stdexcept>
#include <string>
#include <vector>

namespace pedesis {

template <int D, class Pair> class PairForce final : public ForceTerm<D> {
  public:
    // The same evaluator for every pair of species.
    PairForce(std::string name, const Pair& pair)
        : name_(std::move(name)), pairs_{pair}, species_(1) {}
    // One evaluator per pair of `species` species: pairs[a * species + b], symmetric.
    PairForce(std::string name, std::vector<Pair> pairs, std::size_t species)
        : name_(std::move(name)), pairs_(std::move(pairs)), species_(species) {
        if (pairs_.size() != species_ * species_ || species_ == 0)
            throw std::invalid_argument("PairForce: the table must have species^2 entries");
        for (std::size_t a = 0; a < species_; ++a)
            for (std::size_t b = 0; b < a; ++b)
                if (!(pairs_[a * species_ + b] == pairs_[b * species_ + a]))
                    throw std::invalid_argument("PairForce: the table must be symmetric");
    }

    std::string name() const override { return name_; }
    const Pair& pair(std::size_t a = 0, std::size_t b = 0) const { return pairs_[index(a, b)]; }

    double range(const SoftState<D>& s) const override {
        double max_radius = 0.0;
        for (const auto& sp : s.p.species_table) max_radius = std::max(max_radius, sp.radius);
        double r = 0.0;
        for (const Pair& p : pairs_) r = std::max(r, p.max_range(2.0 * max_radius));
        return r;
    }

    double core(const SoftState<D>& s, std::size_t a, std::size_t b) const override {
        const auto& table = s.p.species_table;
        return pair(a, b).core(table[a].radius + table[b].radius);
    }

    void add_forces(SoftState<D>& s, const NeighborList<D>& nl) const override {
        check_species(s.p.species_table.size());
        if (uniform(s))
            add_rows<true>(s, nl);
        else
            add_rows<false>(s, nl);
    }

    // Mixed where asked and where there are mixed rows: one radius and one evaluator,
    // with the AVX2 or AVX-512 set.
    std::optional<Precision> rows_precision(const SoftState<D>& s) const override {
        const bool mixed = s.pair_precision == Precision::mixed && uniform(s) &&
                           mixed_pair_rows_for<D, Pair>(simd_level()) != nullptr;
        return mixed ? Precision::mixed : Precision::full;
    }

    // Sum over species pairs of N_a N_b / (2 V) times the pair's integrals beyond its
    // cutoff, for the evaluators that have them (LjPair with tail).
    PairTotals tail(const std::vector<Species>& table, const std::vector<double>& counts,
                    double volume) const override {
        PairTotals t;
        if constexpr (requires(const Pair& p) { p.template tail_integrals<D>(1.0); }) {
            check_species(table.size());
            for (std::size_t a = 0; a < table.size(); ++a)
                for (std::size_t b = 0; b < table.size(); ++b) {
                    const auto [energy, virial] =
                        pair(a, b).template tail_integrals<D>(table[a].radius + table[b].radius);
                    const double weight = 0.5 * counts[a] * counts[b] / volume;
                    t.energy += weight * energy;
                    t.virial += weight * virial;
                }
            // a homogeneous fluid's share: isotropic
            for (int a = 0; a < D; ++a) t.virial_tensor[a] = t.virial / D;
        }
        return t;
    }

    void add_totals(const SoftState<D>& s, const NeighborList<D>& nl,
                    PairTotals& t) const override {
        check_species(s.p.species_table.size());
        // Under domain decomposition a pair counts for its owned particles: whole between
        // two, half with a ghost (the other half is its owner's), not at all between two
        // ghosts. On one process every weight is exactly 1.
        const std::size_t owned = s.owned();
        for (std::size_t i = 0; i < s.size(); ++i) {
            for (const std::uint32_t* it = nl.begin(i); it != nl.end(i); ++it) {
                const double weight = 0.5 * static_cast<double>((i < owned) + (*it < owned));
                if (weight == 0.0) continue;
                const Vec<D> d = s.box.minimum_image(s.p.position[i] - s.p.position[*it]);
                const double r2 = norm2(d);
                double f_over_r, energy;
                const Pair& pair = pairs_[index(s.p.species[i], s.p.species[*it])];
                if (pair.eval(r2, s.p.radius(i) + s.p.radius(*it), f_over_r, energy)) {
                    t.energy += weight * energy;
                    t.virial += weight * (f_over_r * r2);
                    add_sym_outer<D>(t.virial_tensor, d, d, weight * f_over_r);
                }
            }
        }
    }

    bool add_heat_flux(const SoftState<D>& s, const NeighborList<D>& nl,
                       std::vector<double>& energy, Vec<D>& flux,
                       SymTensor& virial_tensor) const override {
        check_species(s.p.species_table.size());
        for (std::size_t i = 0; i < s.size(); ++i) {
            for (const std::uint32_t* it = nl.begin(i); it != nl.end(i); ++it) {
                const std::uint32_t j = *it;
                const Vec<D> d = s.box.minimum_image(s.p.position[i] - s.p.position[j]);
                double f_over_r, u;
                const Pair& pair = pairs_[index(s.p.species[i], s.p.species[j])];
                if (!pair.eval(norm2(d), s.p.radius(i) + s.p.radius(j), f_over_r, u)) continue;
                energy[i] += 0.5 * u;
                energy[j] += 0.5 * u;
                flux += d * (0.5 * f_over_r * dot(d, s.p.velocity[i] + s.p.velocity[j]));
                add_sym_outer<D>(virial_tensor, d, d, f_over_r);
            }
        }
        return true;
    }

  private:
    template <bool Uniform> void add_rows(SoftState<D>& s, const NeighborList<D>& nl) const {
        const double rc = range(s);
        PairRowsInput<D, Pair> in{s.p.position.data(),
                                  s.p.species.data(),
                                  s.p.species_table.data(),
                                  pairs_.data(),
                                  species_,
                                  rc * rc,
                                  s.force.data(),
                                  &s.box,
                                  &nl,
                                  {}};
        for (int a = 0; a < D; ++a)
            in.inner[a] = s.box.periodic(a) ? s.box.hi(a) - nl.image_free_margin()
                                            : std::numeric_limits<double>::infinity();
        const SimdLevel level = simd_level();
        if constexpr (Uniform)
            if (s.pair_precision == Precision::mixed)
                if (const auto mixed = mixed_pair_rows_for<D, Pair>(level)) {
                    const MixedRowsInput<D, Pair> m = pad_mixed(s, in);
                    nl.for_each_chunk([&](std::span<const std::uint32_t> c) { mixed(m, c); });
                    add_mixed(s);
                    return;
                }
        const auto rows = pair_rows_for<D, Pair, Uniform>(level);
        const bool padded = padded_rows<D> && Uniform && level != SimdLevel::sse2;
        if (padded) pad(s, in);
        nl.for_each_chunk([&](std::span<const std::uint32_t> chunk) { rows(in, chunk); });
        if (padded) unpad(s);
    }

    // The padded copies the 3D SIMD rows work on (pair_rows.hpp, Padded3): the forces
    // start from the state's and go back to it, so each component receives the same
    // additions in the same order as without them. (64 bytes per particle, kept; on a 3D
    // WCA step the two passes cost about 4%, the rows take about 9% less time.)
    void pad(const SoftState<D>& s, PairRowsInput<D, Pair>& in) const {
        const auto n = static_cast<std::int64_t>(s.size());
        position4_.resize(s.size());
        force4_.resize(s.size());
#pragma omp parallel for schedule(static)
        for (std::int64_t i = 0; i < n; ++i)
            for (int a = 0; a < 4; ++a) {
                position4_[i].c[a] = a < D ? s.p.position[i][a] : 0.0;
                force4_[i].c[a] = a < D ? s.force[i][a] : 0.0;
            }
        in.position4 = position4_.data();
        in.force4 = force4_.data();
    }
    void unpad(SoftState<D>& s) const {
        const auto n = static_cast<std::int64_t>(s.size());
#pragma omp parallel for schedule(static)
        for (std::int64_t i = 0; i < n; ++i)
            for (int a = 0; a < D; ++a) s.force[i][a] = force4_[i].c[a];
    }

    // The float copies the mixed rows work on: positions, and forces from zero, which
    // add_mixed then adds to the state's (so that the rows' sums stay in their order).
    MixedRowsInput<D, Pair> pad_mixed(const SoftState<D>& s,
                                      const PairRowsInput<D, Pair>& in) const {
        const auto n = static_cast<std::int64_t>(s.size());
        position4f_.resize(s.size());
        force4f_.resize(s.size());
#pragma omp parallel for schedule(static)
        for (std::int64_t i = 0; i < n; ++i)
            for (int a = 0; a < 4; ++a) {
                position4f_[i].c[a] = a < D ? static_cast<float>(s.p.position[i][a]) : 0.0f;
                force4f_[i].c[a] = 0.0f;
            }
        return {&in, position4f_.data(), force4f_.data()};
    }
    void add_mixed(SoftState<D>& s) const {
        const auto n = static_cast<std::int64_t>(s.size());
#pragma omp parallel for schedule(static)
        for (std::int64_t i = 0; i < n; ++i)
            for (int a = 0; a < D; ++a) s.force[i][a] += static_cast<double>(force4f_[i].c[a]);
    }

    bool uniform(const SoftState<D>& s) const {
        const auto& table = s.p.species_table;
        bool same = true;
        for (const auto& sp : table) same = same && sp.radius == table[0].radius;
        for (const Pair& p : pairs_) same = same && p == pairs_[0];
        return same;
    }

    std::size_t index(std::size_t a, std::size_t b) const {
        return species_ == 1 ? 0 : a * species_ + b;
    }
    void check_species(std::size_t n) const {
        if (species_ != 1 && species_ != n)
            throw std::logic_error("PairForce: a table for " + std::to_string(species_) +
                                   " species used with " + std::to_string(n));
    }

    std::string name_;
    std::vector<Pair> pairs_;
    std::size_t species_;
    // scratch for pad(): kept between evaluations so that a step allocates nothing
    mutable std::vector<Padded3> position4_, force4_;
    mutable std::vector<Padded3f> position4f_, force4f_;
};

} // namespace pedesis
