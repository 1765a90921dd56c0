// The pressure tensor (log columns pressure_xx ... pressure_yz): the pair virial tensor is
// the sum over pairs of r_a F_b (brute force, and the fcc lattice's cubic symmetry at
// LAMMPS's value); a hard-sphere fluid's collision tensor is isotropic within its error,
// with a trace that is the scalar pressure; and a Lennard-Jones liquid slab between its
// vapour has P_N - P_T != 0 only at its two interfaces, where it integrates to twice a
// positive surface tension.
#include "support/gas_builder.hpp"
#include "support/soft_builder.hpp"

#include "pedesis/core/sym_tensor.hpp"
#include "pedesis/event/event_engine.hpp"
#include "pedesis/observe/pressure.hpp"
#include "pedesis/observe/thermo.hpp"
#include "pedesis/soft/evolver.hpp"
#include "pedesis/soft/langevin.hpp"
#include "pedesis/soft/pair_force.hpp"
#include "pedesis/soft/pair_potentials.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <memory>
#include <numbers>
#include <vector>

using namespace pedesis;

namespace {

// sum over pairs i < j within the cutoff of f/r d_a d_b, d = r_i - r_j (minimum image),
// by brute force over all pairs
template <int D, class Pair>
SymTensor brute_virial_tensor(const SoftState<D>& s, const Pair& pair) {
    SymTensor w{};
    for (std::size_t i = 0; i < s.size(); ++i)
        for (std::size_t j = i + 1; j < s.size(); ++j) {
            const Vec<D> d = s.box.minimum_image(s.p.position[i] - s.p.position[j]);
            double f_over_r, energy;
            if (pair.eval(norm2(d), s.p.radius(i) + s.p.radius(j), f_over_r, energy))
                add_sym_outer<D>(w, d, d, f_over_r);
        }
    return w;
}

template <int D, class Pair> void check_pair_tensor(SoftState<D> s, const Pair& pair) {
    const SymTensor want = brute_virial_tensor(s, pair);
    Evolver<D> e(s, 0.3);
    e.add_force(std::make_unique<PairForce<D, Pair>>("pair", pair));
    const PairTotals t = e.pair_totals();
    double scale = 0.0;
    for (double x : want) scale = std::max(scale, std::abs(x));
    ASSERT_GT(scale, 1.0); // dense enough for many pairs
    for (int c = 0; c < 6; ++c)
        EXPECT_NEAR(t.virial_tensor[c], want[c], 1e-10 * scale) << D << "D, " << sym_suffix(c);
    EXPECT_NEAR(sym_trace<D>(t.virial_tensor), t.virial, 1e-12 * scale);
    if constexpr (D == 2) {
        for (int c : {2, 4, 5}) EXPECT_EQ(t.virial_tensor[c], 0.0) << "2D has no " << sym_suffix(c);
    }
}

} // namespace

TEST(PressureTensor, PairVirialTensorIsTheSumOverPairs) {
    check_pair_tensor(test::random_soft_system<2>(400, 14.0, 0.5, 21), HarmonicPair{10.0, -1.0});
    check_pair_tensor(test::random_soft_system<3>(300, 9.0, 0.5, 22), LjPair{1.0, 1.0, 2.5});
    check_pair_tensor(test::random_soft_system<3>(300, 8.0, 0.5, 23), WcaPair{1.0, 1.0});
}

// in.lj's fcc crystal: cubic symmetry makes the virial tensor W/3 times the unit tensor;
// LAMMPS's virial pressure (lennard_jones_test.cpp) is -6.23531727009 per component.
// With the tail correction the homogeneous part adds to the diagonal alone.
TEST(PressureTensor, FccCrystalIsIsotropicAtLammpsValue) {
    SoftState<3> s = test::fcc_soft_state(6, 0.8442);
    const double V = s.box.volume();
    for (bool tail : {false, true}) {
        Evolver<3> e(s, 0.3);
        e.add_force(
            std::make_unique<PairForce<3, LjPair>>("lj", LjPair{1.0, 1.0, 2.5, false, tail}));
        const PairTotals t = e.pair_totals();
        const double rc = 2.5, rho = 0.8442;
        // the tail's pressure: (16/3) pi rho^2 ((2/3) rc^-9 - rc^-3)
        const double p_tail = tail ? 16.0 / 3.0 * std::numbers::pi * rho * rho *
                                         (2.0 / 3.0 * std::pow(rc, -9) - std::pow(rc, -3))
                                   : 0.0;
        for (int a = 0; a < 3; ++a)
            EXPECT_NEAR(t.virial_tensor[a] / V / (-6.23531727009 + p_tail), 1.0, 1e-9)
                << "tail " << tail << ", " << sym_suffix(a);
        for (int c = 3; c < 6; ++c) EXPECT_NEAR(t.virial_tensor[c] / V, 0.0, 1e-9) << sym_suffix(c);
    }
}

