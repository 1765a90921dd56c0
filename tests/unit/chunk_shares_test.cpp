// ChunkShares (core/chunk_shares.hpp): every item exactly once, whatever the team's size
// against the prepared one, and a slow thread's share finished by the others.
#include "pedesis/core/chunk_shares.hpp"

#include <gtest/gtest.h>
#include <omp.h>

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
        // chunks start on the grain and are at most one grain long
        if (first % grain != 0 || last - first > grain || last <= first) ++misaligned;
        for (std::int64_t i = first; i < last; ++i) ++hits[static_cast<std::size_t>(i)];
    }
    int items_not_once() const {
        int wrong = 0;
        for (const auto& h : hits) wrong += h.load() != 1;
        return wrong;
    }
};

// Prepared for `prepared` threads, run by a team of `team` (more, fewer, or as many).
void expect_each_item_once(std::int64_t items, std::int64_t grain, int prepared, int team) {
    Coverage seen(items);
    const int saved = omp_get_max_threads();
    omp_set_num_threads(prepared);
    ChunkShares shares(items, grain);
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

// Thread 0 stalls in its first chunk (as a core slowed by a neighbour would): thread 1
// finishes its own share and then takes the rest of thread 0's from the far end, so
// thread 0 ends with its first chunk only. (Under schedule(static) it would do half.)
TEST(ChunkShares, AStalledThreadsShareIsTakenOver) {
    const std::int64_t items = 64;
    const int saved = omp_get_max_threads();
    omp_set_num_threads(2);
    ChunkShares shares(items, 1);
    omp_set_num_threads(saved);
    std::vector<std::atomic<int>> by(static_cast<std::size_t>(items));
    std::atomic<int> second_done{0};
    int team = 0;
#pragma omp parallel num_threads(2)
    {
#pragma omp single
        team = omp_get_num_threads();
        const int me = omp_get_thread_num();
        shares.run([&](std::int64_t first, std::int64_t) {
            by[static_cast<std::size_t>(first)] = me + 1;
            // thread 0 waits in its first chunk (10 s at most) until thread 1 has done
            // everything else
            if (me == 0 && team == 2 && first == 0)
                for (int k = 0; k < 10000 && second_done.load() < items - 1; ++k)
                    std::this_thread::sleep_for(std::chrono::milliseconds(1));
            if (me == 1) ++second_done;
        });
    }
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

} // namespace
} // namespace pedesis
