#pragma once
// Particle configurations in the JSON layout of the Active Brownian Particles
// tutorial (ABPTutorial, pymd), so that its initial conditions and analysis
// scripts work with pedesis unchanged:
//   {"system": {"time": t, "box": {"Lx": .., "Ly": .. [, "Lz": ..]},
//               "particles": [{"id": 0, "type": 0, "r": [..], "v": [..],
//                              "radius": .., "mass": .. or "inf"}, ...]}}
// Soft/active states add the director "n" and the force "f" per particle, as the
// tutorial's own dump does. Vectors have D components. Keys that pedesis has no use
// for on reading (e.g. the force "f") are ignored.
#include "pedesis/core/box.hpp"
#include "pedesis/core/frame.hpp"
#include "pedesis/core/vec.hpp"

#include <nlohmann/json.hpp>

#include <array>
#include <cstdint>
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

namespace pedesis {

// Particles in tag order; "type" is the species index. Doubles are written with
// round-trip precision, so reading the document back gives identical values. A frame
// with directors and forces (soft/active) gives each particle its director "n" and the
// force "f" of the last step beside "v": what the tutorial's pymd reads as an initial
// configuration (it takes "n", "v" and "f" when present).
template <int D> nlohmann::json to_tutorial_json(const Frame<D>& f);

// One particle as the file gives it; what the file leaves out stays empty and is
// for the caller to fill from its own defaults.
template <int D> struct FileParticle {
    std::uint32_t id = 0;
    int type = 0;
    Vec<D> r{};
    std::optional<Vec<D>> v;
    std::optional<Vec<D>> n;
    std::optional<double> radius, mass; // mass may be +infinity (fixed obstacle)
};

// What a start file holds: the tutorial's JSON (read_tutorial_json), or a frame of a GSD
// or extended XYZ file made into the same shape (io/particle_file.hpp).
template <int D> struct ParticleFile {
    std::optional<Vec<D>> box; // box lengths, if the file has a "box"
    // Per axis periodic (true) or walled, where the file says: GSD's log/pedesis/periodic,
    // XYZ's pbc; the tutorial's JSON does not.
    std::optional<std::array<bool, D>> periodic;
    std::vector<FileParticle<D>> particles; // in file order, ids as given
    // The names of the types, by type index, where the file names them (GSD's
    // particles/types, XYZ's species column); empty for the tutorial's JSON, whose types
    // are numbers only.
    std::vector<std::string> type_names;
    // The radius of a particle whose file gives none, where species are taken from the
    // file: the tutorial's 1, or half of the hoomd schema's default diameter 1 (GSD), or
    // pedesis' default 0.5 (XYZ).
    double default_radius = 1.0;
    // The relative precision of the file's numbers, for comparing its box, radii and
    // masses with a config's: GSD stores single precision; text keeps every digit.
    double precision = 1e-12;
};

// Reads and validates a configuration: every value is checked (finite numbers,
// vectors of D components, positive radius and mass, unique non-negative ids),
// and any fault is an InputError naming the file and the particle and key, or
// the line and column of a JSON syntax error. Checks against the species table
// or the box are the caller's.
template <int D> ParticleFile<D> read_tutorial_json(const std::filesystem::path& path);

// The dimension of a file, read no further than needed to tell: 3 when the box has "Lz"
// or the first particle's "r" has three components, else 2 (also for a malformed file,
// which read_tutorial_json then refuses with the reason).
int tutorial_json_dimension(const std::filesystem::path& path);

} // namespace pedesis