// Hard spheres, eta = 0.30, N = 500, periodic: 30 blocks of 4 time units (about 60
// collisions per particle each). Each diagonal component must agree with the mean
// pressure and each off-diagonal with zero within 4.5 standard errors of the block means
// (the ~0.5% block scatter of Z ~ 2.2 at this size); and a block's diagonal mean is its
// scalar pressure to round-off.
TEST(PressureTensor, HardSphereFluidIsIsotropic) {
    const auto gas = test::make_gas(test::equal_gas<3>(500, 0.30));
    EventEngine<3> e(gas.particles, gas.box, EventParams{});
    StopLimits lim;
    lim.time = 20.0;
    e.run(lim);
    SymTensor start = measure_kinetics(e.snapshot(), e.box(), Momentum::conserving).thermal_tensor;
    std::vector<double> comp[6], mean;
    for (int b = 0; b < 30; ++b) {
        const auto before = e.counters();
        const double t0 = e.time();
        lim.time = t0 + 4.0;
        e.run(lim);
        // elastic collisions keep K; the kinetic tensor's mean over the block is sampled
        // at both ends
        const SymTensor end =
            measure_kinetics(e.snapshot(), e.box(), Momentum::conserving).thermal_tensor;
        const SymTensor kin = sym_midpoint(start, end);
        start = end;
        const SymTensor p =
            interval_pressure_tensor(e.box(), before, e.counters(), e.time() - t0, kin);
        const double scalar = interval_pressure(e.box(), before, e.counters(), e.time() - t0, kin);
        EXPECT_NEAR(sym_trace<3>(p) / 3.0, scalar, 1e-13 * scalar);
        for (int c = 0; c < 6; ++c) comp[c].push_back(p[c]);
        mean.push_back(scalar);
    }
    const test::BlockStats P = test::block_stats(mean);
    for (int c = 0; c < 6; ++c) {
        const test::BlockStats s = test::block_stats(comp[c]);
        const double expected = c < 3 ? P.mean : 0.0;
        EXPECT_NEAR(s.mean, expected, 4.5 * s.std_error)
            << sym_suffix(c) << " = " << s.mean << " +- " << s.std_error << ", P = " << P.mean;
        EXPECT_LT(s.std_error, 0.01 * P.mean) << "blocks too short for the tolerance";
    }
}

namespace {

// in.lj's kind of Lennard-Jones (cut at 2.5, not shifted) at T = 0.8: a liquid slab of
// 7 fcc cells (width ~12) across x in a 4 x 4 cell cross-section, in a box 24 long, the
// rest vapour. Langevin, gamma = 1, dt = 0.005.
struct Slab {
    static constexpr double rho = 0.8, T = 0.8, rc = 2.5, Lx = 24.0;
    SoftState<3> s;
    Slab() {
        const double a = std::cbrt(4.0 / rho), Ly = 4 * a;
        s.box = Box<3>(Vec<3>{{Lx, Ly, Ly}}, std::array<bool, 3>{true, true, true});
        s.resize(4 * 7 * 4 * 4);
        s.p.species_table = {Species{"A", 0.5, 1.0}};
        const double basis[4][3] = {{0, 0, 0}, {0.5, 0.5, 0}, {0.5, 0, 0.5}, {0, 0.5, 0.5}};
        std::size_t i = 0;
        for (int x = 0; x < 7; ++x)
            for (int y = 0; y < 4; ++y)
                for (int z = 0; z < 4; ++z)
                    for (const auto& b : basis) {
                        s.p.position[i] = Vec<3>{
                            {(x + b[0] - 3.5) * a, (y + b[1] - 2.0) * a, (z + b[2] - 2.0) * a}};
                        s.p.tag[i] = static_cast<std::uint32_t>(i);
                        s.director[i] = Vec<3>{{1.0, 0.0, 0.0}};
                        ++i;
                    }
    }
};

// The slab's centre along x: the direction of sum exp(2 pi i x / Lx) (a circular mean,
// which the periodic image of the vapour does not bias).
double slab_centre(const SoftState<3>& s, double Lx) {
    double c = 0.0, sn = 0.0;
    for (const auto& r : s.p.position) {
        c += std::cos(2.0 * std::numbers::pi * r[0] / Lx);
        sn += std::sin(2.0 * std::numbers::pi * r[0] / Lx);
    }
    return std::atan2(sn, c) * Lx / (2.0 * std::numbers::pi);
}

} // namespace

