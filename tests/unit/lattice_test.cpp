// lattice_sites: exact count, every site inside the region, and no two sites closer
// than the lattice spacing allows (so particles of a diameter up to that never overlap,
// including across periodic boundaries); closed axes reach both ends of the region.
#include "pedesis/core/box.hpp"
#include "pedesis/core/error.hpp"
#include "pedesis/setup/lattice.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

using namespace pedesis;

namespace {

// Nearest-neighbour distance of an ideal lattice of the given kind at number density rho.
double ideal_spacing(LatticeKind kind, double rho) {
    switch (kind) {
    case LatticeKind::square:
        return 1.0 / std::sqrt(rho);
    case LatticeKind::hexagonal:
        return std::sqrt(2.0 / (std::sqrt(3.0) * rho));
    case LatticeKind::simple_cubic:
        return std::cbrt(1.0 / rho);
    case LatticeKind::fcc:
        return std::cbrt(4.0 / rho) / std::sqrt(2.0);
    }
    return 0.0;
}

template <int D>
void check_lattice(LatticeKind kind, const Vec<D>& lo, const Vec<D>& hi,
                   const std::array<bool, D>& closed, std::size_t n, double min_fraction) {
    SCOPED_TRACE("n = " + std::to_string(n) + " kind " + std::to_string(static_cast<int>(kind)));
    const auto sites = lattice_sites<D>(kind, lo, hi, closed, n);
    ASSERT_EQ(sites.size(), n);
    double volume = 1.0;
    Vec<D> L = hi - lo;
    std::array<bool, D> periodic;
    for (int a = 0; a < D; ++a) {
        volume *= L[a];
        periodic[a] = !closed[a];
    }
    for (const auto& r : sites) {
        for (int a = 0; a < D; ++a) {
            EXPECT_GE(r[a], lo[a] - 1e-12 * L[a]);
            if (closed[a]) {
                EXPECT_LE(r[a], hi[a] + 1e-12 * L[a]);
            } else {
                EXPECT_LT(r[a], hi[a]);
            }
        }
    }
    // distances (meaningful only once the lattice has many cells: a handful of sites in
    // a big region need not be spread evenly): minimum image over the open axes (the region tiles
    // with its images)
    Box<D> images(L, periodic);
    double dmin = INFINITY;
    for (std::size_t i = 0; i < n; ++i)
        for (std::size_t j = i + 1; j < n; ++j)
            dmin = std::min(dmin, norm(images.minimum_image(sites[i] - sites[j])));
    // on closed axes the outer sites sit on the boundary, so the effective density is
    // that of a slightly smaller region; compare with the spacing at the nominal density
    const double spacing = ideal_spacing(kind, static_cast<double>(n) / volume);
    if (n < 50) return;
    EXPECT_GE(dmin, min_fraction * spacing)
        << "closest pair " << dmin << " vs ideal spacing " << spacing;
}

} // namespace

TEST(Lattice, SquareAndHexagonal) {
    for (bool closed : {false, true}) {
        for (std::size_t n : {1u, 2u, 7u, 100u, 250u, 1000u, 1023u}) {
            check_lattice<2>(LatticeKind::square, Vec<2>{{-10.0, -10.0}}, Vec<2>{{10.0, 10.0}},
                             {closed, closed}, n, closed ? 0.6 : 0.85);
            check_lattice<2>(LatticeKind::hexagonal, Vec<2>{{-10.0, -5.0}}, Vec<2>{{10.0, 15.0}},
                             {closed, closed}, n, closed ? 0.6 : 0.85);
        }
        // elongated region
        check_lattice<2>(LatticeKind::hexagonal, Vec<2>{{0.0, 0.0}}, Vec<2>{{40.0, 5.0}},
                         {closed, !closed}, 300, 0.6);
    }
}

TEST(Lattice, CubicAndFcc) {
    for (bool closed : {false, true}) {
        for (std::size_t n : {1u, 4u, 27u, 100u, 500u, 864u}) {
            check_lattice<3>(LatticeKind::simple_cubic, Vec<3>::filled(-4.0), Vec<3>::filled(4.0),
                             {closed, closed, closed}, n, closed ? 0.5 : 0.8);
            check_lattice<3>(LatticeKind::fcc, Vec<3>::filled(-4.0), Vec<3>::filled(4.0),
                             {closed, closed, closed}, n, closed ? 0.5 : 0.8);
        }
    }
}

