#pragma once
// The parameters of FIRE energy minimisation (dynamics = "minimize", soft/fire.hpp), as
// the config's [minimize] table gives them (setup/minimize_config.hpp). The defaults are
// FIRE 2.0's (Guenole et al., Comput. Mater. Sci. 175, 109584 (2020), table 1) but for
// alpha_start, which is Bitzek et al.'s 0.1 (Phys. Rev. Lett. 97, 170201 (2006)), as
// HOOMD-blue's FIRE takes it (FIRE 2.0 and LAMMPS take 0.25).
#include <cstdint>

namespace pedesis {

struct FireParams {
    // stop when the largest force on a particle, max_i |F_i|, is below this
    double force_tolerance = 1e-10;
    // stop also when the potential energy changes by less than this, relative, from one
    // step to the next (LAMMPS' etol); 0: not checked (it costs an energy pass a step)
    double energy_tolerance = 0.0;
    double dt_start = 0.0; // [run] dt
    double dt_max = 0.0;   // default 10 dt_start
    double dt_min = 0.0;   // default 0.02 dt_start
    std::uint64_t n_delay = 20;
    double f_inc = 1.1;
    double f_dec = 0.5;
    double alpha_start = 0.1;
    double f_alpha = 0.99;
    // largest move of a particle in one step (LAMMPS' dmax), at most the list's skin
    double max_move = 0.1;
    // no lowering of dt in the first n_delay steps (FIRE 2.0's initialdelay)
    bool initial_delay = true;
};

} // namespace pedesis
