#include "pedesis/run/soft_checkpoint.hpp"

#include "pedesis/core/error.hpp"
#include "pedesis/core/particle_checks.hpp"
#include "pedesis/io/atomic_file.hpp"
#include "pedesis/io/binary_stream.hpp"
#include "pedesis/io/checkpoint_file.hpp"
#include "pedesis/run/checkpoint_engines.hpp"

#include <fmt/format.h>

#include <cmath>

#include <fstream>

namespace pedesis {

namespace {

// 3: the run's summed temperature; 4: active_ou's active velocities; 5: Lees-Edwards
// shear (the rate, the box's offset and the list's, the velocity profile and P_xy series)
// and the [transport] measurement; 6: the integrators' own state (a thermostat's), by name;
// 7: the box of the list's last build (a barostat changes the box)
constexpr std::uint32_t soft_checkpoint_version = 7;

// The state's arrays in checkpoint order; one list serves saving and loading.
template <class State, class F> void for_each_array(State& s, F&& f) {
    f(s.p.position);
    f(s.p.velocity);
    f(s.p.tag);
    f(s.p.species);
    f(s.director);
    f(s.force);
    f(s.torque);
    f(s.image);
}

} // namespace

template <int D>
void save_soft_checkpoint(const std::filesystem::path& path, const SoftState<D>& s,
                          const Evolver<D>& evolver, const SoftRunBook<D>& book) {
    CheckpointWriter file(path);
    std::ostream& out = file.out();
    binary::put_header(out, soft_checkpoint_magic, soft_checkpoint_version, D);
    binary::put(out, s.box);
    binary::put(out, s.p.species_table);
    binary::put(out, s.step);
    binary::put(out, s.time);
    for_each_array(s, [&](const auto& v) { binary::put(out, v); });
    binary::put(out, evolver.list_reference());
    binary::put(out, evolver.list_builds());
    binary::put(out, book.start);
    binary::put(out, book.frames);
    binary::put(out, book.samples);
    binary::put(out, book.sum_pressure);
    binary::put(out, book.sum_polar_order);
    binary::put(out, book.sum_temperature);
    binary::put(out, s.active_velocity); // (empty without active_ou)
    binary::put(out, s.box.shear_rate());
    binary::put(out, s.box.shear_offset());
    binary::put(out, evolver.list_shear_offset());
    binary::put(out, book.shear.velocity_sum);
    binary::put(out, book.shear.count);
    binary::put(out, book.shear.shear_stress);
    binary::put<std::uint8_t>(out, book.transport.has_value());
    if (book.transport) book.transport->save(out);
    binary::put<std::uint64_t>(out, evolver.integrators().size());
    for (const auto& i : evolver.integrators()) {
        binary::put(out, i->name());
        binary::put(out, i->saved_state());
    }
    // the box of the list's build, which a barostat's box has left since
    binary::put(out, evolver.list_box_lengths());
    file.commit();
}

template <int D>
void load_soft_checkpoint(const std::filesystem::path& path, const RunConfig& c, SoftState<D>& s,
                          Evolver<D>& evolver, SoftRunBook<D>& book) {
    CheckpointReader file(path);
    std::istream& in = file.in();
    try {
        // another engine's checkpoint is told by its magic word, read ahead
        std::uint64_t word = 0;
        binary::get(in, word);
        if (word != soft_checkpoint_magic) throw InputError(foreign_checkpoint(word, soft_engine));
        in.seekg(-static_cast<std::streamoff>(sizeof word), std::ios::cur);
        // (a version-3 file is this one without active velocities: runs before active_ou
        // continue from theirs; versions 3 and 4 have no shear)
        const std::uint32_t version =
            binary::get_header(in, soft_checkpoint_magic, soft_checkpoint_version, D,
                               "soft-engine (brownian, langevin, nve)", 3);
        binary::get(in, s.box);
        binary::get(in, s.p.species_table);
        const std::size_t n_species = s.p.species_table.size();
        binary::get(in, s.step);
        binary::get(in, s.time);
        for_each_array(s, [&](auto& v) { binary::get(in, v); });
        std::vector<Vec<D>> reference;
        std::uint64_t builds = 0;
        binary::get(in, reference);
        binary::get(in, builds);
        binary::get(in, book.start);
        binary::get(in, book.frames);
        binary::get(in, book.samples);
        binary::get(in, book.sum_pressure);
        binary::get(in, book.sum_polar_order);
        binary::get(in, book.sum_temperature);
        s.active_velocity.clear();
        if (version >= 4) binary::get(in, s.active_velocity);
        double rate = 0.0, offset = 0.0, list_offset = 0.0;
        book.shear = ShearRecord{};
        if (version >= 5) {
            binary::get(in, rate);
            binary::get(in, offset);
            binary::get(in, list_offset);
            binary::get(in, book.shear.velocity_sum);
            binary::get(in, book.shear.count);
            binary::get(in, book.shear.shear_stress);
        }
        book.transport.reset();
        if (version >= 5) {
            std::uint8_t measured = 0;
            binary::get(in, measured);
            if (measured > 1) throw InputError("file is corrupt (transport flag)");
            if (measured) book.transport.emplace(TransportMeasurement<D>::load(in, "checkpoint"));
        }
        // An integrator the checkpoint has no state for (a thermostat that a restart
        // switches on) starts from its own.
        std::uint64_t integrators = 0;
        if (version >= 6) binary::get(in, integrators);
        if (integrators > 64) throw InputError("file is corrupt (integrator count)");
        for (std::uint64_t k = 0; k < integrators; ++k) {
            std::string name;
            std::vector<double> saved;
            binary::get(in, name);
            binary::get(in, saved);
            for (const auto& i : evolver.integrators())
                if (i->name() == name) i->restore_state(saved);
        }
        std::vector<double> list_lengths;
        if (version >= 7) binary::get(in, list_lengths);
        file.finish();
        if (book.shear.velocity_sum.size() != book.shear.count.size())
            throw InputError("file is corrupt (velocity profile lengths differ)");
        // (a corrupt rate or offset is refused by the box)
        s.box.set_shear_rate(rate);
        s.box.set_shear_offset(offset);
        if (rate != c.shear_rate)
            throw InputError(fmt::format("[box] shear_rate = {} in {} does not match the "
                                         "checkpoint's, {}: a run continues at its own rate",
                                         c.shear_rate, c.file, rate));
        const std::size_t n = s.p.position.size();
        if (s.p.velocity.size() != n || s.p.tag.size() != n || s.p.species.size() != n ||
            s.director.size() != n || s.force.size() != n || s.torque.size() != n ||
            s.image.size() != n || book.start.size() != n ||
            (!s.active_velocity.empty() && s.active_velocity.size() != n) ||
            (!reference.empty() && reference.size() != n) ||
            (book.transport && book.transport->plan().particles > n))
            throw InputError("file is corrupt (array lengths differ)");
        check_restored_particles(s.p, s.box, true);
        for (std::size_t i = 0; i < n; ++i)
            for (int a = 0; a < D; ++a)
                if (!std::isfinite(s.director[i][a]) || !std::isfinite(book.start[i][a]) ||
                    (!s.active_velocity.empty() && !std::isfinite(s.active_velocity[i][a])))
                    throw InputError("corrupt state: particle " + std::to_string(s.p.tag[i]) +
                                     ": director, start position or active velocity is not a "
                                     "finite number");
        if (!std::isfinite(s.time) || s.time < 0.0)
            throw InputError("corrupt state: the time is not a finite number >= 0");

        if (!c.species.empty()) {
            if (c.species.size() != n_species) throw InputError("species do not match " + c.file);
            for (std::size_t k = 0; k < n_species; ++k)
                if (s.p.species_table[k].name != c.species[k].name ||
                    s.p.species_table[k].radius != c.species[k].radius ||
                    !(s.p.species_table[k].mass == c.species[k].mass))
                    throw InputError("species '" + s.p.species_table[k].name + "' does not match " +
                                     c.file);
        }
        if (!c.box_lengths.empty())
            for (int a = 0; a < D; ++a)
                if (!c.barostat.on && s.box.length(a) != c.box_lengths[static_cast<std::size_t>(a)])
                    throw InputError("box does not match " + c.file);
        try {
            evolver.restore_list(reference, builds, list_offset, list_lengths);
        } catch (const RunError& e) {
            // the list's positions come from the file: a bad one is a corrupt file (exit 2)
            throw InputError(std::string("corrupt neighbour-list state: ") + e.what());
        }
        evolver.mark_forces_current();
    } catch (const InputError& err) {
        throw InputError(path.string() + ": " + err.what());
    }
}

template void save_soft_checkpoint<2>(const std::filesystem::path&, const SoftState<2>&,
                                      const Evolver<2>&, const SoftRunBook<2>&);
template void save_soft_checkpoint<3>(const std::filesystem::path&, const SoftState<3>&,
                                      const Evolver<3>&, const SoftRunBook<3>&);
template void load_soft_checkpoint<2>(const std::filesystem::path&, const RunConfig&, SoftState<2>&,
                                      Evolver<2>&, SoftRunBook<2>&);
template void load_soft_checkpoint<3>(const std::filesystem::path&, const RunConfig&, SoftState<3>&,
                                      Evolver<3>&, SoftRunBook<3>&);

} // namespace pedesis
