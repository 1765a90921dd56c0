// NeighborList::needs_rebuild against brute force. The list may stay past the old rule
// (a particle moved more than skin/2), so what must hold is the rule's purpose: while
// it says "no rebuild", every pair now closer than r_cut is in the rows. Checked along
// random walks in periodic, walled and mixed boxes (with storage reorders between
// steps), and on a perfect lattice whose sites lie on the cell faces, where a pair is
// brought to a hair either side of the cutoff.
#include "pedesis/core/rng.hpp"
#include "pedesis/spatial/neighbor_list.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <numeric>
#include <set>
#include <string>
#include <utility>
#include <vector>

#include "support/random_positions.hpp"

using namespace pedesis;

namespace {

using Pair = std::pair<std::uint32_t, std::uint32_t>;

template <int D> std::set<Pair> rows_of(const NeighborList<D>& nl) {
    std::set<Pair> s;
    for (std::uint32_t i = 0; i < nl.size(); ++i)
        for (const std::uint32_t* p = nl.begin(i); p != nl.end(i); ++p)
            s.insert({std::min(i, *p), std::max(i, *p)});
    return s;
}

// A pair now closer than r_cut that the rows do not hold, by looking at every pair.
template <int D>
bool a_close_pair_is_missing(const Box<D>& box, const std::vector<Vec<D>>& pos,
                             const std::set<Pair>& rows, double r_cut) {
    for (std::uint32_t i = 0; i < pos.size(); ++i)
        for (std::uint32_t j = i + 1; j < pos.size(); ++j)
            if (norm2(box.minimum_image(pos[i] - pos[j])) < r_cut * r_cut && !rows.count({i, j}))
                return true;
    return false;
}

// Steps walked; of them, those where a pair within r_cut was unlisted (the rule must
// then ask for a rebuild), where the list stayed although the old rule would have
// rebuilt, and where it was rebuilt.
struct WalkCounts {
    int steps = 0, missing = 0, kept_past_half_skin = 0, rebuilds = 0;
};

// Random walks of every particle, steps of a sixth of the skin per axis (so that some
// pairs jump the skin between two checks); at each step the rule is asked, and
// obeyed. Every eighth step the storage is shuffled (the list follows with reorder).
template <int D>
WalkCounts walk(const Box<D>& box, std::size_t n, double r_cut, double skin, std::uint64_t seed) {
    auto pos = test::random_positions(box, n, seed, 4);
    NeighborList<D> nl(box, r_cut, skin);
    nl.build(pos);
    std::set<Pair> rows = rows_of(nl);
    WalkCounts c;
    for (std::uint32_t step = 0; step < 120; ++step) {
        for (std::size_t i = 0; i < n; ++i) {
            CounterRng rng(seed, RngStream::thermostat, static_cast<std::uint32_t>(i), step);
            for (int a = 0; a < D; ++a) {
                pos[i][a] += skin / 6.0 * rng.normal();
                // walls: reflected back into the box
                if (!box.periodic(a)) pos[i][a] = std::clamp(pos[i][a], box.lo(a), box.hi(a));
            }
            box.wrap(pos[i]);
        }
        if (step % 8 == 7) {
            std::vector<std::uint32_t> order(n);
            std::iota(order.begin(), order.end(), 0u);
            CounterRng rng(seed, RngStream::placement, 0, step);
            for (std::size_t k = n - 1; k > 0; --k)
                std::swap(order[k], order[static_cast<std::size_t>(rng.uniform(0.0, k + 1.0))]);
            std::vector<Vec<D>> shuffled(n);
            for (std::size_t k = 0; k < n; ++k) shuffled[k] = pos[order[k]];
            pos = shuffled;
            nl.reorder(order);
            rows = rows_of(nl);
        }
        ++c.steps;
        const bool rebuild = nl.needs_rebuild(pos);
        const bool missing = a_close_pair_is_missing(box, pos, rows, r_cut);
        c.missing += missing ? 1 : 0;
        if (missing && !rebuild) {
            ADD_FAILURE() << test::describe_box(box) << ", r_cut " << r_cut << ", skin " << skin
                          << ", seed " << seed << ", step " << step
                          << ": a pair within r_cut is missing and no rebuild is asked for";
        }
        if (!rebuild) {
            c.kept_past_half_skin += nl.moved_half_skin(pos) ? 1 : 0;
            continue;
        }
        nl.build(pos);
        rows = rows_of(nl);
        ++c.rebuilds;
    }
    return c;
}

template <int D> void check_walks(const std::vector<Box<D>>& boxes) {
    WalkCounts all;
    std::uint64_t seed = 11;
    for (const Box<D>& box : boxes)
        for (double r_cut : {1.0, 1.7})
            for (double skin : {0.3, 0.8}) {
                const WalkCounts c = walk(box, D == 2 ? 500 : 700, r_cut, skin, ++seed);
                all.steps += c.steps;
                all.kept_past_half_skin += c.kept_past_half_skin;
                all.rebuilds += c.rebuilds;
                all.missing += c.missing;
            }
    // the walks exercised both sides of the rule: lists kept past the old skin/2 rule,
    // and pairs that did come within r_cut unlisted (each a rebuild asked for)
    EXPECT_GT(all.kept_past_half_skin, all.steps / 10) << all.steps << " steps";
    EXPECT_GT(all.missing, all.steps / 20) << all.steps << " steps";
    EXPECT_GE(all.rebuilds, all.missing);
}

TEST(NeighborListRebuild, NoPairWithinTheCutoffIsMissingAlongRandomWalks2D) {
    check_walks<2>({Box<2>(Vec<2>{{14.0, 14.0}}, {true, true}),
                    Box<2>(Vec<2>{{14.0, 9.0}}, {true, false}),
                    Box<2>(Vec<2>{{12.0, 12.0}}, {false, false})});
}

TEST(NeighborListRebuild, NoPairWithinTheCutoffIsMissingAlongRandomWalks3D) {
    check_walks<3>({Box<3>(Vec<3>{{8.0, 8.0, 8.0}}, {true, true, true}),
                    Box<3>(Vec<3>{{8.0, 8.0, 7.0}}, {true, true, false})});
}

// A square lattice of spacing 1 with r_list = 2 (sites on the cell faces), r_cut 1.5,
// skin 0.5. Sites i and j at distance sqrt(5) (not list partners) move toward each
// other by delta each, more than skin/2 and less than the skin: their pair comes within
// r_cut when 2 delta > sqrt(5) - 1.5, and no other pair comes that near.
TEST(NeighborListRebuild, APairOnALatticeIsCaughtAtTheCutoff) {
    const int n = 8;
    const Box<2> box(Vec<2>{{double(n), double(n)}}, {true, true});
    std::vector<Vec<2>> pos;
    for (int y = 0; y < n; ++y)
        for (int x = 0; x < n; ++x) pos.push_back(Vec<2>{{x - 0.5 * n, y - 0.5 * n}});
    const double r_cut = 1.5, skin = 0.5;
    NeighborList<2> nl(box, r_cut, skin);
    nl.build(pos);
    const std::size_t i = 3 * n + 3, j = 4 * n + 5; // (3, 3) and (5, 4)
    const Vec<2> toward = (1.0 / std::sqrt(5.0)) * (pos[j] - pos[i]);
    for (double gap : {-1e-7, 1e-7}) {
        const double delta = 0.5 * (std::sqrt(5.0) - (r_cut + gap));
        auto moved = pos;
        moved[i] += delta * toward;
        moved[j] -= delta * toward;
        SCOPED_TRACE("the pair at r_cut " + std::string(gap < 0 ? "- " : "+ ") + "1e-7");
        ASSERT_GT(delta, 0.5 * skin);
        ASSERT_LT(delta, skin);
        EXPECT_TRUE(nl.moved_half_skin(moved)) << "the old rule would rebuild";
        EXPECT_EQ(nl.needs_rebuild(moved), gap < 0);
        EXPECT_EQ(a_close_pair_is_missing(box, moved, rows_of(nl), r_cut), gap < 0);
    }
}

TEST(NeighborListRebuild, FarMovesManyMoversAndBadPositionsRebuild) {
    const Box<2> box(Vec<2>{{20.0, 20.0}}, {true, true});
    const auto pos = test::random_positions(box, 400, 5, 4);
    const double skin = 0.4;
    NeighborList<2> nl(box, 1.0, skin);
    nl.build(pos);
    EXPECT_FALSE(nl.needs_rebuild(pos));

    // one particle 0.6 of the skin away from where it was, far from every other: kept
    auto lone = pos;
    lone.push_back(Vec<2>{{0.0, 0.0}});
    for (std::size_t k = 0; k < pos.size(); ++k)
        if (norm2(box.minimum_image(pos[k])) < 4.0 * 4.0) lone[k] += Vec<2>{{8.0, 8.0}};
    for (auto& r : lone) box.wrap(r);
    nl.build(lone);
    auto moved = lone;
    moved.back()[0] += 0.6 * skin;
    EXPECT_TRUE(nl.moved_half_skin(moved));
    EXPECT_FALSE(nl.needs_rebuild(moved));
    // the same particle more than the skin away (the bound image_free_margin relies on)
    moved.back()[0] = lone.back()[0] + 1.01 * skin;
    EXPECT_TRUE(nl.needs_rebuild(moved));

    // every particle moved by 0.6 of the skin alike: no pair changes, but too many
    // moved to check one by one
    auto all = lone;
    for (auto& r : all) {
        r[1] += 0.6 * skin;
        box.wrap(r);
    }
    EXPECT_TRUE(nl.needs_rebuild(all));

    auto bad = lone;
    bad[7][0] = std::numeric_limits<double>::quiet_NaN();
    EXPECT_TRUE(nl.needs_rebuild(bad));
}

} // namespace
