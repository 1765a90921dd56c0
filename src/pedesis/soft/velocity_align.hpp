#pragma once
// Velocity alignment (Vicsek-like): tau_i = J sum_j n_i x v_j / |v_j| over the neighbours
// closer than a and i itself, turning n_i towards the direction its neighbourhood moves
// in (LAMMPS' fix align/neighbor with velocities, SAMoS' velocity alignment). v_j is the
// velocity the state holds when the torques are computed: the last step's displacement
// over dt for brownian (noise included), the half-kicked velocity for langevin and nve. A
// particle at rest (v_j = 0) adds nothing.
#include "pedesis/core/chunk_shares.hpp"
#include "pedesis/soft/alignment_loop.hpp"

#include <cmath>
#include <vector>

namespace pedesis {

template <int D> class VelocityAlign final : public AlignmentTerm<D> {
  public:
    using AlignmentTerm<D>::AlignmentTerm;
    std::string name() const override { return "velocity_align"; }

    // The unit velocities first (ghosts' too: they are neighbours), once a particle
    // rather than once a pair; then the pair loop, n_i x u_j to i and n_j x u_i to j.
    void add_torques(SoftState<D>& s, const NeighborList<D>& nl) const override {
        unit_.resize(s.size());
        const Vec<D>* v = s.p.velocity.data();
        Vec<D>* u = unit_.data();
        parallel_for_each_index(static_cast<std::int64_t>(s.size()), {}, [&](std::int64_t i) {
            const double speed = norm(v[i]);
            u[i] = speed > 0.0 ? v[i] * (1.0 / speed) : Vec<D>{};
        });
        add_alignment_torques(s, nl, this->a_, Rule{s.director.data(), unit_.data(), this->J_});
    }

  private:
    struct Rule {
        using Sum = Vec<D>;
        const Vec<D>* dir;
        const Vec<D>* unit;
        double J;
        struct Row {
            const Vec<D>* dir;
            const Vec<D>* unit;
            double J;
            Vec<D> ni, ui;
            const Vec<D>& share(std::uint32_t j) const { return unit[j]; }
            TorqueVec<D> on_neighbour(std::uint32_t j) const { return J * cross(dir[j], ui); }
            // (i's own velocity among the sum's terms)
            TorqueVec<D> on_row(const Vec<D>& sum) const { return J * cross(ni, sum + ui); }
        };
        Row row(std::uint32_t i) const { return {dir, unit, J, dir[i], unit[i]}; }
    };

    mutable std::vector<Vec<D>> unit_; // v_j / |v_j|, reused every step
};

} // namespace pedesis
