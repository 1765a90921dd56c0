#pragma once
// A constant active torque (chiral active particles, HOOMD-blue's active_torque): every
// particle of species s feels the torque c_s e, with e the z axis (2D: the torque is the
// number c_s; 3D: about the lab frame's z axis) or, in 3D, one lab-frame vector for all
// species. With brownian_rotation of friction gamma the director turns at the angular
// velocity omega = c_s e / gamma (3D: precesses about e), the circle swimmers of van
// Teeffelen & Loewen (2008) in 2D.
#include "pedesis/core/chunk_shares.hpp"
#include "pedesis/core/error.hpp"
#include "pedesis/soft/per_species.hpp"
#include "pedesis/soft/plugins.hpp"

#include <cmath>
#include <vector>

namespace pedesis {

template <int D> class ActiveTorque final : public TorqueTerm<D> {
  public:
    // magnitude c_s per species about z, or about `axis` (3D: a lab-frame vector for every
    // species is that axis with c = 1)
    explicit ActiveTorque(PerSpecies magnitude, TorqueVec<D> axis = z_axis())
        : magnitude_(std::move(magnitude)), axis_(axis) {
        for (double c : magnitude_.values())
            if (!std::isfinite(c)) throw InputError("active_torque: torque must be finite");
        for (int a = 0; a < components; ++a)
            if (!std::isfinite(axis_[a])) throw InputError("active_torque: torque must be finite");
    }
    std::string name() const override { return "active_torque"; }

    // The torque on species s of `count`.
    TorqueVec<D> torque(std::size_t s, std::size_t count) const {
        return magnitude_.at(s, count) * axis_;
    }

    void add_torques(SoftState<D>& s, const NeighborList<D>&) const override {
        const std::size_t ns = s.p.species_table.size();
        table_.resize(ns);
        for (std::size_t k = 0; k < ns; ++k) table_[k] = torque(k, ns);
        const TorqueVec<D>* c = table_.data();
        const std::uint16_t* sp = s.p.species.data();
        TorqueVec<D>* torque = s.torque.data();
        parallel_for_each_index(static_cast<std::int64_t>(s.owned()), s.thread_shares,
                                [&](std::int64_t i) { torque[i] += c[sp[i]]; });
    }

    static TorqueVec<D> z_axis() {
        TorqueVec<D> e{};
        e[components - 1] = 1.0;
        return e;
    }

  private:
    static constexpr int components = D == 2 ? 1 : 3;
    PerSpecies magnitude_;
    TorqueVec<D> axis_;
    mutable std::vector<TorqueVec<D>> table_; // per species, reused every step
};

} // namespace pedesis
