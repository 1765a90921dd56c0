#pragma once
// One-body external fields for soft particles (LAMMPS' fix gravity and fix spring, SAMoS'
// gravity and traps):
//   gravity:       F_i = -w_i e_axis,   U = sum_i w_i x_i,axis
//   harmonic_trap: F_i,a = -k_a (x_i,a - c_a),   U = sum_i sum_a k_a (x_i,a - c_a)^2 / 2
// w is the weight of the particle's species (negative: buoyant). Heights are the stored
// positions, measured from the box's centre (the origin), wrapped on periodic axes: a
// gravity along a periodic axis is a constant drive, and its energy jumps where a
// particle wraps. The trap's displacement takes the nearest image of the centre on
// periodic axes. Each logs its energy (gravity_energy, trap_energy) and adds it to the
// potential energy; neither has a virial.
#include "pedesis/core/chunk_shares.hpp"
#include "pedesis/core/error.hpp"
#include "pedesis/soft/per_species.hpp"
#include "pedesis/soft/plugins.hpp"

#include <cmath>
#include <string>
#include <vector>

namespace pedesis {

template <int D> class Gravity final : public ForceTerm<D> {
  public:
    Gravity(PerSpecies weight, int axis) : weight_(std::move(weight)), axis_(axis) {
        for (double w : weight_.values())
            if (!std::isfinite(w)) throw InputError("gravity: force must be finite");
    }
    std::string name() const override { return "gravity"; }
    int axis() const { return axis_; }

    void add_forces(SoftState<D>& s, const NeighborList<D>&) const override {
        weight_.tabulate(s.p.species_table.size(), table_, [](double w) { return w; });
        const double* w = table_.data();
        const std::uint16_t* sp = s.p.species.data();
        const int a = axis_;
        const auto n = static_cast<std::int64_t>(s.owned());
        parallel_for_each_index(n, s.thread_shares,
                                [&](std::int64_t i) { s.force[i][a] -= w[sp[i]]; });
    }

    void add_totals(const SoftState<D>& s, const NeighborList<D>&, PairTotals& t) const override {
        t.energy += energy(s);
    }
    std::vector<std::string> log_columns(const SoftState<D>&) const override {
        return {"gravity_energy"};
    }
    void log_values(const SoftState<D>& s, std::vector<double>& out) const override {
        out.push_back(energy(s));
    }

  private:
    double energy(const SoftState<D>& s) const {
        weight_.tabulate(s.p.species_table.size(), table_, [](double w) { return w; });
        double u = 0.0;
        for (std::size_t i = 0; i < s.owned(); ++i)
            u += table_[s.p.species[i]] * s.p.position[i][axis_];
        return u;
    }

    PerSpecies weight_;
    int axis_;
    mutable std::vector<double> table_; // per-species weight, reused every step
};

template <int D> class HarmonicTrap final : public ForceTerm<D> {
  public:
    // Per species and the same on every axis (`k`), or one stiffness per axis for every
    // species (`k_axes`, D values; then `k` is not read).
    HarmonicTrap(PerSpecies k, std::vector<double> k_axes, Vec<D> centre)
        : k_(std::move(k)), k_axes_(std::move(k_axes)), centre_(centre) {
        for (double v : k_.values())
            if (!(v >= 0.0 && std::isfinite(v)))
                throw InputError("harmonic_trap: k must be a finite number >= 0");
        for (double v : k_axes_)
            if (!(v >= 0.0 && std::isfinite(v)))
                throw InputError("harmonic_trap: k must be a finite number >= 0");
        if (!k_axes_.empty() && k_axes_.size() != static_cast<std::size_t>(D))
            throw InputError("harmonic_trap: k gives " + std::to_string(k_axes_.size()) +
                             " numbers for a " + std::to_string(D) + "D box");
        for (int a = 0; a < D; ++a)
            if (!std::isfinite(centre_[a]))
                throw InputError("harmonic_trap: centre must be finite");
    }
    std::string name() const override { return "harmonic_trap"; }
    const Vec<D>& centre() const { return centre_; }
    // The stiffness along axis a of species s (of `count`).
    double stiffness(std::size_t s, std::size_t count, int a) const {
        return k_axes_.empty() ? k_.at(s, count) : k_axes_[static_cast<std::size_t>(a)];
    }

    void add_forces(SoftState<D>& s, const NeighborList<D>&) const override {
        tabulate(s);
        const Vec<D>* k = table_.data();
        const std::uint16_t* sp = s.p.species.data();
        const auto n = static_cast<std::int64_t>(s.owned());
        parallel_for_each_index(n, s.thread_shares, [&](std::int64_t i) {
            const Vec<D> d = offset(s, static_cast<std::size_t>(i));
            for (int a = 0; a < D; ++a) s.force[i][a] -= k[sp[i]][a] * d[a];
        });
    }

    void add_totals(const SoftState<D>& s, const NeighborList<D>&, PairTotals& t) const override {
        t.energy += energy(s);
    }
    std::vector<std::string> log_columns(const SoftState<D>&) const override {
        return {"trap_energy"};
    }
    void log_values(const SoftState<D>& s, std::vector<double>& out) const override {
        out.push_back(energy(s));
    }

  private:
    // x_i - c, to the nearest image of the centre on periodic axes (the centre may lie
    // anywhere, so not Box::minimum_image, which expects a displacement within 1.5 L)
    Vec<D> offset(const SoftState<D>& s, std::size_t i) const {
        Vec<D> d = s.p.position[i] - centre_;
        for (int a = 0; a < D; ++a)
            if (s.box.periodic(a)) {
                const double L = s.box.length(a);
                d[a] -= L * std::nearbyint(d[a] / L);
            }
        return d;
    }

    double energy(const SoftState<D>& s) const {
        tabulate(s);
        double u = 0.0;
        for (std::size_t i = 0; i < s.owned(); ++i) {
            const Vec<D> d = offset(s, i);
            for (int a = 0; a < D; ++a) u += 0.5 * table_[s.p.species[i]][a] * d[a] * d[a];
        }
        return u;
    }

    void tabulate(const SoftState<D>& s) const {
        const std::size_t ns = s.p.species_table.size();
        table_.resize(ns);
        for (std::size_t k = 0; k < ns; ++k)
            for (int a = 0; a < D; ++a) table_[k][a] = stiffness(k, ns, a);
    }

    PerSpecies k_;
    std::vector<double> k_axes_;
    Vec<D> centre_;
    mutable std::vector<Vec<D>> table_; // per species, per axis stiffness
};

} // namespace pedesis
