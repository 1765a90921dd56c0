#pragma once
// Turns a soft-engine run config into its initial SoftState: the particles either come
// from the [initial] file (the ABP tutorial's JSON, a GSD or an extended XYZ frame, which
// may also give the box, the species and the directors) or are placed as for any other
// engine; a director the file does not give is a seeded random unit vector.
#include "pedesis/io/tutorial_json.hpp"
#include "pedesis/setup/run_config.hpp"
#include "pedesis/soft/soft_state.hpp"

namespace pedesis {

template <int D> SoftState<D> build_soft_state(const RunConfig& c);
// The same with the [initial] file already read (read_initial_file of the config as
// given, or of the completed one: the types are the same), so that a large file is
// parsed once; null when the config has no file.
template <int D> SoftState<D> build_soft_state(const RunConfig& c, const ParticleFile<D>* file);

// The config with what the initial file supplies filled in: its box when the config has
// no [box] (periodic on every axis), and one species per particle type when the config
// has no [[species]] (named as the file names its types, else A, B, ... by type number;
// radius and mass from the file, else ParticleFile::default_radius and 1).
template <int D> RunConfig complete_from_initial_file(const RunConfig& c);
template <int D>
RunConfig complete_from_initial_file(const RunConfig& c, const ParticleFile<D>* file);

} // namespace pedesis
