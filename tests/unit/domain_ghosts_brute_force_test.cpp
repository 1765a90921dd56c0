// The MPI ghost sets of DomainDecomposition against an O(N^2) minimum-image scan, with
// 2 to 8 processes faked by threads (support/thread_communicator.hpp). After scatter
// and redistribute, and again after the particles have moved (up to skin / 2, and a few
// across the box) and been redistributed: the owned sets partition the particles and
// each lies in its process's domain; each process holds as ghosts every particle of
// another domain within `range` of its own (minimum image), none beyond range along any
// axis, none twice, each a bitwise copy of its owner's; and the neighbour list each
// process builds on its local_box from local_positions holds every pair within the
// list range that involves one of its particles. Geometries: sc, fcc, square and
// hexagonal lattices and random positions with particles on the domain faces (exactly
// and a ulp either side), at -L/2 and one ulp inside +L/2, partners a ulp either side of
// the range across them; boxes whose domains are exactly the range wide and a ulp
// either side; rectangular boxes; 1 and 2 OpenMP threads per process on a case large
// enough to use them. Every failure names its case.
#include "pedesis/soft/domain_decomposition.hpp"
#include "pedesis/spatial/neighbor_list.hpp"

#include <gtest/gtest.h>
#include <omp.h>

#include <algorithm>
#include <map>
#include <mutex>
#include <random>
#include <string>
#include <vector>

#include "support/face_pairs.hpp"
#include "support/lattices.hpp"
#include "support/pair_sets.hpp"
#include "support/random_positions.hpp"
#include "support/thread_communicator.hpp"

using namespace pedesis;
using test::PairSet;

