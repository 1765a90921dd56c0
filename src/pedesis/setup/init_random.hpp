#pragma once
// The ABP tutorial's random_init: N = round(phi V) particles at uniform random positions
// at least rcut apart (minimum image) in a periodic box centred at the origin, each with
// a uniform random director, as a SoftState in tag order. Shared by `pedesis init
// random` and the Python module's pedesis.builder.random_init, which name the
// parameters in their own way (`--phi` or `phi`) in messages.
#include "pedesis/soft/soft_state.hpp"

#include <cstdint>
#include <optional>
#include <string>

namespace pedesis {

struct InitRandomOptions {
    double phi = 0.0;
    double L = 0.0;
    std::optional<double> Ly, Lz;
    double rcut = 0.0;
    double radius = 1.0;
    std::uint64_t seed = 1;
    std::string context = "init random"; // message prefix
    std::string option_prefix = "--";    // how parameters are named in messages
};

// Throws InputError for impossible parameters (naming the parameter) and when the
// density is too high to place centres rcut apart at random.
template <int D> SoftState<D> init_random(const InitRandomOptions& o);

// "box 50 x 50" style lengths, for messages and summaries.
template <int D> std::string box_lengths_text(const Box<D>& box);

} // namespace pedesis
