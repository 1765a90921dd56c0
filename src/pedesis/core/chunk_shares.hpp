#pragma once
// The per-particle loops of a step (integrators, zeroing, the wrap, the rebuild check),
// shared out so that a slow core does not hold the step back. Each thread of the parallel
// region first takes the chunks of its own contiguous share, the one schedule(static)
// would give it (so consecutive loops over the same particles touch the same memory on
// the same core); once its share is done it takes what is left of the other shares, from
// their far ends, a chunk at a time.
//
// Why not schedule(static) or schedule(dynamic): on a shared host one core of two is often
// slowed by a neighbour (a busy sibling hyperthread, 10-20% for seconds), and under
// schedule(static) the other then waits at the end of every loop (ABP at 36,000 particles,
// two threads: 3-9% of the step). schedule(dynamic) balances, but every chunk it hands
// out moves one shared counter's cache line between the cores (about 140 ns a chunk here),
// while a thread taking from its own share touches only its own line.
//
// Which thread runs a chunk varies from run to run; the loops served here compute each
// particle apart from the others (or reduce with min, max, or, or integer sums), so the
// results do not.
#include <omp.h>

#include <algorithm>
#include <atomic>
#include <cstdint>
#include <memory>

namespace pedesis {

class ChunkShares {
  public:
    // [0, items) in chunks of `grain` items (the last may be shorter), shared among the
    // threads the next parallel region will have at most (omp_get_max_threads()).
    ChunkShares(std::int64_t items, std::int64_t grain)
        : items_(std::max<std::int64_t>(items, 0)), grain_(std::max<std::int64_t>(grain, 1)),
          threads_(std::max(omp_get_max_threads(), 1)), shares_(new Share[threads_]) {
        // (a share's ends are 32-bit: a coarser grain where the chunks would not fit)
        grain_ = std::max<std::int64_t>(grain_, items_ / 0xffffffff + 1);
        const std::int64_t chunks = (items_ + grain_ - 1) / grain_;
        for (int t = 0; t < threads_; ++t)
            shares_[t].range.store(pack(chunks * t / threads_, chunks * (t + 1) / threads_),
                                   std::memory_order_relaxed);
    }

    // Called by every thread of the region (or from outside one): calls body(first, last)
    // for item ranges that together cover [0, items) once. A region with fewer threads
    // than prepared is served too: every caller goes on through all the shares until each
    // is empty. Each pass of the loops below takes a chunk or finds a share empty, so a
    // caller returns after at most chunks + threads passes without a lost race, and a race
    // is lost only to a caller that took a chunk.
    template <class Body> void run(Body&& body) {
        const int team = omp_in_parallel() ? omp_get_num_threads() : 1;
        const int own = omp_in_parallel() ? omp_get_thread_num() : 0;
        // With a team as large as prepared, thread t starts on share t; otherwise the
        // shares are spread over the callers the same way.
        const int first_share = team >= threads_ ? own % threads_ : own * threads_ / team;
        for (std::int64_t c; (c = take_front(first_share)) >= 0;) call(body, c);
        for (int k = 1; k < threads_; ++k) {
            const int victim = (first_share + k) % threads_;
            for (std::int64_t c; (c = take_back(victim)) >= 0;) call(body, c);
        }
    }

  private:
    // [front, back) of the chunks not yet taken, in one word so that taking from either
    // end is one compare-and-swap; on its own cache line so that a thread taking from its
    // share does not disturb the others.
    struct alignas(64) Share {
        std::atomic<std::uint64_t> range{0};
    };
    static std::uint64_t pack(std::int64_t front, std::int64_t back) {
        return static_cast<std::uint64_t>(front) | (static_cast<std::uint64_t>(back) << 32);
    }

    std::int64_t take_front(int s) { return take(s, true); }
    std::int64_t take_back(int s) { return take(s, false); }
    // The chunk taken, or -1 once the share is empty.
    std::int64_t take(int s, bool front) {
        std::atomic<std::uint64_t>& range = shares_[s].range;
        std::uint64_t now = range.load(std::memory_order_relaxed);
        for (;;) {
            const auto f = static_cast<std::int64_t>(now & 0xffffffffu);
            const auto b = static_cast<std::int64_t>(now >> 32);
            if (f >= b) return -1;
            const std::uint64_t next = front ? pack(f + 1, b) : pack(f, b - 1);
            // (a failed exchange reloads `now`: another caller took a chunk of this share)
            if (range.compare_exchange_strong(now, next, std::memory_order_relaxed))
                return front ? f : b - 1;
        }
    }
    template <class Body> void call(Body& body, std::int64_t c) {
        const std::int64_t first = c * grain_;
        body(first, std::min(items_, first + grain_));
    }

    std::int64_t items_, grain_;
    int threads_;
    std::unique_ptr<Share[]> shares_;
};

// Items a thread takes at a time in light per-item loops (a copy, a sum, a kick: about a
// microsecond of work, against some 10 ns to take the chunk)
constexpr std::int64_t light_items_per_chunk = 1024;

// body(i) for every i in [0, n), in parallel, shared out as above (for loops whose items
// each take a few nanoseconds; no reduction).
template <class Body> void parallel_for_each_index(std::int64_t n, Body&& body) {
    ChunkShares shares(n, light_items_per_chunk);
#pragma omp parallel
    shares.run([&](std::int64_t first, std::int64_t last) {
        for (std::int64_t i = first; i < last; ++i) body(i);
    });
}

} // namespace pedesis
