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

    void add_forces(SoftState<D>& s, const NeighborList<D>& nl) const override {
        const auto& table = s.p.species_table;
        check_species(table.size());
        bool uniform = true;
        for (const auto& sp : table) uniform = uniform && sp.radius == table[0].radius;
        for (const Pair& p : pairs_) uniform = uniform && p == pairs_[0];
        if (uniform)
            add_rows<true>(s, nl);
        else
            add_rows<false>(s, nl);
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
                }
            }
        }
    }

  private:
    // Candidates are filtered in chunks: those within the pair's largest range are
    // packed (branch-free) into a buffer and only they are evaluated. A third to a half
    // of a row lies in the skin, at random, so testing each candidate with a branch
    // mispredicted often; evaluating the packed ones keeps list order, so the sums are the same
    // whatever the thread count.
    static constexpr int chunk = 32;

    // With one radius for all species (the common case) the sum of radii is a constant
    // and the rows never read the species of a neighbour.
    template <bool Uniform> void add_rows(SoftState<D>& s, const NeighborList<D>& nl) const {
        const Vec<D>* pos = s.p.position.data();
        const std::uint16_t* sp = s.p.species.data();
        const Species* table = s.p.species_table.data();
        const Pair* pairs = pairs_.data();
        const std::size_t ns = species_;
        const double rc = range(s);
        const double rc2 = rc * rc;
        Vec<D>* force = s.force.data();
        const Box<D>& box = s.box;
        // Rows of particles this far inside every periodic face need no minimum image.
        std::array<double, D> inner;
        for (int a = 0; a < D; ++a)
            inner[a] = box.periodic(a) ? box.hi(a) - nl.image_free_margin()
                                       : std::numeric_limits<double>::infinity();
        nl.for_each_chunk([&](std::span<const std::uint32_t> rows) {
            for (const std::uint32_t i : rows) {
                const Vec<D> ri = pos[i];
                const double rad_i = table[sp[i]].radius;
                const Pair* pair_row = pairs + (Uniform || ns == 1 ? 0 : sp[i] * ns);
                bool interior = true;
                for (int a = 0; a < D; ++a) interior = interior && std::abs(ri[a]) < inner[a];
                Vec<D> f{};
                // plain arrays: a std::array of Vec would be zeroed for every row
                double dbuf[chunk][D], r2buf[chunk], rsbuf[chunk];
                std::uint32_t jbuf[chunk];
                std::uint16_t sbuf[chunk]; // the neighbours' species (non-uniform path)
                for (const std::uint32_t* it = nl.begin(i); it != nl.end(i);) {
                    const std::uint32_t* const stop =
                        it + std::min<std::ptrdiff_t>(chunk, nl.end(i) - it);
                    int m = 0;
                    if (interior)
                        for (; it != stop; ++it) {
                            const Vec<D> d = ri - pos[*it];
                            if constexpr (!Uniform) sbuf[m] = sp[*it];
                            pack(d, *it, Uniform ? 0.0 : rad_i + table[sp[*it]].radius, rc2, dbuf,
                                 r2buf, rsbuf, jbuf, m);
                        }
                    else
                        for (; it != stop; ++it) {
                            const Vec<D> d = box.minimum_image(ri - pos[*it]);
                            if constexpr (!Uniform) sbuf[m] = sp[*it];
                            pack(d, *it, Uniform ? 0.0 : rad_i + table[sp[*it]].radius, rc2, dbuf,
                                 r2buf, rsbuf, jbuf, m);
                        }
                    double frbuf[chunk];
                    if constexpr (Uniform) {
                        // Every packed pair lies within the one range: F/r for all of them in
                        // a loop without branches (several pairs per SIMD instruction).
                        const double rsum_uniform = 2.0 * rad_i;
                        const Pair& pair = pairs[0];
                        for (int q = 0; q < m; ++q)
                            frbuf[q] = pair.force_over_r(r2buf[q], rsum_uniform);
                    } else {
                        for (int q = 0; q < m; ++q) {
                            double energy;
                            const Pair& pair = pair_row[ns == 1 ? 0 : sbuf[q]];
                            if (!pair.eval(r2buf[q], rsbuf[q], frbuf[q], energy)) frbuf[q] = 0.0;
                        }
                    }
                    // summed in list order; each neighbour gets the opposite force
                    for (int q = 0; q < m; ++q) {
                        Vec<D>& fj = force[jbuf[q]];
                        for (int a = 0; a < D; ++a) {
                            const double fa = frbuf[q] * dbuf[q][a];
                            f[a] += fa;
                            fj[a] -= fa;
                        }
                    }
                }
                force[i] += f;
            }
        });
    }

    static void pack(const Vec<D>& d, std::uint32_t j, double rsum, double rc2,
                     double (&dbuf)[chunk][D], double (&r2buf)[chunk], double (&rsbuf)[chunk],
                     std::uint32_t (&jbuf)[chunk], int& m) {
        const double r2 = detail::squared_length(d);
        for (int a = 0; a < D; ++a) dbuf[m][a] = d[a];
        r2buf[m] = r2;
        rsbuf[m] = rsum;
        jbuf[m] = j;
        m += r2 < rc2;
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
};

} // namespace pedesis
