#pragma once
// The event engine's neighbour lists, read back from its checkpoint (EventEngine::save,
// the one public view of them): the list centres, the skin and every particle's list.
// The reader follows the field order of EventEngine::save for checkpoint version 8 up to
// the lists (the image counts, flux moments and shear state come after them); a new
// version fails here with the engine's own "unsupported version" message, which means
// this reader must follow the change.
#include "pedesis/core/collision_counters.hpp"
#include "pedesis/event/event_engine.hpp"
#include "pedesis/io/binary_stream.hpp"

#include <cstdint>
#include <sstream>
#include <vector>

namespace pedesis::test {

template <int D> struct EventLists {
    std::vector<Species> species_table;
    Box<D> box;
    double skin = 0.0;
    std::vector<std::uint16_t> species;
    std::vector<Vec<D>> centre;
    std::vector<std::vector<std::uint32_t>> neighbours; // per particle, as stored
    // where in the checkpoint the first particle's event partner (an int32) lies
    std::size_t first_event_partner_offset = 0;
};

template <int D> EventLists<D> read_event_lists(const EventEngine<D>& engine) {
    using binary::get;
    std::stringstream buf;
    engine.save(buf);
    EventLists<D> out;
    binary::get_header(buf, 0x4b43455344455045ull, 8, D, "event");
    get(buf, out.species_table);
    get(buf, out.box);
    double now = 0.0, kinetic = 0.0, kinetic_exact = 0.0;
    get(buf, now);
    get(buf, out.skin);
    get(buf, kinetic);
    get(buf, kinetic_exact);
    std::uint64_t stalled = 0;
    get(buf, stalled);
    EventCounters<D> counters;
    get(buf, counters);
    double growth_rate = 0.0, radius_time = 0.0, next_growth = 0.0, growth_kinetic = 0.0;
    double window_time = 0.0, window_virial = 0.0, last_pressure = 0.0;
    std::vector<double> radius_rate;
    std::uint64_t window_collisions = 0, growth_steps = 0;
    std::uint8_t growing = 0;
    GrowthEnd ended{};
    get(buf, growth_rate);
    get(buf, radius_rate);
    get(buf, radius_time);
    get(buf, next_growth);
    get(buf, growth_kinetic);
    get(buf, window_time);
    get(buf, window_collisions);
    get(buf, window_virial);
    get(buf, growing);
    get(buf, ended);
    get(buf, last_pressure);
    get(buf, growth_steps);
    std::vector<Vec<D>> position, velocity;
    std::vector<std::uint32_t> tag, count, ev_count;
    std::vector<double> t, ev_time, last_collision;
    std::vector<std::int32_t> ev_partner;
    get(buf, position);
    get(buf, velocity);
    get(buf, tag);
    get(buf, out.species);
    get(buf, t);
    get(buf, out.centre);
    get(buf, count);
    get(buf, ev_time);
    out.first_event_partner_offset =
        static_cast<std::size_t>(buf.tellg()) + sizeof(std::uint64_t); // past the length
    get(buf, ev_partner);
    get(buf, ev_count);
    get(buf, last_collision);
    std::uint32_t stride = 0;
    std::vector<std::uint16_t> n_nbr;
    std::vector<std::uint32_t> nbr;
    get(buf, stride);
    get(buf, n_nbr);
    get(buf, nbr);
    const std::size_t n = position.size();
    if (out.centre.size() != n || n_nbr.size() != n || nbr.size() != n * stride)
        throw InputError("event checkpoint: list arrays of unexpected sizes (the reader in "
                         "tests/support/event_lists.hpp no longer follows EventEngine::save)");
    out.neighbours.resize(n);
    for (std::size_t i = 0; i < n; ++i)
        out.neighbours[i].assign(nbr.begin() + static_cast<std::ptrdiff_t>(i * stride),
                                 nbr.begin() + static_cast<std::ptrdiff_t>(i * stride + n_nbr[i]));
    return out;
}

} // namespace pedesis::test
