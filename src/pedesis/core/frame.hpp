#pragma once
// One instant of any engine, read-only: what writers and observers take, so that no
// file format knows an engine and every engine writes every format.
//
// The per-particle fields an engine does not have are null: the hard-particle engines
// have no director or force, and only the soft engine counts periodic images. Writers
// leave an absent field out of the file, or write its neutral value where the format
// requires the field (image 0, the identity orientation).
#include "pedesis/core/box.hpp"
#include "pedesis/core/particles.hpp"

#include <array>
#include <cstdint>
#include <vector>

namespace pedesis {

template <int D> struct Frame {
    const Box<D>& box;
    const ParticleStore<D>& particles; // storage order; tags say which particle is which
    double time = 0.0;
    // Time steps so far; the event engine, which has none, gives its collisions so far.
    std::uint64_t step = 0;
    // Per particle in storage order, or null where the engine has no such field
    // (pointers, not spans: an empty system still has its fields).
    const std::vector<Vec<D>>* directors = nullptr; // unit polarity
    const std::vector<Vec<D>>* forces = nullptr;    // total force of the last step
    const std::vector<std::array<std::int32_t, D>>* images = nullptr; // periodic boxes crossed

    std::size_t size() const { return particles.size(); }
    bool has_director() const { return directors != nullptr; }
    bool has_force() const { return forces != nullptr; }
    const Vec<D>& director(std::size_t i) const { return (*directors)[i]; }
    const Vec<D>& force(std::size_t i) const { return (*forces)[i]; }
    // The velocity in the laboratory frame, what files show: under Lees-Edwards shear the
    // stored (peculiar) velocity plus the streaming velocity, else the stored one.
    Vec<D> lab_velocity(std::size_t i) const {
        return box.lab_velocity(particles.position[i], particles.velocity[i]);
    }
    std::array<std::int32_t, D> image(std::size_t i) const {
        return images ? (*images)[i] : std::array<std::int32_t, D>{};
    }
};

// The frame of hard particles: no director, force or image counts.
template <int D>
Frame<D> frame_of(const ParticleStore<D>& p, const Box<D>& box, double time,
                  std::uint64_t step = 0) {
    return Frame<D>{box, p, time, step};
}

} // namespace pedesis
