#pragma once
// Structure-of-arrays particle store. The storage index of a particle may change
// (engines sort for locality); its tag never does, and outputs are in tag order.
#include "pedesis/core/species.hpp"
#include "pedesis/core/vec.hpp"

#include <cstdint>
#include <vector>

namespace pedesis {

// Reorders v so that new index i holds what was at order[i] (order a permutation).
template <class T> void permute_by(std::vector<T>& v, const std::vector<std::uint32_t>& order) {
    const std::vector<T> old = v;
    for (std::size_t i = 0; i < order.size(); ++i) v[i] = old[order[i]];
}

template <int D> struct ParticleStore {
    std::vector<Vec<D>> position;
    std::vector<Vec<D>> velocity;
    std::vector<std::uint32_t> tag;
    std::vector<std::uint16_t> species;
    std::vector<Species> species_table;

    std::size_t size() const { return position.size(); }

    void resize(std::size_t n) {
        position.resize(n);
        velocity.resize(n);
        tag.resize(n);
        species.resize(n);
    }

    double radius(std::size_t i) const { return species_table[species[i]].radius; }
    double mass(std::size_t i) const { return species_table[species[i]].mass; }

    // New storage index i holds the particle that was at order[i].
    void apply_order(const std::vector<std::uint32_t>& order) {
        permute_by(position, order);
        permute_by(velocity, order);
        permute_by(tag, order);
        permute_by(species, order);
    }

    // storage index of each tag
    std::vector<std::uint32_t> index_of_tags() const {
        std::vector<std::uint32_t> idx(size());
        for (std::size_t i = 0; i < size(); ++i) idx[tag[i]] = static_cast<std::uint32_t>(i);
        return idx;
    }
};

} // namespace pedesis
