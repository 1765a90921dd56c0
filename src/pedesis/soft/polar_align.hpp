#pragma once
// Polar alignment of the ABP tutorial: tau_i = J sum_j n_i x n_j over neighbours closer
// than a; in 2D that is J sum_j sin(theta_j - theta_i), turning n_i towards n_j.
#include "pedesis/soft/alignment_loop.hpp"

namespace pedesis {

template <int D> class PolarAlign final : public AlignmentTerm<D> {
  public:
    using AlignmentTerm<D>::AlignmentTerm;
    std::string name() const override { return "polar_align"; }

    // n_i x n_j to i and n_j x n_i = -(n_i x n_j) to j; the torque on i is
    // n_i x (the sum of the n_j in range).
    void add_torques(SoftState<D>& s, const NeighborList<D>& nl) const override {
        add_alignment_torques(s, nl, this->a_, Rule{s.director.data(), this->J_});
    }

  private:
    struct Rule {
        using Sum = Vec<D>;
        const Vec<D>* dir;
        double J;
        struct Row {
            const Vec<D>* dir;
            double J;
            Vec<D> ni;
            const Vec<D>& share(std::uint32_t j) const { return dir[j]; }
            TorqueVec<D> on_neighbour(std::uint32_t j) const { return J * cross(dir[j], ni); }
            TorqueVec<D> on_row(const Vec<D>& sum) const { return J * cross(ni, sum); }
        };
        Row row(std::uint32_t i) const { return {dir, J, dir[i]}; }
    };
};

} // namespace pedesis
