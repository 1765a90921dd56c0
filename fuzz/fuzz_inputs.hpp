#pragma once
// What each fuzz target does with one input, as functions: the libFuzzer targets
// (fuzz_*.cpp) call them, and tests/unit/fuzz_regressions_test.cpp replays the seed corpus
// and every input that once crashed (fuzz/regressions/<target>/) through them in every
// build. Each returns normally or throws InputError (a refusal); anything else is a bug.
#include "fuzz_support.hpp"

#include "pedesis/io/checkpoint_file.hpp"
#include "pedesis/io/gsd_reader.hpp"
#include "pedesis/io/particle_file.hpp"
#include "pedesis/io/tutorial_json.hpp"
#include "pedesis/io/xyz_reader.hpp"
#include "pedesis/run/run.hpp"
#include "pedesis/run/sweep.hpp"
#include "pedesis/setup/run_config.hpp"

#include <sstream>

namespace pedesis::fuzz {

// The TOML config reader (pedesis run CONFIG) on arbitrary text.
inline void config_input(const std::uint8_t* data, std::size_t size) {
    const std::string text(reinterpret_cast<const char*>(data), size);
    (void)parse_run_config(text, "fuzz.toml", false);
}

// The tutorial-JSON reader ([initial] file) on arbitrary bytes, in 2D and 3D.
inline void tutorial_json_input(const std::uint8_t* data, std::size_t size) {
    const auto path = as_file(data, size, ".json");
    refusal_allowed([&] { (void)read_tutorial_json<2>(path); });
    (void)read_tutorial_json<3>(path);
}

// The same file as a start ([initial] file, System.read_init): its dimension, then its
// first and last frames in 2D and 3D, each of which may be refused.
inline void start_file_input(const std::filesystem::path& path) {
    refusal_allowed([&] { (void)particle_file_dimension(path); });
    for (std::int64_t frame : {0, -1}) {
        refusal_allowed([&] { (void)read_particle_file<2>(path, frame); });
        refusal_allowed([&] { (void)read_particle_file<3>(path, frame); });
    }
}

// The extended-XYZ reader (pedesis render, analyze): open, then every frame; then the
// file as a start.
inline void xyz_input(const std::uint8_t* data, std::size_t size) {
    const auto path = as_file(data, size, ".xyz");
    start_file_input(path);
    const XyzReader reader(path, true);
    for (std::size_t k = 0; k < reader.frames(); ++k) (void)reader.frame(k);
}

// The GSD reader (pedesis render, analyze): open, then the frames; then the file as a
// start.
inline void gsd_input(const std::uint8_t* data, std::size_t size) {
    const auto path = as_file(data, size, ".gsd");
    start_file_input(path);
    const GsdReader reader(path);
    for (std::uint64_t k = 0; k < reader.frames() && k < 64; ++k) (void)reader.frame(k);
}

// The checkpoint loaders (pedesis run --restart) on arbitrary state. The bytes go inside
// a valid envelope (length and CRC right), so that the parsers behind the checksum are
// what is fuzzed: a crafted file must be refused too, not only a corrupt one. The first
// byte picks the engine (event, stepped, soft), each with a small config of its own (the
// system the seeds in corpus/fuzz_checkpoint were written for).
inline void checkpoint_input(const std::uint8_t* data, std::size_t size) {
    static const char* const configs[] = {
        // event
        "dimension = 2\nseed = 3\n[box]\nlength = 20.0\nboundary = \"wall\"\n[[species]]\n"
        "name = \"A\"\ncount = 20\nradius = 0.5\n[run]\ntime = 2.0\n[output]\nprogress = "
        "false\nformats = []\n",
        // stepped
        "dimension = 2\ndynamics = \"stepped\"\nseed = 2\n[box]\nlength = 20.0\n[[species]]\n"
        "name = \"A\"\ncount = 20\nradius = 0.5\n[stepped]\ndt = 0.01\n[run]\ntime = 2.0\n"
        "[output]\nprogress = false\nformats = []\n",
        // soft
        "dimension = 2\ndynamics = \"brownian\"\nseed = 1\n[box]\nlength = 20.0\n[[species]]\n"
        "name = \"A\"\ncount = 20\nradius = 1.0\n[initial]\npositions = \"random\"\n"
        "[[force]]\nname = \"harmonic\"\nk = 10.0\n[[integrator]]\nname = \"brownian\"\n"
        "T = 0.1\ngamma = 1.0\n[run]\nsteps = 40\ndt = 0.01\n[output]\nprogress = false\n"
        "formats = []\n",
        // event under Lees-Edwards shear with the rescaling thermostat
        "dimension = 2\nseed = 4\n[box]\nlength = 20.0\nshear_rate = 0.5\n[[species]]\n"
        "name = \"A\"\ncount = 20\nradius = 0.5\n[event]\nthermostat = \"rescale\"\n"
        "temperature = 1.0\n[run]\ntime = 2.0\n[output]\nprogress = false\nformats = []\n",
        // event under gravity on a vibrated floor, Andersen thermostat, white-noise kicks
        "dimension = 2\nseed = 5\n[box]\nlength = 20.0\nboundary = [\"periodic\", \"wall\"]\n"
        "[[species]]\nname = \"A\"\ncount = 20\nradius = 0.5\n[event]\ngravity = [0.0, -1.0]\n"
        "thermostat = \"andersen\"\ntemperature = 1.0\nthermostat_rate = 0.5\n"
        "driving = \"white_noise\"\ndriving_rate = 0.5\ndriving_strength = 0.1\n"
        "[event.moving_wall]\naxis = \"y\"\namplitude = 0.2\nfrequency = 1.0\n[run]\n"
        "time = 2.0\n[output]\nprogress = false\nformats = []\n",
        // soft: Nose-Hoover chains
        "dimension = 2\ndynamics = \"nose_hoover\"\nseed = 1\n[box]\nlength = 20.0\n[[species]]\n"
        "name = \"A\"\ncount = 20\nradius = 1.0\n[initial]\npositions = \"random\"\nvelocities = "
        "\"maxwell_boltzmann\"\ntemperature = 1.0\n[[force]]\nname = \"harmonic\"\nk = 10.0\n"
        "[[integrator]]\nname = \"nose_hoover\"\nT = 1.0\ntau = 0.5\n[run]\nsteps = 40\n"
        "dt = 0.01\n[output]\nprogress = false\nformats = []\n",
        // soft: the MTK barostat beside langevin
        "dimension = 2\ndynamics = \"langevin\"\nseed = 1\n[box]\nlength = 20.0\n[[species]]\n"
        "name = \"A\"\ncount = 20\nradius = 1.0\n[initial]\npositions = \"random\"\nvelocities = "
        "\"maxwell_boltzmann\"\ntemperature = 1.0\n[[force]]\nname = \"harmonic\"\nk = 10.0\n"
        "[[integrator]]\nname = \"langevin\"\nT = 1.0\ngamma = 1.0\n[barostat]\npressure = "
        "0.1\ntau = 1.0\n[run]\nsteps = 40\ndt = 0.01\n[output]\nprogress = false\n"
        "formats = []\n",
    };
    if (size == 0) return;
    const auto dir = std::filesystem::temp_directory_path() /
                     ("pedesis_fuzz_ckpt_" + std::to_string(::getpid()));
    std::filesystem::create_directories(dir);
    remove_at_exit(dir);
    const auto path = dir / "checkpoint.bin";
    {
        CheckpointWriter file(path);
        file.out().write(reinterpret_cast<const char*>(data + 1),
                         static_cast<std::streamsize>(size - 1));
        file.commit();
    }
    const RunConfig c = parse_run_config(configs[data[0] % std::size(configs)], "fuzz.toml", false);
    RunOptions o;
    o.out_dir = dir / "out"; // never written: the loaders run before the run directory
    o.restart = path;
    o.config_path = dir / "fuzz.toml";
    std::ostringstream console;
    (void)make_run(c, o, console);
}

// The sweep reader (pedesis sweep SWEEP): arbitrary text as the sweep file, beside a
// small base config it may name as base.toml; every point's config is built and checked,
// nothing is run or written.
inline void sweep_input(const std::uint8_t* data, std::size_t size) {
    const auto dir = std::filesystem::temp_directory_path() /
                     ("pedesis_fuzz_sweep_" + std::to_string(::getpid()));
    std::filesystem::create_directories(dir);
    remove_at_exit(dir);
    std::ofstream(dir / "base.toml", std::ios::trunc)
        << "dimension = 2\nseed = 3\n[box]\nlength = 20.0\nboundary = \"wall\"\n"
           "[[species]]\nname = \"A\"\ncount = 20\nradius = 0.5\n[event]\n"
           "restitution = 1.0\n[run]\ntime = 2.0\n";
    const auto path = dir / "sweep.toml";
    std::ofstream(path, std::ios::binary | std::ios::trunc)
        .write(reinterpret_cast<const char*>(data), static_cast<std::streamsize>(size));
    (void)load_sweep(path.string(), dir / "out");
}

} // namespace pedesis::fuzz
