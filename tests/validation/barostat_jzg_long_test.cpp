// Validation of the MTK barostat (soft/barostat.hpp) against the Lennard-Jones equation of
// state of Johnson, Zollweg & Gubbins, Mol. Phys. 78, 591 (1993) (their MBWR fit, Table 10,
// written out below from the paper's formulas), for the full potential: the runs cut it at
// 3 sigma with the tail corrections (g = 1 beyond), in the forces' virial and so in the
// barostat's pressure.
// - At T* = 2 and P* = P_JZG(rho* = 0.6) = 1.7668 an NPT run (langevin + isotropic MTK,
//   500 particles) has <N/V> = 0.600 within 0.006 (1%: the block-averaged error is about
//   0.002, the tail's g = 1 approximation at 3 sigma shifts P by well under 1%).
// - Its volume fluctuations give kappa_T = var V / (T <V>), which equals the one from the
//   slope of P(rho) of two NVT runs at rho = 0.57 and 0.63 (langevin alone; the central
//   difference's own error is 0.5% by the MBWR's curvature), and the MBWR's own
//   1 / (rho dP/drho) = 0.179, within 25% (the fluctuation estimate is known to about 5%
//   from its blocks, the slope to about 4%).
#include "support/soft_builder.hpp"

#include "pedesis/soft/barostat.hpp"
#include "pedesis/soft/evolver.hpp"
#include "pedesis/soft/langevin.hpp"
#include "pedesis/soft/pair_force.hpp"
#include "pedesis/soft/pair_potentials.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <iostream>
#include <memory>
#include <vector>

using namespace pedesis;

namespace {

// JZG's MBWR pressure P(rho, T) (Table 10's x_1..x_32, gamma = 3).
double jzg_pressure(double rho, double T) {
    const double x[33] = {0,
                          0.8623085097507421,
                          2.976218765822098,
                          -8.402230115796038,
                          0.1054136629203555,
                          -0.8564583828174598,
                          1.582759470107601,
                          0.7639421948305453,
                          1.753173414312048,
                          2.798291772190376e3,
                          -4.8394220260857657e-2,
                          0.9963265197721935,
                          -3.698000291272493e1,
                          2.084012299434647e1,
                          8.305402124717285e1,
                          -9.574799715203068e2,
                          -1.477746229234994e2,
                          6.398607852471505e1,
                          1.603993673294834e1,
                          6.805916615864377e1,
                          -2.791293578795945e3,
                          -6.245128304568454,
                          -8.116836104958410e3,
                          1.488735559561229e1,
                          -1.059346754655084e4,
                          -1.131607632802822e2,
                          -8.867771540418822e3,
                          -3.986982844450543e1,
                          -4.689270299917261e3,
                          2.593535277438717e2,
                          -2.694523589434903e3,
                          -7.218487631550215e2,
                          1.721802063863269e2};
    const double T2 = T * T;
    const double a[8] = {x[1] * T + x[2] * std::sqrt(T) + x[3] + x[4] / T + x[5] / T2,
                         x[6] * T + x[7] + x[8] / T + x[9] / T2,
                         x[10] * T + x[11] + x[12] / T,
                         x[13],
                         x[14] / T + x[15] / T2,
                         x[16] / T,
                         x[17] / T + x[18] / T2,
                         x[19] / T2};
    const double b[6] = {(x[20] + x[21] / T) / T2, (x[22] + x[23] / T2) / T2,
                         (x[24] + x[25] / T) / T2, (x[26] + x[27] / T2) / T2,
                         (x[28] + x[29] / T) / T2, (x[30] + x[31] / T + x[32] / T2) / T2};
    double p = rho * T;
    for (int i = 0; i < 8; ++i) p += a[i] * std::pow(rho, i + 2);
    const double F = std::exp(-3.0 * rho * rho);
    for (int i = 0; i < 6; ++i) p += F * b[i] * std::pow(rho, 2 * i + 3);
    return p;
}

constexpr double T = 2.0, rho0 = 0.6, dt = 0.005;
const LjPair lj{1.0, 1.0, 3.0, false, true};

// Mean and its error from `blocks` block means.
struct Estimate {
    double mean, error;
};
Estimate blocked(const std::vector<double>& x, int blocks = 10) {
    const std::size_t per = x.size() / static_cast<std::size_t>(blocks);
    std::vector<double> m(static_cast<std::size_t>(blocks), 0.0);
    for (int b = 0; b < blocks; ++b) {
        for (std::size_t k = 0; k < per; ++k) m[b] += x[b * per + k];
        m[b] /= static_cast<double>(per);
    }
    double mean = 0.0, var = 0.0;
    for (double v : m) mean += v / blocks;
    for (double v : m) var += (v - mean) * (v - mean) / (blocks - 1);
    return {mean, std::sqrt(var / blocks)};
}

void maxwell(SoftState<3>& s) {
    for (std::size_t i = 0; i < s.size(); ++i) {
        CounterRng rng(11, RngStream::velocity, static_cast<std::uint32_t>(i));
        for (int a = 0; a < 3; ++a) s.p.velocity[i][a] = std::sqrt(T) * rng.normal();
    }
}

double twice_kinetic(const SoftState<3>& s) {
    double k = 0.0;
    for (const auto& v : s.p.velocity) k += norm2(v);
    return k;
}

// Mean pressure (with its error) of an NVT run at density rho.
Estimate nvt_pressure(double rho) {
    SoftState<3> s = test::fcc_soft_state(5, rho);
    maxwell(s);
    Evolver<3> e(s, 0.4);
    e.add_force(std::make_unique<PairForce<3, LjPair>>("lj", lj));
    e.add_integrator(std::make_unique<LangevinIntegrator<3>>(PerSpecies(T), PerSpecies(0.5), 21));
    e.run(5000, dt);
    std::vector<double> p;
    for (int k = 0; k < 4000; ++k) {
        e.run(10, dt);
        p.push_back((twice_kinetic(s) + e.pair_totals().virial) / (3.0 * s.box.volume()));
    }
    return blocked(p);
}

} // namespace

