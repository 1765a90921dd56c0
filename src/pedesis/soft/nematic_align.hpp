#pragma once
// Nematic alignment: tau_i = J sum_j (n_i . n_j) n_i x n_j over neighbours closer than a;
// in 2D (J/2) sum_j sin 2(theta_j - theta_i). It turns n_i towards n_j or towards -n_j,
// whichever is nearer, so that heads and tails are alike (LAMMPS' fix align/neighbor
// nematic, SAMoS' nematic alignment); for small angles it is polar_align's J (theta_j -
// theta_i).
#include "pedesis/soft/alignment_loop.hpp"

namespace pedesis {

template <int D> class NematicAlign final : public AlignmentTerm<D> {
  public:
    using AlignmentTerm<D>::AlignmentTerm;
    std::string name() const override { return "nematic_align"; }

    // (n_i . n_j) n_i x n_j = n_i x (n_j n_j^T) n_i: the row sums the tensors n_j n_j^T
    // of its neighbours (their upper triangles), and j gets (n_j . n_i) n_j x n_i.
    void add_torques(SoftState<D>& s, const NeighborList<D>& nl) const override {
        add_alignment_torques(s, nl, this->a_, Rule{s.director.data(), this->J_});
    }

  private:
    static constexpr int K = D * (D + 1) / 2; // xx, xy, yy (xz, yz, zz in 3D: see dyad)
    static Vec<K> dyad(const Vec<D>& n) {
        if constexpr (D == 2)
            return Vec<K>{{n[0] * n[0], n[0] * n[1], n[1] * n[1]}};
        else
            return Vec<K>{
                {n[0] * n[0], n[0] * n[1], n[0] * n[2], n[1] * n[1], n[1] * n[2], n[2] * n[2]}};
    }
    static Vec<D> times(const Vec<K>& q, const Vec<D>& n) {
        if constexpr (D == 2)
            return Vec<D>{{q[0] * n[0] + q[1] * n[1], q[1] * n[0] + q[2] * n[1]}};
        else
            return Vec<D>{{q[0] * n[0] + q[1] * n[1] + q[2] * n[2],
                           q[1] * n[0] + q[3] * n[1] + q[4] * n[2],
                           q[2] * n[0] + q[4] * n[1] + q[5] * n[2]}};
    }

    struct Rule {
        using Sum = Vec<K>;
        const Vec<D>* dir;
        double J;
        struct Row {
            const Vec<D>* dir;
            double J;
            Vec<D> ni;
            Vec<K> share(std::uint32_t j) const { return dyad(dir[j]); }
            TorqueVec<D> on_neighbour(std::uint32_t j) const {
                return (J * dot(dir[j], ni)) * cross(dir[j], ni);
            }
            TorqueVec<D> on_row(const Vec<K>& q) const { return J * cross(ni, times(q, ni)); }
        };
        Row row(std::uint32_t i) const { return {dir, J, dir[i]}; }
    };
};

} // namespace pedesis
