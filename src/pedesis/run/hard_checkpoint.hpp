#pragma once
// A hard-particle run's checkpoint: a magic word naming the engine, the engine's exact
// state, then the run's own record (hard_run_output.hpp). One layout for the event and
// stepped runs; each names its engine with its own magic word.
#include "pedesis/core/error.hpp"
#include "pedesis/io/atomic_file.hpp"
#include "pedesis/io/binary_stream.hpp"
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
    write_file_atomically(
        path,
        [&](std::ostream& out) {
            binary::put(out, magic);
            e.save(out);
            s.save(out);
        },
        true);
}

// Restores the engine with the config's parameters and checks the config's species and
// box against the checkpoint's; `species_of(engine)` gives the engine's species table.
// Every fault is an InputError naming the file; `not_this` says what a foreign file is.
template <class Engine, class Params, int D, class SpeciesOf>
std::unique_ptr<Engine> load_hard_checkpoint(const std::filesystem::path& path, std::uint64_t magic,
                                             const char* not_this, const Params& params,
                                             const RunConfig& c, HardRunRecord<D>& s,
                                             SpeciesOf species_of) {
    std::ifstream in(path, std::ios::binary);
    if (!in) throw InputError(path.string() + ": cannot open checkpoint");
    try {
        std::uint64_t word = 0;
        binary::get(in, word);
        if (word != magic) throw InputError(not_this);
        auto e = std::make_unique<Engine>(Engine::load(in, params));
        s.load(in);
        check_checkpoint_matches(species_of(*e), e->box(), c);
        return e;
    } catch (const InputError& err) {
        throw InputError(path.string() + ": " + err.what());
    }
}

} // namespace pedesis
