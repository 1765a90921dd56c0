#pragma once
// What a blow-up's message says of its likely cause, from what the run knew at its start:
// an overfull box (the particles, taken as spheres of their pair potential's core, fill
// more than close packing), a start with pairs inside each other's core, or else a time
// step too long for the forces. "Reduce dt" alone sent users after the wrong fix when
// the start overlapped or the box was absurdly dense.
#include "pedesis/soft/plugins.hpp"

#include <cstdint>
#include <limits>
#include <memory>
#include <string>
#include <vector>

namespace pedesis {

struct StartFacts {
    bool measured = false;
    std::uint64_t step = 0; // the step of the measurement (a run's first)
    // the pair that lies deepest inside its core, relative to the core
    double closest_ratio = std::numeric_limits<double>::infinity();
    double closest = 0.0, core = 0.0;
    std::uint32_t tag_a = 0, tag_b = 0;
    std::string core_term; // the force term whose core that is
    // sum over species of N_s times the area (2D) or volume (3D) of a ball of diameter
    // core(s, s), over the box's
    double packing = 0.0;
    std::string packing_term;
    double packing_core = 0.0; // of the most numerous species
    std::string one_body;      // a one-body term's start_overlap (the first term's that has one)
};

// The facts above for the state as it is, its pairs taken from `list` (which must hold
// every pair closer than the largest core).
template <int D>
StartFacts measure_start(const SoftState<D>& s, const NeighborList<D>& list,
                         const std::vector<std::unique_ptr<ForceTerm<D>>>& forces);

// The text a blow-up's message ends with: "; likely cause: ..., fix" or "; reduce dt".
std::string blow_up_cause(const StartFacts& start, std::uint64_t failed_step, double dt, int dim);

} // namespace pedesis
