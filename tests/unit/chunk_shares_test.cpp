// ChunkShares (core/chunk_shares.hpp): every item exactly once, whatever the team's size
// against the prepared one and whatever the layout; a slow thread's share finished by the
// others; each thread starting on the shares a layout gives it.
#include "pedesis/core/chunk_shares.hpp"

#include <gtest/gtest.h>
#include <omp.h>

#include <array>
#include <atomic>
#include <chrono>
#include <cstdint>
#include <thread>
#include <vector>

namespace pedesis {
namespace {

struct Coverage {
    std::vector<std::atomic<int>> hits;
    std::atomic<int> misaligned{0};
    explicit Coverage(std::int64_t n) : hits(static_cast<std::size_t>(n)) {}
    void take(std::int64_t first, std::int64_t last, std::int64_t grain) {
        // chunks are at most one grain long and never empty
        if (last - first > grain || last <= first) ++misaligned;
        for (std::int64_t i = first; i < last; ++i) ++hits[static_cast<std::size_t>(i)];
    }
    int items_not_once() const {
        int wrong = 0;
        for (const auto& h : hits) wrong += h.load() != 1;
        return wrong;
    }
};

// Prepared for `prepared` threads, run by a team of `team` (more, fewer, or as many).
void expect_each_item_once(std::int64_t items, std::int64_t grain, int prepared, int team,
                           const std::vector<std::int64_t>& bounds = {}) {
    Coverage seen(items);
    const int saved = omp_get_max_threads();
    omp_set_num_threads(prepared);
    ChunkShares shares(items, grain, 1, bounds);
    omp_set_num_threads(saved);
#pragma omp parallel num_threads(team)
    shares.run([&](std::int64_t first, std::int64_t last) { seen.take(first, last, grain); });
    EXPECT_EQ(seen.items_not_once(), 0)
        << items << " items, grain " << grain << ", prepared " << prepared << ", team " << team;
    EXPECT_EQ(seen.misaligned.load(), 0) << items << " items, grain " << grain;
}

TEST(ChunkShares, EveryItemOnceForEveryTeamSize) {
    for (std::int64_t items : {0, 1, 2, 5, 255, 256, 257, 1023, 1024, 1025, 10007})
        for (std::int64_t grain : {1, 3, 4, 256, 1024, 100000})
            for (int prepared : {1, 2, 3, 5})
                for (int team : {1, 2, 3, 5}) expect_each_item_once(items, grain, prepared, team);
}

TEST(ChunkShares, EveryItemOnceForEveryLayout) {
    // two threads' layouts of 64 items in 1, 2 and 3 rounds, with empty shares; and
    // layouts that do not fit (equal shares then)
    const std::vector<std::vector<std::int64_t>> layouts = {
        {0, 64, 64},
        {0, 0, 64},
        {0, 10, 30, 40, 64},
        {0, 0, 0, 0, 64},
        {0, 5, 5, 6, 60, 64, 64},
        {0, 64},
        {0, 30, 20, 64},
        {1, 30, 64},
        {0, 30, 63},
        {0, 10, 20, 64},
        {},
    };
    for (const auto& bounds : layouts)
        for (std::int64_t grain : {1, 3, 64})
            for (int team : {1, 2, 3}) expect_each_item_once(64, grain, 2, team, bounds);
}

TEST(ChunkShares, OutsideARegionOneCallerTakesEverything) {
    const int saved = omp_get_max_threads();
    omp_set_num_threads(4);
    Coverage seen(1000);
    ChunkShares shares(1000, 7);
    shares.run([&](std::int64_t first, std::int64_t last) { seen.take(first, last, 7); });
    omp_set_num_threads(saved);
    EXPECT_EQ(seen.items_not_once(), 0);
    EXPECT_EQ(seen.misaligned.load(), 0);
}

TEST(ChunkShares, NoChunksForNoItems) {
    int calls = 0;
    ChunkShares shares(0, 16);
    shares.run([&](std::int64_t, std::int64_t) { ++calls; });
    EXPECT_EQ(calls, 0);
}

// Waits until done() (checked every millisecond), 10 s at most.
template <class Done> void wait_for(Done&& done) {
    for (int k = 0; k < 10000 && !done(); ++k)
        std::this_thread::sleep_for(std::chrono::milliseconds(1));
}

// ChunkShares prepared for two threads (bounds as in its constructor).
ChunkShares shares_for_two(std::int64_t units, std::int64_t per_item,
                           const std::vector<std::int64_t>& bounds) {
    const int saved = omp_get_max_threads();
    omp_set_num_threads(2);
    ChunkShares shares(units, 1, per_item, bounds);
    omp_set_num_threads(saved);
    return shares;
}

// shares.run on a team of two, body(thread, first, last, team) for each chunk; the team's
// size (2 unless the runtime gave fewer).
template <class Body> int run_on_two(ChunkShares& shares, Body&& body) {
    int team = 0;
#pragma omp parallel num_threads(2)
    {
#pragma omp single
        team = omp_get_num_threads();
        const int me = omp_get_thread_num();
        shares.run([&](std::int64_t first, std::int64_t last) { body(me, first, last, team); });
    }
    return team;
}

// Thread 0 stalls in its first chunk (as a core slowed by a neighbour would): thread 1
// finishes its own share and then takes the rest of thread 0's from the far end, so
// thread 0 ends with its first chunk only. (Under schedule(static) it would do half.)
TEST(ChunkShares, AStalledThreadsShareIsTakenOver) {
    const std::int64_t items = 64;
    ChunkShares shares = shares_for_two(items, 1, {});
    std::vector<std::atomic<int>> by(static_cast<std::size_t>(items));
    std::atomic<int> second_done{0};
    std::atomic<bool> first_began{false};
    const int team = run_on_two(shares, [&](int me, std::int64_t first, std::int64_t, int size) {
        by[static_cast<std::size_t>(first)] = me + 1;
        if (size != 2) return;
        // thread 0 stalls in its first chunk until thread 1 has done everything else;
        // thread 1 begins only once thread 0 holds that chunk (on a loaded machine
        // thread 0 may start late, and thread 1 would take its whole share)
        if (me == 0 && !first_began.exchange(true))
            wait_for([&] { return second_done.load() >= items - 1; });
        if (me == 1) {
            if (second_done.load() == 0) wait_for([&] { return first_began.load(); });
            ++second_done;
        }
    });
    ASSERT_EQ(team, 2);
    int by_first = 0, by_second = 0;
    for (const auto& b : by) {
        by_first += b.load() == 1;
        by_second += b.load() == 2;
    }
    EXPECT_EQ(by_first, 1);
    EXPECT_EQ(by_second, items - 1);
    EXPECT_EQ(by.front().load(), 1); // thread 0 started on its own share's front
}

// The order in which each of two threads takes items, one at a time. The first `head`
// items of thread 0 and the first item of thread 1 are taken before either thread can
// help the other: thread 1 waits in its first item until thread 0 has taken `head`, and
// thread 0 after its `head`-th until thread 1 has begun (10 s at most each).
std::array<std::vector<std::int64_t>, 2> orders_of_two(ChunkShares& shares, std::size_t head) {
    std::array<std::vector<std::int64_t>, 2> taken;
    std::atomic<std::size_t> first_count{0};
    std::atomic<bool> second_began{false};
    const int team =
        run_on_two(shares, [&](int me, std::int64_t first, std::int64_t last, int size) {
            for (std::int64_t i = first; i < last; ++i) {
                taken[static_cast<std::size_t>(me)].push_back(i);
                if (size != 2) continue;
                if (me == 1 && !second_began.exchange(true))
                    wait_for([&] { return first_count.load() >= head; });
                if (me == 0 && ++first_count == head) wait_for([&] { return second_began.load(); });
            }
        });
    EXPECT_EQ(team, 2);
    return taken;
}

// Thread 0 owns [0, 10) and [30, 40), thread 1 [10, 30) and [40, 64): each starts on its
// own, in order, before it helps the other.
TEST(ChunkShares, ALayoutsThreadsStartOnTheirOwnShares) {
    ChunkShares shares = shares_for_two(64, 1, {0, 10, 30, 40, 64});
    EXPECT_EQ(shares.rounds(), 2);
    const auto taken = orders_of_two(shares, 20);
    std::vector<std::int64_t> own0;
    for (std::int64_t i = 0; i < 10; ++i) own0.push_back(i);
    for (std::int64_t i = 30; i < 40; ++i) own0.push_back(i);
    ASSERT_GE(taken[0].size(), own0.size());
    EXPECT_EQ(std::vector<std::int64_t>(taken[0].begin(), taken[0].begin() + 20), own0);
    // thread 0 then helps from the far end of thread 1's first share
    if (taken[0].size() > 20) {
        EXPECT_EQ(taken[0][20], 29);
    }
    ASSERT_FALSE(taken[1].empty());
    EXPECT_EQ(taken[1].front(), 10);
}

// Bounds in particles, 64 to an item: rounded to the nearest item. Bounds that do not fit
// (made for three threads) give the equal split.
TEST(ChunkShares, LayoutsInUnitsOfPartsOfAnItem) {
    ChunkShares rounded = shares_for_two(200, 64, {0, 100, 200}); // items 0-1 and 2-3
    const auto taken = orders_of_two(rounded, 2);
    ASSERT_GE(taken[0].size(), 2u);
    EXPECT_EQ(taken[0][0], 0);
    EXPECT_EQ(taken[0][1], 1);
    ASSERT_FALSE(taken[1].empty());
    EXPECT_EQ(taken[1].front(), 2);
    ChunkShares stale = shares_for_two(640, 64, {0, 100, 200, 640}); // 10 items
    EXPECT_EQ(stale.rounds(), 1);
    const auto equal = orders_of_two(stale, 5);
    ASSERT_FALSE(equal[1].empty());
    EXPECT_EQ(equal[1].front(), 5);
}

} // namespace
} // namespace pedesis
