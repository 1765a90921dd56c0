// The `lj` force (Lennard-Jones cut at 2.5 sigma, not shifted, as LAMMPS' lj/cut) on the
// perfect fcc crystal of LAMMPS' in.lj benchmark (rho = 0.8442): the potential energy
// per atom and the virial pressure are lattice sums, the same for any whole number of
// cells whose box exceeds twice the list range. LAMMPS (Debian's 20220106 build, in.lj
// with `run 0` and `compute pressure NULL virial`, thermo printed to 12 digits) gives
// -6.77336805323 and -6.23531727009 for 20^3 and 6^3 cells alike. Both are sums of
// ~40 terms per atom in double precision: 1e-9 relative is far above rounding and far
// below any real difference (one shell of neighbours more or less moves them by 1e-2).
#include "support/soft_builder.hpp"

#include "pedesis/soft/evolver.hpp"
#include "pedesis/soft/pair_force.hpp"
#include "pedesis/soft/pair_potentials.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <memory>

using namespace pedesis;

TEST(LennardJones, FccLatticeSumsEqualLammps) {
    const int cells = 6;
    SoftState<3> s = test::fcc_soft_state(cells, 0.8442);
    const double L = s.box.length(0);
    Evolver<3> e(s, 0.3);
    e.add_force(std::make_unique<PairForce<3, LjPair>>("lj", LjPair{1.0, 1.0, 2.5}));
    const auto totals = e.pair_totals();
    const double n = static_cast<double>(s.size());
    EXPECT_NEAR(totals.energy / n / -6.77336805323, 1.0, 1e-9) << totals.energy / n;
    const double p_virial = totals.virial / (3.0 * L * L * L);
    EXPECT_NEAR(p_virial / -6.23531727009, 1.0, 1e-9) << p_virial;
    // the crystal is in mechanical balance: every force vanishes by symmetry
    std::fill(s.force.begin(), s.force.end(), Vec<3>{});
    e.forces()[0]->add_forces(s, e.neighbor_list());
    double largest = 0.0;
    for (const auto& f : s.force) largest = std::max(largest, norm(f));
    EXPECT_LT(largest, 1e-12);
}