// The profile is computed here, independently of the engine: each particle's kinetic
// m v_a v_b, and half of each pair's r_a F_b (the Harasima split), binned by x from the
// slab's centre. Its bins sum to the engine's whole-box tensor; its P_N - P_T must vanish
// within 4 standard errors in the bulk liquid (|x| < 3) and the vapour (|x| > 10: the
// interfaces, at |x| ~ 5.5, have a negative lobe on their vapour side out to ~9), and the
// two interfaces must hold the whole integral, 2 gamma, with gamma > 0 at 5 standard
// errors; and the engine's whole-box tensor gives gamma = (Lx / 2) (P_N - P_T) > 0 at
// 5 standard errors. 10 blocks of 40 time units after 20 to melt and settle.
TEST(PressureTensor, LiquidSlabHasItsAnisotropyAtTheInterfaces) {
    Slab slab;
    SoftState<3>& s = slab.s;
    const LjPair lj{1.0, 1.0, Slab::rc};
    Evolver<3> e(s, 0.3);
    e.add_force(std::make_unique<PairForce<3, LjPair>>("lj", lj));
    e.add_integrator(std::make_unique<LangevinIntegrator<3>>(Slab::T, 1.0, 5));
    const double dt = 0.005, Lx = Slab::Lx, V = s.box.volume(), area = V / Lx;
    for (int k = 0; k < 4000; ++k) e.evolve(dt);

    constexpr int bins = 24;
    const double width = Lx / bins;
    std::vector<double> bulk, vapour, interfaces, global;
    for (int block = 0; block < 10; ++block) {
        std::vector<double> diff(bins, 0.0); // sum over samples of (P_N - P_T) per bin
        double global_diff = 0.0; // the engine's whole-box P_N - P_T, summed over samples
        int samples = 0;
        for (int k = 1; k <= 8000; ++k) {
            e.evolve(dt);
            if (k % 100 != 0) continue;
            ++samples;
            const double centre = slab_centre(s, Lx);
            auto bin_of = [&](const Vec<3>& r) {
                double x = r[0] - centre;
                x -= Lx * std::round(x / Lx);
                return std::min(bins - 1, static_cast<int>((x + 0.5 * Lx) / width));
            };
            std::vector<double> d(bins, 0.0);
            SymTensor whole{};
            double kinetic = 0.0;
            for (std::size_t i = 0; i < s.size(); ++i) {
                const Vec<3>& v = s.p.velocity[i];
                const double k = v[0] * v[0] - 0.5 * (v[1] * v[1] + v[2] * v[2]);
                d[bin_of(s.p.position[i])] += k;
                kinetic += k;
                for (std::size_t j = i + 1; j < s.size(); ++j) {
                    const Vec<3> r = s.box.minimum_image(s.p.position[i] - s.p.position[j]);
                    double f_over_r, u;
                    if (!lj.eval(norm2(r), 1.0, f_over_r, u)) continue;
                    const double n_minus_t =
                        f_over_r * (r[0] * r[0] - 0.5 * (r[1] * r[1] + r[2] * r[2]));
                    d[bin_of(s.p.position[i])] += 0.5 * n_minus_t;
                    d[bin_of(s.p.position[j])] += 0.5 * n_minus_t;
                    add_sym_outer<3>(whole, r, r, f_over_r);
                }
            }
            const PairTotals t = e.pair_totals();
            for (int c = 0; c < 6; ++c)
                ASSERT_NEAR(t.virial_tensor[c], whole[c], 1e-9 * std::abs(t.virial))
                    << sym_suffix(c);
            for (int b = 0; b < bins; ++b) diff[b] += d[b] / (area * width);
            const SymTensor& w = t.virial_tensor;
            global_diff += (kinetic + w[0] - 0.5 * (w[1] + w[2])) / V;
        }
        // integrals over x of the block's mean P_N - P_T
        double in_bulk = 0.0, in_vapour = 0.0, at_interfaces = 0.0;
        for (int b = 0; b < bins; ++b) {
            const double x = (b + 0.5) * width - 0.5 * Lx, value = diff[b] / samples * width;
            if (std::abs(x) < 3.0)
                in_bulk += value;
            else if (std::abs(x) > 10.0)
                in_vapour += value;
            else
                at_interfaces += value;
        }
        bulk.push_back(in_bulk);
        vapour.push_back(in_vapour);
        interfaces.push_back(at_interfaces);
        global.push_back(global_diff / samples * Lx);
    }
    const auto b = test::block_stats(bulk), v = test::block_stats(vapour),
               i = test::block_stats(interfaces), g = test::block_stats(global);
    std::printf("integrals of P_N - P_T: bulk liquid %.4f +- %.4f, vapour %.4f +- %.4f, "
                "interfaces %.4f +- %.4f; whole box %.4f +- %.4f: gamma = %.4f +- %.4f\n",
                b.mean, b.std_error, v.mean, v.std_error, i.mean, i.std_error, g.mean, g.std_error,
                0.5 * g.mean, 0.5 * g.std_error);
    EXPECT_NEAR(b.mean, 0.0, 4.0 * b.std_error);
    EXPECT_NEAR(v.mean, 0.0, 4.0 * v.std_error);
    EXPECT_GT(i.mean, 5.0 * i.std_error);
    EXPECT_GT(g.mean, 5.0 * g.std_error); // the engine's own tensor: gamma > 0
}
