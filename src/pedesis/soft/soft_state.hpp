#pragma once
// State of a soft / active particle system (the `brownian`, `langevin` and `nve`
// dynamics): the shared particle store plus what forces, torques and integrators need.
// Positions are kept wrapped into the box; `image` counts the periodic boxes crossed so
// that unwrapped positions (for the MSD) are r + image * L, plus image_y times the
// offset along x under Lees-Edwards shear (the sliding images: core/box.hpp).
// Velocities are peculiar under shear: relative to the streaming velocity rate * y
// along x (Frame::lab_velocity adds it back for files).
#include "pedesis/core/box.hpp"
#include "pedesis/core/frame.hpp"
#include "pedesis/core/particles.hpp"
#include "pedesis/core/precision.hpp"

#include <array>
#include <cstdint>
#include <vector>

namespace pedesis {

// A torque is a pseudo-scalar in 2D (about z) and a vector in 3D.
template <int D> using TorqueVec = Vec<D == 2 ? 1 : 3>;

template <int D> struct SoftState {
    Box<D> box;
    ParticleStore<D> p;               // position, velocity, tag, species
    std::vector<Vec<D>> director;     // unit polarity n_i
    std::vector<Vec<D>> force;        // total force of the current step
    std::vector<TorqueVec<D>> torque; // total torque of the current step
    std::vector<std::array<std::int32_t, D>> image;
    // The active velocity p_i of active Ornstein-Uhlenbeck particles (soft/active_ou.hpp):
    // empty without active_ou, and then no per-particle loop touches it.
    std::vector<Vec<D>> active_velocity;
    std::uint64_t step = 0;
    double time = 0.0;
    // Under domain decomposition (soft/domain_decomposition.hpp) the last `ghosts`
    // particles are copies of other processes' particles within interaction range: they
    // enter neighbour lists and pair sums but are not integrated. 0 on one process.
    std::size_t ghosts = 0;
    // How the per-particle loops share the particles out among threads: the storage
    // ranges on which the force loop started each thread at the last sort
    // (NeighborList::thread_share_bounds, core/chunk_shares.hpp). A hint for speed only:
    // where it no longer fits (another particle count or thread count), equal shares.
    std::vector<std::int64_t> thread_shares;
    // The pair rows' precision (core/precision.hpp): a setting of the run, not a state
    // of its particles (checkpoints do not hold it; the config does).
    Precision pair_precision = Precision::full;

    std::size_t size() const { return p.size(); }
    // The particles this process integrates: indices [0, owned()).
    std::size_t owned() const { return p.size() - ghosts; }

    void resize(std::size_t n) {
        for_each_field([n](auto& v) { v.resize(n); });
    }

    // Reorders storage so that new index i holds the particle at old index order[i]; tags
    // travel with the particles, so nothing a user sees changes.
    void apply_order(const std::vector<std::uint32_t>& order) {
        for_each_field([&](auto& v) { permute_by(v, order); });
    }

    // Calls f on every per-particle array (what travels with a particle).
    template <class F> void for_each_field(F&& f) {
        f(p.position);
        f(p.velocity);
        f(p.tag);
        f(p.species);
        f(director);
        f(force);
        f(torque);
        f(image);
        if (!active_velocity.empty()) f(active_velocity);
    }

    // Keeps the particles i with keep[i] (keep.size() <= size()), in their order, and
    // drops the rest and every ghost.
    void keep_only(const std::vector<char>& keep) {
        std::size_t w = 0;
        for (std::size_t i = 0; i < keep.size(); ++i) {
            if (!keep[i]) continue;
            if (w != i) for_each_field([&](auto& v) { v[w] = v[i]; });
            ++w;
        }
        ghosts = 0;
        resize(w);
    }

    // The view writers and observers take (valid while the state is neither resized nor
    // reordered).
    Frame<D> frame() const { return {box, p, time, step, &director, &force, &image}; }

    Vec<D> unwrapped(std::size_t i) const {
        Vec<D> r = p.position[i];
        for (int a = 0; a < D; ++a) r[a] += image[i][a] * box.length(a);
        if (box.sheared()) r[0] += image[i][1] * box.shear_offset();
        return r;
    }
};

} // namespace pedesis
