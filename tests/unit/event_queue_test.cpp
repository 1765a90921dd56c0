// EventQueue: the top is always the (time, index) minimum of a reference array under
// random updates, and draining the queue yields the reference's sorted order.
#include "pedesis/core/rng.hpp"
#include "pedesis/event/event_queue.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <limits>
#include <numeric>
#include <vector>

using namespace pedesis;

namespace {

constexpr double inf = std::numeric_limits<double>::infinity();

std::uint32_t reference_top(const std::vector<double>& t) {
    std::uint32_t best = 0;
    for (std::uint32_t i = 1; i < t.size(); ++i)
        if (t[i] < t[best]) best = i; // strict: the lowest index wins ties
    return best;
}

// times drawn from a small set of values so that ties are frequent, plus infinities
double random_time(CounterRng& rng, bool coarse) {
    const double u = rng.uniform();
    if (u < 0.05) return inf;
    const double x = rng.uniform(0.0, 100.0);
    return coarse ? std::floor(x / 10.0) : x;
}

} // namespace

TEST(EventQueue, SingleElement) {
    EventQueue q;
    q.build({3.0});
    EXPECT_FALSE(q.empty());
    EXPECT_EQ(q.top(), 0u);
    EXPECT_EQ(q.top_time(), 3.0);
    q.update(0, 1.0);
    EXPECT_EQ(q.top_time(), 1.0);
    q.update(0, inf);
    EXPECT_EQ(q.top_time(), inf);
}

TEST(EventQueue, TopMatchesReferenceUnderRandomUpdates) {
    for (bool coarse : {false, true}) {
        for (std::uint32_t n : {1u, 2u, 3u, 7u, 64u, 1000u}) {
            CounterRng rng(7 + n, RngStream::placement, coarse);
            std::vector<double> t(n);
            for (auto& x : t) x = random_time(rng, coarse);
            EventQueue q;
            q.build(t);
            for (int step = 0; step < 20000; ++step) {
                const std::uint32_t who = reference_top(t);
                ASSERT_EQ(q.top(), who) << "n " << n << " step " << step;
                ASSERT_EQ(q.top_time(), t[who]);
                // update either the top (as the engine does) or anyone else
                const std::uint32_t k =
                    rng.uniform() < 0.5 ? who : static_cast<std::uint32_t>(rng.uniform() * n) % n;
                t[k] = random_time(rng, coarse);
                q.update(k, t[k]);
            }
        }
    }
}

TEST(EventQueue, DrainsInSortedOrder) {
    for (bool coarse : {false, true}) {
        const std::uint32_t n = 500;
        CounterRng rng(99, RngStream::placement, coarse);
        std::vector<double> t(n);
        for (auto& x : t) x = random_time(rng, coarse);
        EventQueue q;
        q.build(t);
        // scramble with some updates first
        for (int step = 0; step < 2000; ++step) {
            const auto k = static_cast<std::uint32_t>(rng.uniform() * n) % n;
            t[k] = random_time(rng, coarse);
            q.update(k, t[k]);
        }
        std::vector<std::uint32_t> expected(n);
        std::iota(expected.begin(), expected.end(), 0u);
        std::stable_sort(expected.begin(), expected.end(),
                         [&](std::uint32_t a, std::uint32_t b) { return t[a] < t[b]; });
        // drain: take the top and push it past everything (a time larger than all)
        std::vector<std::uint32_t> got;
        for (std::uint32_t k = 0; k < n; ++k) {
            if (q.top_time() >= 1e300) break; // only drained or infinite events left
            got.push_back(q.top());
            q.update(q.top(), 1e300);
        }
        expected.resize(got.size());
        EXPECT_EQ(got, expected);
        for (std::uint32_t k : expected) EXPECT_NE(t[k], inf);
    }
}

TEST(EventQueue, OrderIndependentOfHistory) {
    // Two queues reaching the same times by different update histories agree on the top
    // at every step of a common continuation (needed for bit-for-bit restarts).
    const std::uint32_t n = 300;
    CounterRng rng(5, RngStream::placement, 0);
    std::vector<double> t(n);
    for (auto& x : t) x = random_time(rng, true);
    EventQueue a;
    a.build(t);
    for (int step = 0; step < 3000; ++step) {
        const auto k = static_cast<std::uint32_t>(rng.uniform() * n) % n;
        t[k] = random_time(rng, true);
        a.update(k, t[k]);
    }
    EventQueue b;
    b.build(t);
    for (int step = 0; step < 3000; ++step) {
        ASSERT_EQ(a.top(), b.top());
        ASSERT_EQ(a.top_time(), b.top_time());
        const std::uint32_t k = a.top();
        const double x = random_time(rng, true) + 100.0 * step;
        a.update(k, x);
        b.update(k, x);
    }
}
