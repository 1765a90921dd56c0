#pragma once
// The one pair loop of the soft engine. It runs over the half neighbour list: each
// pair is evaluated once and added to both particles, in the list's colour order
// (NeighborList::for_each_chunk), so forces are bit-identical whatever the number of
// threads.
#include "pedesis/soft/plugins.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <span>

namespace pedesis {

template <int D, class Pair> class PairForce final : public ForceTerm<D> {
  public:
    PairForce(std::string name, const Pair& pair) : name_(std::move(name)), pair_(pair) {}

    std::string name() const override { return name_; }
    const Pair& pair() const { return pair_; }

    double range(const SoftState<D>& s) const override {
        double max_radius = 0.0;
        for (const auto& sp : s.p.species_table) max_radius = std::max(max_radius, sp.radius);
        return pair_.max_range(2.0 * max_radius);
    }

    void add_forces(SoftState<D>& s, const NeighborList<D>& nl) const override {
        const auto& table = s.p.species_table;
        bool uniform = true;
        for (const auto& sp : table) uniform = uniform && sp.radius == table[0].radius;
        if (uniform)
            add_rows<true>(s, nl);
        else
            add_rows<false>(s, nl);
    }

    void add_totals(const SoftState<D>& s, const NeighborList<D>& nl,
                    PairTotals& t) const override {
        for (std::size_t i = 0; i < s.size(); ++i) {
            for (const std::uint32_t* it = nl.begin(i); it != nl.end(i); ++it) {
                const Vec<D> d = s.box.minimum_image(s.p.position[i] - s.p.position[*it]);
                const double r2 = norm2(d);
                double f_over_r, energy;
                if (pair_.eval(r2, s.p.radius(i) + s.p.radius(*it), f_over_r, energy)) {
                    t.energy += energy;
                    t.virial += f_over_r * r2;
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
        double max_radius = 0.0;
        for (const auto& t : s.p.species_table) max_radius = std::max(max_radius, t.radius);
        const double rc = pair_.max_range(2.0 * max_radius);
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
                bool interior = true;
                for (int a = 0; a < D; ++a) interior = interior && std::abs(ri[a]) < inner[a];
                Vec<D> f{};
                // plain arrays: a std::array of Vec would be zeroed for every row
                double dbuf[chunk][D], r2buf[chunk], rsbuf[chunk];
                std::uint32_t jbuf[chunk];
                for (const std::uint32_t* it = nl.begin(i); it != nl.end(i);) {
                    const std::uint32_t* const stop =
                        it + std::min<std::ptrdiff_t>(chunk, nl.end(i) - it);
                    int m = 0;
                    if (interior)
                        for (; it != stop; ++it) {
                            const Vec<D> d = ri - pos[*it];
                            pack(d, *it, Uniform ? 0.0 : rad_i + table[sp[*it]].radius, rc2, dbuf,
                                 r2buf, rsbuf, jbuf, m);
                        }
                    else
                        for (; it != stop; ++it) {
                            const Vec<D> d = box.minimum_image(ri - pos[*it]);
                            pack(d, *it, Uniform ? 0.0 : rad_i + table[sp[*it]].radius, rc2, dbuf,
                                 r2buf, rsbuf, jbuf, m);
                        }
                    double frbuf[chunk];
                    if constexpr (Uniform) {
                        // Every packed pair lies within the one range: F/r for all of them in
                        // a loop without branches (several pairs per SIMD instruction).
                        const double rsum_uniform = 2.0 * rad_i;
                        for (int q = 0; q < m; ++q)
                            frbuf[q] = pair_.force_over_r(r2buf[q], rsum_uniform);
                    } else {
                        for (int q = 0; q < m; ++q) {
                            double energy;
                            if (!pair_.eval(r2buf[q], rsbuf[q], frbuf[q], energy)) frbuf[q] = 0.0;
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

    std::string name_;
    Pair pair_;
};

} // namespace pedesis
