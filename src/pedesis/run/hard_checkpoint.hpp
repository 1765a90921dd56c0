#pragma once
// A hard-particle run's checkpoint: a magic word naming the engine, the engine's exact
// state, then the run's own record (hard_run_output.hpp). One layout for the event and
// stepped runs; each names its engine with its own magic word.
#include "pedesis/core/error.hpp"
#include "pedesis/core/particle_checks.hpp"
#include "pedesis/io/atomic_file.hpp"
#include "pedesis/io/binary_stream.hpp"
#include "pedesis/io/checkpoint_file.hpp"
#include "pedesis/run/checkpoint_engines.hpp"
#include "pedesis/run/hard_run_output.hpp"

#include <cstdint>
#include <filesystem>
#include <fstream>
#include <memory>
#include <string>

namespace pedesis {

template <class Engine, int D>
void save_hard_checkpoint(const std::filesystem::path& path, std::uint64_t magic, const Engine& e,
                          const HardRunRecord<D>& s) {
    CheckpointWriter file(path);
    binary::put(file.out(), magic);
    e.save(file.out());
    s.save(file.out());
    file.commit();
}

// Restores the engine with the config's parameters and checks the config's species and
// box against the checkpoint's; `particles_of(engine)` gives the engine's particle store,
// whose contents are checked too (checkpoint_checks.hpp).
// Every fault is an InputError naming the file; `engine` names the engine, for the message
// about another engine's checkpoint (checkpoint_engines.hpp).
template <class Engine, class Params, int D, class ParticlesOf>
std::unique_ptr<Engine> load_hard_checkpoint(const std::filesystem::path& path, std::uint64_t magic,
                                             const char* engine, const Params& params,
                                             const RunConfig& c, HardRunRecord<D>& s,
                                             ParticlesOf particles_of) {
    CheckpointReader file(path);
    std::istream& in = file.in();
    try {
        std::uint64_t word = 0;
        binary::get(in, word);
        if (word != magic) throw InputError(foreign_checkpoint(word, engine));
        auto e = std::make_unique<Engine>(Engine::load(in, params));
        s.load(in);
        // (checkpoints written before issue 51 end here)
        if (file.has_more()) s.load_extension(in);
        file.finish();
        const std::size_t n = particles_of(*e).size();
        if ((!s.start.empty() && s.start.size() != n) ||
            (s.transport && s.transport->plan().particles > n))
            throw InputError("checkpoint: the run record does not fit the particles (corrupt)");
        // the event engine keeps each particle at its own last event: not wrapped
        check_restored_particles(particles_of(*e), e->box(), false);
        check_checkpoint_matches(particles_of(*e).species_table, e->box(), c);
        return e;
    } catch (const InputError& err) {
        throw InputError(path.string() + ": " + err.what());
    }
}

} // namespace pedesis
