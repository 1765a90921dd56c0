#pragma once
// Velocity Verlet for Newtonian dynamics (the `nve` engine):
//   pre-step:  v += (dt/2) F/m,  r += dt v
//   post-step: v += (dt/2) F/m   (F of the new positions)
// It is symplectic and time-reversible, so the energy error stays bounded, O(dt^2), over
// long runs instead of drifting. The pre-step reads the forces of the current positions,
// hence needs_initial_forces(). A particle of infinite mass is a fixed obstacle.
//
// Under Lees-Edwards shear at rate g (core/box.hpp) the velocities are peculiar and the
// equations SLLOD's: dr/dt = v + g y e_x, dv/dt = F/m - g v_y e_x. The same splitting
// with each part's exact flow (detail::sllod_kick, sllod_drift in langevin.hpp).
#include "pedesis/core/chunk_shares.hpp"
#include "pedesis/soft/blow_up.hpp"
#include "pedesis/soft/plugins.hpp"
#include "pedesis/soft/sllod.hpp"

#include <cmath>
#include <cstdint>
#include <limits>
#include <string>
#include <utility>
#include <vector>

namespace pedesis {

template <int D> class VelocityVerletIntegrator final : public Integrator<D> {
  public:
    // (a thermostat that steps with it gives its own name, for the messages)
    explicit VelocityVerletIntegrator(std::string name = "nve") : name_(std::move(name)) {}
    std::string name() const override { return name_; }
    bool needs_initial_forces() const override { return true; }

    void prestep(SoftState<D>& s, double dt, double max_move) override {
        tabulate(s, dt);
        if (s.box.sheared()) {
            detail::sllod_kick_drift(s, kick_, drift_, dt, max_move, name());
            return;
        }
        const double* kick = kick_.data();
        const double* drift = drift_.data();
        const std::uint16_t* sp = s.p.species.data();
        const Vec<D>* force = s.force.data();
        Vec<D>* pos = s.p.position.data();
        Vec<D>* vel = s.p.velocity.data();
        const auto n = static_cast<std::int64_t>(s.owned());
        const double max2 = max_move * max_move;
        std::int64_t bad = std::numeric_limits<std::int64_t>::max();
        ChunkShares shares(n, light_items_per_chunk, 1, s.thread_shares);
#pragma omp parallel reduction(min : bad)
        shares.run([&](std::int64_t first, std::int64_t last) {
            for (std::int64_t i = first; i < last; ++i) {
                vel[i] += kick[sp[i]] * force[i];
                const Vec<D> move = drift[sp[i]] * vel[i];
                if (!(norm2(move) <= max2)) bad = std::min(bad, i);
                pos[i] += move;
            }
        });
        if (bad != std::numeric_limits<std::int64_t>::max()) {
            const auto i = static_cast<std::size_t>(bad);
            detail::throw_bad_move(s, i, drift_[sp[i]] * vel[i], max_move, name());
        }
    }

    void poststep(SoftState<D>& s, double dt, double) override {
        tabulate(s, dt); // one entry per species: cheap, and no pre-step state is relied on
        const double* kick = kick_.data();
        const std::uint16_t* sp = s.p.species.data();
        const Vec<D>* force = s.force.data();
        Vec<D>* vel = s.p.velocity.data();
        const auto n = static_cast<std::int64_t>(s.owned());
        if (s.box.sheared()) {
            detail::sllod_kick(s, kick_, dt);
            return;
        }
        parallel_for_each_index(n, s.thread_shares,
                                [&](std::int64_t i) { vel[i] += kick[sp[i]] * force[i]; });
    }

    // Per species: half kick dt/(2m), and drift dt, zero for an infinite mass so that an
    // obstacle stays put even if it was given a velocity.
    static void tabulate(const std::vector<Species>& table, double dt, std::vector<double>& kick,
                         std::vector<double>& drift) {
        kick.resize(table.size());
        drift.resize(table.size());
        for (std::size_t k = 0; k < table.size(); ++k) {
            kick[k] = 0.5 * dt * table[k].inverse_mass();
            drift[k] = std::isinf(table[k].mass) ? 0.0 : dt;
        }
    }

  private:
    void tabulate(const SoftState<D>& s, double dt) {
        tabulate(s.p.species_table, dt, kick_, drift_);
    }

    std::string name_;
    std::vector<double> kick_, drift_;
};

} // namespace pedesis