TEST(BarostatValidation, LjFluidReachesTheJzgDensityAndCompressibility) {
    const double P = jzg_pressure(rho0, T);
    const double h = 1e-4;
    const double slope_jzg = (jzg_pressure(rho0 + h, T) - jzg_pressure(rho0 - h, T)) / (2 * h);
    const double kappa_jzg = 1.0 / (rho0 * slope_jzg);

    // NPT from a slightly dilute start
    SoftState<3> s = test::fcc_soft_state(5, 0.55);
    maxwell(s);
    const double n = static_cast<double>(s.size());
    Evolver<3> e(s, 0.4);
    e.add_force(std::make_unique<PairForce<3, LjPair>>("lj", lj));
    e.add_integrator(std::make_unique<MtkIntegrator<3>>(
        P, 1.0, false,
        MtkIntegrator<3>::Bath{PerSpecies(T), PerSpecies(0.5), 21, detail::NoiseShape::gaussian},
        [&e] { return e.pair_totals().virial_tensor; }));
    e.run(10000, dt);
    std::vector<double> density, volume, pressure;
    for (int k = 0; k < 6000; ++k) {
        e.run(10, dt);
        const double V = s.box.volume();
        density.push_back(n / V);
        volume.push_back(V);
        pressure.push_back((twice_kinetic(s) + e.pair_totals().virial) / (3.0 * V));
    }
    const Estimate rho = blocked(density), p_npt = blocked(pressure);
    // kappa_T from each block's volume variance, for its error
    std::vector<double> kappas;
    const std::size_t per = volume.size() / 10;
    for (std::size_t b = 0; b < 10; ++b) {
        double m = 0.0, m2 = 0.0;
        for (std::size_t k = b * per; k < (b + 1) * per; ++k) {
            m += volume[k] / static_cast<double>(per);
            m2 += volume[k] * volume[k] / static_cast<double>(per);
        }
        kappas.push_back((m2 - m * m) / (T * m));
    }
    const Estimate kappa = blocked(kappas);
    const double kappa_npt = kappa.mean;

    const Estimate lo = nvt_pressure(rho0 - 0.03), hi = nvt_pressure(rho0 + 0.03);
    const double slope = (hi.mean - lo.mean) / 0.06;
    const double slope_error = std::hypot(hi.error, lo.error) / 0.06;
    const double kappa_nvt = 1.0 / (rho0 * slope);

    std::cout << "P_JZG(0.6, 2) = " << P << "; NPT: rho = " << rho.mean << " +- " << rho.error
              << ", <P> = " << p_npt.mean << " +- " << p_npt.error << "\n"
              << "kappa_T: NPT fluctuations " << kappa_npt << " +- " << kappa.error
              << ", NVT slope " << kappa_nvt << " (dP/drho = " << slope << " +- " << slope_error
              << "), JZG " << kappa_jzg << "\n";
    EXPECT_NEAR(rho.mean, rho0, 0.006);
    EXPECT_NEAR(p_npt.mean, P, 0.05);
    EXPECT_NEAR(kappa_npt / kappa_nvt, 1.0, 0.25);
    EXPECT_NEAR(kappa_npt / kappa_jzg, 1.0, 0.25);
    EXPECT_NEAR(kappa_nvt / kappa_jzg, 1.0, 0.25);
}
