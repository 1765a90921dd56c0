#pragma once
// The one pair loop of the soft engine. It runs over a full neighbour list in parallel
// over particles: each particle sums its own neighbours in list order, so forces are
// bit-identical whatever the number of threads.
#include "pedesis/soft/plugins.hpp"

#include <algorithm>

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
        const auto n = static_cast<std::int64_t>(s.size());
        const Vec<D>* pos = s.p.position.data();
        const std::uint16_t* sp = s.p.species.data();
        const Species* table = s.p.species_table.data();
        Vec<D>* force = s.force.data();
        const Box<D>& box = s.box;
#pragma omp parallel for schedule(static)
        for (std::int64_t ii = 0; ii < n; ++ii) {
            const auto i = static_cast<std::size_t>(ii);
            const Vec<D> ri = pos[i];
            const double rad_i = table[sp[i]].radius;
            Vec<D> f{};
            for (const std::uint32_t* it = nl.begin(i); it != nl.end(i); ++it) {
                const Vec<D> d = box.minimum_image(ri - pos[*it]);
                double f_over_r, energy;
                if (pair_.eval(norm2(d), rad_i + table[sp[*it]].radius, f_over_r, energy))
                    f += f_over_r * d;
            }
            force[i] += f;
        }
    }

    void add_totals(const SoftState<D>& s, const NeighborList<D>& nl,
                    PairTotals& t) const override {
        for (std::size_t i = 0; i < s.size(); ++i) {
            for (const std::uint32_t* it = nl.begin(i); it != nl.end(i); ++it) {
                if (*it <= i) continue; // each pair once
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
    std::string name_;
    Pair pair_;
};

} // namespace pedesis
