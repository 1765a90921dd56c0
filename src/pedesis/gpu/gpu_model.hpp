#pragma once
// What the CUDA twin of the soft engine runs, as plain data: the model fixed for a run
// (dimension, box, list, pair table, which terms and integrators) and the per-species
// coefficients of a step, which steering may change. The host side
// (gpu/gpu_stepper.cpp) fills these from the config's plug-ins; the kernels
// (gpu/device_system.cu) read them. C++17, shared by both compilers.
#include "pedesis/soft/pair_potentials.hpp"

#include <cstdint>
#include <vector>

namespace pedesis::gpu {

enum class PairKind : int { none, harmonic, wca, lj };
// What moves the positions: overdamped (brownian), BAOAB (langevin), velocity Verlet
// (nve), or nothing (a run that only rotates directors).
enum class Mover : int { none, brownian, langevin, nve };

struct Model {
    int dim = 2;
    std::size_t particles = 0;
    std::size_t species = 1;
    double box[3] = {1.0, 1.0, 1.0}; // lengths, every axis periodic
    double r_cut = 0.0;              // the list's interaction range
    double skin = 0.0;
    PairKind pair = PairKind::none;
    // one evaluator per pair of species, [a * species + b], of the kind `pair`
    std::vector<HarmonicPair> harmonic;
    std::vector<WcaPair> wca;
    std::vector<LjPair> lj;
    std::vector<double> radius; // per species
    bool propulsion = false;    // self_propulsion: alpha n_i
    bool align = false;         // polar_align: J n_i x sum n_j within align_range
    double align_range = 0.0;
    Mover mover = Mover::none;
    bool rotation = false;           // brownian_rotation
    std::uint64_t seed = 0;          // of the position integrator's noise
    std::uint64_t rotation_seed = 0; // of brownian_rotation's
};

// Per species, for one step (the CPU integrators' own tables, see soft/brownian.hpp and
// soft/langevin.hpp).
struct SpeciesCoefficients {
    double alpha = 0.0;                     // active force
    double drift = 0.0, kick = 0.0;         // brownian: dt / gamma, sqrt(2 T dt / gamma)
    double rot_drift = 0.0, rot_kick = 0.0; // brownian_rotation, the same for angles
    double half_kick = 0.0;                 // langevin, nve: dt / (2 m)
    double half_drift = 0.0;                // langevin: dt / 2 (0 for infinite mass); nve: dt
    double damp = 1.0, noise = 0.0; // langevin: exp(-gamma dt / m), sqrt((1 - damp^2) T / m)

    bool operator==(const SpeciesCoefficients& o) const {
        return alpha == o.alpha && drift == o.drift && kick == o.kick && rot_drift == o.rot_drift &&
               rot_kick == o.rot_kick && half_kick == o.half_kick && half_drift == o.half_drift &&
               damp == o.damp && noise == o.noise;
    }
};

struct StepCoefficients {
    std::vector<SpeciesCoefficients> species;
    double J = 0.0;         // polar_align coupling
    bool noisy = false;     // any translational noise
    bool rot_noisy = false; // any rotational noise
    double dt = 0.0;
    double max_move = 0.0; // a longer move in one step is a blow-up (the skin)
};

// Energy, virial and virial tensor of the pair forces (soft/plugins.hpp's PairTotals,
// C++17; the tensor's slots as core/sym_tensor.hpp's).
struct Totals {
    double energy = 0.0, virial = 0.0;
    double virial_tensor[6] = {};
};

} // namespace pedesis::gpu
