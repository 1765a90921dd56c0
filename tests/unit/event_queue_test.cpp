// EventQueue: the top is always the (time, index) minimum of a reference array under
// random updates, and draining the queue yields the reference's sorted order; on
// engine-like workloads (times that only move forward, event rates that change by
// orders of magnitude, events far beyond the calendar's reach) the bucket calendar
// pops exactly the sequence of a reference ordered set.
#include "pedesis/core/rng.hpp"
#include "pedesis/event/event_queue.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <limits>
#include <numeric>
#include <set>
#include <utility>
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

namespace {

// Pops `events` events as the engine does (take the top, give it a later time; now and
// then give a random other particle a new time after now) and checks every pop against
// a std::set of (time, index). `scale(k)` is the typical wait at pop k.
template <class Scale>
void engine_like_workload(std::uint32_t n, int events, std::uint64_t seed, Scale scale) {
    CounterRng rng(seed, RngStream::placement, n);
    std::vector<double> t(n);
    std::set<std::pair<double, std::uint32_t>> reference;
    for (std::uint32_t i = 0; i < n; ++i) {
        t[i] = rng.uniform() < 0.01 ? inf : rng.uniform(0.0, scale(0));
        reference.insert({t[i], i});
    }
    EventQueue q;
    q.build(t);
    const auto set_time = [&](std::uint32_t i, double x) {
        reference.erase({t[i], i});
        t[i] = x;
        reference.insert({x, i});
        q.update(i, x);
    };
    for (int k = 0; k < events; ++k) {
        const auto [now, who] = *reference.begin();
        ASSERT_EQ(q.top_time(), now) << "pop " << k;
        ASSERT_EQ(q.top(), who) << "pop " << k;
        if (now == inf) return; // nothing left to happen
        const double u = rng.uniform();
        // mostly near future, sometimes far beyond the calendar (overflow), sometimes never
        const double wait = u < 0.9 ? rng.uniform(0.0, scale(k)) : u < 0.99 ? 1e4 * scale(k) : inf;
        set_time(who, now + wait);
        if (rng.uniform() < 0.5) {
            const auto other = static_cast<std::uint32_t>(rng.uniform() * n) % n;
            if (other != who) set_time(other, now + rng.uniform(0.0, 2.0 * scale(k)));
        }
    }
}

} // namespace

TEST(EventQueue, CalendarPopsInExactTimeOrder) {
    for (std::uint32_t n : {1u, 5u, 100u, 5000u})
        engine_like_workload(n, 200000, 3, [](int) { return 1.0; });
}

TEST(EventQueue, CalendarFollowsEventRatesThatChangeByOrdersOfMagnitude) {
    // a gas that cools (waits grow 10^4-fold) and then is compressed (waits shrink again):
    // the bucket width must be chosen anew, and the order must never change
    engine_like_workload(2000, 300000, 4, [](int k) {
        const double x = static_cast<double>(k) / 300000.0;
        return std::pow(10.0, 4.0 * std::sin(3.14159 * x));
    });
}

TEST(EventQueue, CalendarWithTiesAndTimesFarApart) {
    // equal times (ties broken by index) and a few events 1e12 ahead of the rest
    const std::uint32_t n = 1000;
    std::vector<double> t(n);
    for (std::uint32_t i = 0; i < n; ++i) t[i] = i % 10 == 0 ? 1e12 + i % 3 : std::floor(i / 7.0);
    EventQueue q;
    q.build(t);
    std::vector<std::uint32_t> order(n);
    std::iota(order.begin(), order.end(), 0u);
    std::stable_sort(order.begin(), order.end(),
                     [&](std::uint32_t a, std::uint32_t b) { return t[a] < t[b]; });
    for (std::uint32_t k = 0; k < n; ++k) {
        ASSERT_EQ(q.top(), order[k]) << k;
        ASSERT_EQ(q.top_time(), t[order[k]]);
        q.update(order[k], inf);
    }
    EXPECT_EQ(q.top_time(), inf);
}
