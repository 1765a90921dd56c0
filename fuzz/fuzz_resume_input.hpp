#pragma once
// What `pedesis run --resume` reads from a run directory that may not be its own (copied,
// edited, or another program's): the record of the checkpoints' outputs, the outputs it
// cuts back to them, and the directory's config.toml, which it compares with the config.
// The first byte chooses which; the rest is the file.
#include "fuzz_support.hpp"

#include "pedesis/io/frame_writers.hpp"
#include "pedesis/io/resume_record.hpp"
#include "pedesis/run/resume.hpp"

#include <array>

namespace pedesis::fuzz {

// A run directory's growing outputs as a run leaves them: a log and three frames of two
// particles in GSD, XYZ and VTP.
inline void write_outputs(const std::filesystem::path& dir) {
    ParticleStore<2> p;
    p.species_table = {Species{"A", 0.5, 1.0}};
    p.resize(2);
    p.position = {Vec<2>{-1.0, 0.5}, Vec<2>{2.0, -3.0}};
    p.velocity = {Vec<2>{0.25, 1.0}, Vec<2>{-1.0, 0.0}};
    p.tag = {0, 1};
    p.species = {0, 0};
    const Box<2> box(Vec<2>{10.0, 10.0}, std::array<bool, 2>{true, true});
    FrameWriters<2> frames(dir, {"gsd", "xyz", "vtp"});
    AtomicAppendFile log(dir / "log.csv");
    log.append("time,temperature\n");
    for (std::uint64_t k = 0; k < 3; ++k) {
        frames.write(Frame<2>{box, p, 0.5 * static_cast<double>(k), k}, k);
        log.append(std::to_string(k) + ",1.0\n");
    }
}

inline void resume_input(const std::uint8_t* data, std::size_t size) {
    if (size == 0) return;
    const std::string text(reinterpret_cast<const char*>(data) + 1, size - 1);
    const std::filesystem::path dir = std::filesystem::temp_directory_path() /
                                      ("pedesis_fuzz_resume_" + std::to_string(::getpid()));
    remove_at_exit(dir);
    std::filesystem::remove_all(dir);
    std::filesystem::create_directories(dir);
    if (data[0] % 2 == 0) {
        // a record, then the outputs cut back to each of its entries
        write_outputs(dir);
        std::ofstream(dir / checkpoint_record_file, std::ios::binary) << text;
        for (const OutputMarks& m : read_checkpoint_record(dir / checkpoint_record_file)) {
            refusal_allowed([&] { (void)AtomicAppendFile(dir / "log.csv", m.log_bytes); });
            refusal_allowed([&] { (void)FrameWriters<2>(dir, {"gsd", "xyz", "vtp"}, m.frames); });
        }
        return;
    }
    // the directory's config.toml against a config of this pedesis, then the whole plan
    std::ofstream(dir / "config.toml", std::ios::binary) << text;
    const std::string config = "dimension = 2\nseed = 3\n[box]\nlength = 20.0\n[[species]]\n"
                               "name = \"A\"\ncount = 50\nradius = 0.5\n[run]\ntime = 2.0\n";
    bool end_changed = false;
    (void)config_difference(text, config, end_changed);
    (void)plan_resume(dir, text);
}

} // namespace pedesis::fuzz