TEST(Lattice, PerfectLatticeHasIdealSpacing) {
    // 10 x 10 square sites in a periodic 10 x 10 region: spacing exactly 1
    auto sq = lattice_sites<2>(LatticeKind::square, Vec<2>{{-5.0, -5.0}}, Vec<2>{{5.0, 5.0}},
                               {false, false}, 100);
    Box<2> box(Vec<2>{{10.0, 10.0}}, {true, true});
    double dmin = INFINITY;
    for (std::size_t i = 0; i < sq.size(); ++i)
        for (std::size_t j = i + 1; j < sq.size(); ++j)
            dmin = std::min(dmin, norm(box.minimum_image(sq[i] - sq[j])));
    EXPECT_NEAR(dmin, 1.0, 1e-12);
    // 4 x 4 x 4 fcc cells in a periodic cube of edge 4: 256 sites, spacing sqrt(1/2)
    auto f = lattice_sites<3>(LatticeKind::fcc, Vec<3>::filled(-2.0), Vec<3>::filled(2.0),
                              {false, false, false}, 256);
    Box<3> cube(Vec<3>::filled(4.0), {true, true, true});
    dmin = INFINITY;
    for (std::size_t i = 0; i < f.size(); ++i)
        for (std::size_t j = i + 1; j < f.size(); ++j)
            dmin = std::min(dmin, norm(cube.minimum_image(f[i] - f[j])));
    EXPECT_NEAR(dmin, std::sqrt(0.5), 1e-12);
}

TEST(Lattice, ClosedAxesReachBothEnds) {
    // a full 10 x 10 square lattice on closed axes spans the region exactly
    auto s = lattice_sites<2>(LatticeKind::square, Vec<2>{{-4.5, -2.0}}, Vec<2>{{4.5, 7.0}},
                              {true, true}, 100);
    for (int a = 0; a < 2; ++a) {
        double mn = INFINITY, mx = -INFINITY;
        for (const auto& r : s) {
            mn = std::min(mn, r[a]);
            mx = std::max(mx, r[a]);
        }
        EXPECT_NEAR(mn, a == 0 ? -4.5 : -2.0, 1e-12);
        EXPECT_NEAR(mx, a == 0 ? 4.5 : 7.0, 1e-12);
    }
}

TEST(Lattice, NoOverlapForDenseDisksAndSpheres) {
    // unit-diameter particles at the packing fractions the physics tests use
    for (double eta : {0.2, 0.4, 0.6, 0.7}) {
        const std::size_t n = 900;
        const double L = std::sqrt(n * std::numbers::pi / 4.0 / eta);
        auto s = lattice_sites<2>(LatticeKind::hexagonal, Vec<2>::filled(-L / 2),
                                  Vec<2>::filled(L / 2), {false, false}, n);
        Box<2> box(Vec<2>::filled(L), {true, true});
        for (std::size_t i = 0; i < n; ++i)
            for (std::size_t j = i + 1; j < n; ++j)
                ASSERT_GE(norm(box.minimum_image(s[i] - s[j])), 1.0) << "eta " << eta;
    }
    for (double eta : {0.3, 0.45, 0.55}) {
        const std::size_t n = 500;
        const double L = std::cbrt(n * std::numbers::pi / 6.0 / eta);
        auto s = lattice_sites<3>(LatticeKind::fcc, Vec<3>::filled(-L / 2), Vec<3>::filled(L / 2),
                                  {false, false, false}, n);
        Box<3> box(Vec<3>::filled(L), {true, true, true});
        for (std::size_t i = 0; i < n; ++i)
            for (std::size_t j = i + 1; j < n; ++j)
                ASSERT_GE(norm(box.minimum_image(s[i] - s[j])), 1.0) << "eta " << eta;
    }
}

TEST(Lattice, BadInput) {
    EXPECT_THROW(lattice_sites<2>(LatticeKind::square, Vec<2>{{1.0, 0.0}}, Vec<2>{{1.0, 1.0}},
                                  {false, false}, 10),
                 InputError);
    EXPECT_THROW(parse_lattice("fcc", 2), InputError);
    EXPECT_THROW(parse_lattice("hexagonal", 3), InputError);
    EXPECT_EQ(parse_lattice("hexagonal", 2), LatticeKind::hexagonal);
    EXPECT_EQ(parse_lattice("fcc", 3), LatticeKind::fcc);
}