namespace {

// What one process holds after a redistribute, by tag.
template <int D> struct Held {
    std::array<int, D> grid{};
    std::vector<std::uint32_t> owned, ghosts;
    std::map<std::uint32_t, Vec<D>> where; // tag -> position held (owned and ghosts)
    PairSet local_pairs;                   // the local neighbour list, as tag pairs
};

template <int D> struct Case {
    std::string name;
    Box<D> box;
    std::vector<Vec<D>> pos;
    double r_cut, skin;
    int processes, threads = 1;
    std::uint64_t seed;
};

// Displacement of a particle by tag: up to skin / 2 on each axis; every 50th particle
// goes half a box away (a migration past the neighbouring domains).
template <int D> Vec<D> displacement(const Case<D>& c, std::uint32_t tag) {
    std::mt19937_64 gen(c.seed * 1000003u + tag);
    Vec<D> d;
    for (int a = 0; a < D; ++a) {
        const double h = tag % 50 == 7 ? 0.5 * c.box.length(a) : 0.5 * c.skin / std::sqrt(D);
        d[a] = std::uniform_real_distribution<double>(-h, h)(gen);
    }
    return d;
}

template <int D> SoftState<D> whole_state(const Case<D>& c, const std::vector<Vec<D>>& pos) {
    SoftState<D> s;
    s.box = c.box;
    s.resize(pos.size());
    s.p.species_table = {Species{"A", 0.5, 1.0}};
    for (std::size_t i = 0; i < pos.size(); ++i) {
        s.p.position[i] = pos[i];
        s.p.tag[i] = static_cast<std::uint32_t>(i);
        s.director[i][0] = 1.0;
    }
    return s;
}

// Runs the decomposition on c.processes threads: two redistributes, the particles
// moved between them. Returns what each process held after each.
template <int D> std::array<std::vector<Held<D>>, 2> decompose(const Case<D>& c) {
    const double range = c.r_cut + c.skin;
    std::array<std::vector<Held<D>>, 2> held;
    for (auto& h : held) h.resize(static_cast<std::size_t>(c.processes));
    test::run_processes(c.processes, [&](Communicator& comm) {
        omp_set_num_threads(c.threads);
        DomainDecomposition<D> dd(comm, c.box, range);
        SoftState<D> s = whole_state(c, c.pos);
        dd.scatter(s);
        NeighborList<D> nl(dd.local_box(c.skin), c.r_cut, c.skin);
        std::vector<Vec<D>> local;
        for (int phase = 0; phase < 2; ++phase) {
            if (phase == 1)
                for (std::size_t i = 0; i < s.owned(); ++i) {
                    s.p.position[i] += displacement(c, s.p.tag[i]);
                    c.box.wrap(s.p.position[i]);
                }
            dd.redistribute(s);
            dd.local_positions(s.p.position, local, c.skin);
            nl.build(local);
            Held<D>& h =
                held[static_cast<std::size_t>(phase)][static_cast<std::size_t>(comm.rank())];
            h.grid = dd.grid();
            for (std::size_t i = 0; i < s.size(); ++i) {
                (i < s.owned() ? h.owned : h.ghosts).push_back(s.p.tag[i]);
                h.where[s.p.tag[i]] = s.p.position[i];
            }
            for (std::uint32_t i = 0; i < nl.size(); ++i)
                for (const std::uint32_t* p = nl.begin(i); p != nl.end(i); ++p)
                    h.local_pairs.push_back(
                        {std::min(s.p.tag[i], s.p.tag[*p]), std::max(s.p.tag[i], s.p.tag[*p])});
            std::sort(h.local_pairs.begin(), h.local_pairs.end());
        }
    });
    return held;
}

// Domain coordinates of a process, as the decomposition numbers them.
template <int D> std::array<int, D> domain_of_rank(int rank, const std::array<int, D>& grid) {
    std::array<int, D> c;
    for (int a = 0; a < D; ++a) {
        c[a] = rank % grid[a];
        rank /= grid[a];
    }
    return c;
}

// Per-axis distance from x to slab c of n along a periodic axis (0 inside).
inline double slab_distance(double x, int c, int n, double L) {
    if (n == 1) return 0.0;
    const double w = L / n, lo = -0.5 * L + c * w, hi = lo + w;
    double best = 1e300;
    for (int k = -1; k <= 1; ++k) {
        const double y = x + k * L;
        best = std::min(best, y < lo ? lo - y : y > hi ? y - hi : 0.0);
    }
    return best;
}

template <int D>
void check_phase(const Case<D>& c, const std::vector<Vec<D>>& pos, const std::vector<Held<D>>& held,
                 const std::string& label) {
    const double range = c.r_cut + c.skin, r_list = range;
    // Within a relative 1e-12 of the range either answer is right, as for NeighborList's
    // list_rounding: the decomposition wraps and shifts coordinates (each rounding by an
    // ulp of L), so a distance that close to the range has no exact side.
    const double inner_range = range * (1.0 - 1e-12);
    const std::size_t n = pos.size();
    const std::array<int, D> grid = held[0].grid;
    // owned sets partition the particles, each in its own domain
    std::vector<int> owner(n, -1);
    for (int q = 0; q < c.processes; ++q) {
        const auto& h = held[static_cast<std::size_t>(q)];
        EXPECT_EQ(h.grid, grid) << label;
        const auto dom = domain_of_rank<D>(q, grid);
        for (std::uint32_t t : h.owned) {
            ASSERT_LT(t, n) << label;
            EXPECT_EQ(owner[t], -1) << label << ": particle " << t << " owned by processes "
                                    << owner[t] << " and " << q;
            owner[t] = q;
            for (int a = 0; a < D; ++a)
                EXPECT_LE(slab_distance(pos[t][a], dom[a], grid[a], c.box.length(a)),
                          1e-12 * c.box.length(a))
                    << label << ": particle " << t << " at " << test::exact(pos[t])
                    << " owned by process " << q << " outside its domain along axis " << a;
            EXPECT_EQ(h.where.at(t), pos[t]) << label << ": particle " << t << " moved";
        }
    }
    for (std::size_t t = 0; t < n; ++t)
        EXPECT_NE(owner[t], -1) << label << ": particle " << t << " owned by no process";
    // ghosts: every particle within range of the domain, none beyond it on an axis
    for (int q = 0; q < c.processes; ++q) {
        const auto& h = held[static_cast<std::size_t>(q)];
        const auto dom = domain_of_rank<D>(q, grid);
        std::vector<int> copies(n, 0);
        for (std::uint32_t t : h.ghosts) {
            ASSERT_LT(t, n) << label;
            ++copies[t];
            EXPECT_NE(owner[t], q)
                << label << ": process " << q << " holds its own particle " << t << " as a ghost";
            EXPECT_EQ(h.where.at(t), pos[t])
                << label << ": ghost " << t << " differs from its owner's";
        }
        std::size_t missing = 0, extra = 0, twice = 0;
        std::string first;
        for (std::uint32_t t = 0; t < n; ++t) {
            if (owner[t] == q) continue;
            double d2 = 0.0, widest = 0.0;
            for (int a = 0; a < D; ++a) {
                const double d = slab_distance(pos[t][a], dom[a], grid[a], c.box.length(a));
                d2 += d * d;
                widest = std::max(widest, d);
            }
            twice += copies[t] > 1;
            if (d2 < inner_range * inner_range && copies[t] == 0 && missing++ == 0)
                first = "particle " + std::to_string(t) + " at " + test::exact(pos[t]) + ", " +
                        test::exact(std::sqrt(d2)) + " from the domain of process " +
                        std::to_string(q);
            extra += copies[t] > 0 && widest > range * (1.0 + 1e-12);
        }
        EXPECT_EQ(missing, 0u) << label << ": " << missing << " ghosts missing, the first "
                               << first;
        EXPECT_EQ(extra, 0u) << label << ": process " << q << " holds ghosts beyond range";
        EXPECT_EQ(twice, 0u) << label << ": process " << q << " holds a particle twice";
    }
    // each process's list: every pair within r_list (less the band) that involves one of
    // its particles, none beyond it (plus the band)
    const PairSet all = test::brute_pairs_within(c.box, pos, r_list * (1.0 - 1e-12));
    const PairSet outer = test::brute_pairs_within(c.box, pos, r_list * (1.0 + 1e-12));
    for (int q = 0; q < c.processes; ++q) {
        const auto& h = held[static_cast<std::size_t>(q)];
        PairSet mine;
        for (const auto& pr : all)
            if (owner[pr.first] == q || owner[pr.second] == q) mine.push_back(pr);
        EXPECT_TRUE(test::minus(mine, h.local_pairs).empty())
            << label << ", process " << q << ": "
            << test::describe_pairs(test::minus(mine, h.local_pairs), "missing from its list",
                                    c.box, pos);
        EXPECT_TRUE(test::minus(h.local_pairs, outer).empty())
            << label << ", process " << q << ": "
            << test::describe_pairs(test::minus(h.local_pairs, outer), "listed beyond r_list",
                                    c.box, pos);
    }
}

template <int D> void check_case(const Case<D>& c) {
    const std::string label =
        c.name + ", " + test::exact_box(c.box) + ", r_cut " + test::exact(c.r_cut) + ", skin " +
        test::exact(c.skin) + ", " + std::to_string(c.processes) + " processes, " +
        std::to_string(c.threads) + " threads, seed " + std::to_string(c.seed);
    const auto held = decompose(c);
    check_phase(c, c.pos, held[0], label + ", scattered");
    std::vector<Vec<D>> moved = c.pos;
    for (std::size_t i = 0; i < moved.size(); ++i) {
        moved[i] += displacement(c, static_cast<std::uint32_t>(i));
        c.box.wrap(moved[i]);
    }
    check_phase(c, moved, held[1], label + ", moved");
}

// A box of `whole[a]` ranges per axis (nudged by a ulp), the grid the decomposition
// picks, and positions: a lattice or uniform, plus pairs on the domain faces.
template <int D> int check_geometries(int cases, std::uint64_t seed0) {
    int checked = 0;
    for (int k = 0; k < cases; ++k) {
        const std::uint64_t seed = seed0 + static_cast<std::uint64_t>(k);
        std::mt19937_64 gen(seed);
        const int processes = 2 + static_cast<int>(gen() % 7);
        const double r_cut = std::uniform_real_distribution<double>(0.8, 2.5)(gen);
        const double skin = std::array<double, 4>{0.0, 0.1, 0.4, 1.5 * r_cut}[gen() % 4];
        const double range = r_cut + skin;
        const int nudge = static_cast<int>(gen() % 3) - 1;
        Vec<D> L;
        // a ulp short of 2 ranges the list itself refuses a periodic axis: 3 or more
        const int fewest = nudge < 0 ? 3 : 2;
        for (int a = 0; a < D; ++a)
            L[a] = test::nudged((fewest + static_cast<double>(gen() % (D == 2 ? 7 : 4))) * range,
                                nudge);
        std::array<bool, D> periodic;
        periodic.fill(true);
        Box<D> box(L, periodic);
        std::array<int, D> grid;
        try {
            grid = domain_grid<D>(processes, box, range);
        } catch (const InputError&) {
            continue; // no grid of domains a range wide: the decomposition refuses it
        }
        std::vector<Vec<D>> pos;
        std::string what;
        if (k % 2 == 0) {
            const auto kind = test::lattice_kinds<D>()[static_cast<std::size_t>(k / 2) % 2];
            // sites on the domain faces when L is exact: sc, square and hexagonal of spacing
            // range / 2, fcc of cube edge range (4 sites per range^3, not 32)
            Vec<D> edge =
                test::unit_cell<D>(kind, kind == test::LatticeKind::fcc ? range : 0.5 * range);
            std::array<int, D> cells;
            for (int a = 0; a < D; ++a) cells[a] = static_cast<int>(std::ceil(L[a] / edge[a]));
            pos = test::lattice_sites(box, kind, cells, edge);
            what = test::lattice_name(kind, D) + " lattice";
        } else {
            pos = test::random_positions(
                box, static_cast<std::size_t>(1.5 * box.volume() / std::pow(range, D)), seed, 4);
            what = "uniform";
        }
        test::add_face_pairs(box, grid, 30, test::near_reach(range), gen, pos);
        check_case(Case<D>{what + " with pairs on domain faces", box, pos, r_cut, skin, processes,
                           1, seed});
        ++checked;
    }
    return checked;
}

TEST(DomainGhostsBruteForce, Geometries2D) {
    const int n = check_geometries<2>(120, 100);
    EXPECT_GT(n, 80);
    RecordProperty("cases", n);
}

TEST(DomainGhostsBruteForce, Geometries3D) {
    const int n = check_geometries<3>(100, 700);
    EXPECT_GT(n, 50);
    RecordProperty("cases", n);
}

// Enough particles per process (2000, tens of thousands of list entries: several of the list's
// chunks of 4096 entries) that the list build runs threaded: the same sets with 1 and 2
// threads.
TEST(DomainGhostsBruteForce, OneAndTwoThreadsPerProcess) {
    const Box<2> box(Vec<2>{{64.0, 32.0}}, {true, true});
    std::mt19937_64 gen(5);
    auto pos = test::random_positions(box, 4000, 5, 6);
    test::add_face_pairs(box, std::array<int, 2>{2, 1}, 100, test::near_reach(3.0), gen, pos);
    for (int threads : {1, 2})
        check_case(Case<2>{"uniform, 2 domains of 2000", box, pos, 2.5, 0.5, 2, threads, 5});
}

} // namespace
