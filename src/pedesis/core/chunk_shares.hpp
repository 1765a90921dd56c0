#pragma once
// The per-particle loops of a step (integrators, zeroing, the wrap, the rebuild check)
// and the colours of the force loop, shared out so that a slow core does not hold the
// step back. Each thread of the parallel region first takes the chunks of its own shares
// (one contiguous range, as schedule(static) would give it, or the ranges the force loop
// gave it: below); once they are done it takes what is left of the other threads'
// shares, from their far ends, a chunk at a time.
//
// Why not schedule(static) or schedule(dynamic): on a shared host one core of two is often
// slowed by a neighbour (a busy sibling hyperthread, 10-20% for seconds), and under
// schedule(static) the other then waits at the end of every loop (ABP at 36,000 particles,
// two threads: 3-9% of the step). schedule(dynamic) balances, but every chunk it hands
// out moves one shared counter's cache line between the cores (about 140 ns a chunk here),
// while a thread taking from its own share touches only its own line.
//
// Why the force loop's ranges: the integrators read the forces the force loop has just
// written. A particle integrated on the core that summed its force finds the force in
// that core's cache; under an equal split half of them came from the other core's
// (2D ABP on two threads: the Brownian move took 3.4 times its one-thread time).
//
// Which thread runs a chunk varies from run to run; the loops served here compute each
// item apart from the others (or reduce with min, max, or, or integer sums), so the
// results do not.
#include <omp.h>

#include <algorithm>
#include <atomic>
#include <cstdint>
#include <memory>
#include <span>

namespace pedesis {

class ChunkShares {
  public:
    // [0, items) in chunks of `grain` items, in one contiguous share for each thread the
    // next parallel region will have at most (omp_get_max_threads()).
    ChunkShares(std::int64_t items, std::int64_t grain)
        : ChunkShares(items, grain, 1, std::span<const std::int64_t>{}) {}

    // The same, the shares laid out by `bounds` where that is a layout for this many
    // threads: share j is [bounds[j], bounds[j + 1]) in units (particles, say) of which
    // an item holds `per_item` (rounded to whole items), thread j % threads owns share j,
    // bounds[0] = 0 and bounds.back() = units. Any other `bounds` (empty, stale, made for
    // another thread count) gives the equal shares.
    ChunkShares(std::int64_t units, std::int64_t grain, std::int64_t per_item,
                std::span<const std::int64_t> bounds)
        : grain_(std::max<std::int64_t>(grain, 1)), threads_(std::max(omp_get_max_threads(), 1)) {
        per_item = std::max<std::int64_t>(per_item, 1);
        units = std::max<std::int64_t>(units, 0);
        // (a share's ends are 32-bit; pedesis counts particles in 32 bits)
        items_ = std::min<std::int64_t>((units + per_item - 1) / per_item, 0xffffffff);
        const bool laid_out = fits(bounds, units);
        shares_count_ = laid_out ? static_cast<int>(bounds.size()) - 1 : threads_;
        shares_.reset(new Share[static_cast<std::size_t>(shares_count_)]);
        auto item_at = [&](std::size_t j) {
            if (j + 1 == bounds.size()) return items_;
            return std::min(items_, (bounds[j] + per_item / 2) / per_item);
        };
        for (int j = 0; j < shares_count_; ++j) {
            const auto u = static_cast<std::size_t>(j);
            const std::int64_t front = laid_out ? item_at(u) : items_ * j / threads_;
            const std::int64_t back = laid_out ? item_at(u + 1) : items_ * (j + 1) / threads_;
            shares_[u].range.store(pack(front, back), std::memory_order_relaxed);
        }
    }

    // Called by every thread of the region (or from outside one): calls body(first, last)
    // for item ranges of at most `grain` items that together cover [0, items) once.
    void run(auto&& body) { run_rounds(0, rounds(), body); }

    // The same for the items of the shares of round k only (shares k * threads ..
    // (k + 1) * threads - 1: one colour of the force loop), so that a barrier can follow
    // each round.
    void run_round(int k, auto&& body) { run_rounds(k, k + 1, body); }

    int rounds() const { return shares_count_ / threads_; }

  private:
    // [front, back) of the items not yet taken, in one word so that taking from either
    // end is one compare-and-swap; on its own cache line so that a thread taking from its
    // share does not disturb the others.
    struct alignas(64) Share {
        std::atomic<std::uint64_t> range{0};
    };
    static std::uint64_t pack(std::int64_t front, std::int64_t back) {
        return static_cast<std::uint64_t>(front) | (static_cast<std::uint64_t>(back) << 32);
    }

    bool fits(std::span<const std::int64_t> bounds, std::int64_t units) const {
        if (bounds.size() < 2 || (bounds.size() - 1) % static_cast<std::size_t>(threads_) != 0 ||
            bounds.front() != 0 || bounds.back() != units)
            return false;
        return std::is_sorted(bounds.begin(), bounds.end());
    }

    // Each pass of the loops below takes a chunk or finds a share empty, so a caller
    // returns after at most (chunks + shares) passes without a lost race, and a race is
    // lost only to a caller that took a chunk.
    void run_rounds(int from, int to, auto& body) {
        const int team = omp_in_parallel() ? omp_get_num_threads() : 1;
        const int me = omp_in_parallel() ? omp_get_thread_num() : 0;
        // A team smaller than prepared: caller c plays thread c * threads / team and,
        // stealing, finishes the shares of the threads nobody plays.
        const int own = team >= threads_ ? me % threads_ : me * threads_ / team;
        for (int k = from; k < to; ++k)
            for (std::int64_t first, last; take(k * threads_ + own, true, first, last);)
                body(first, last);
        for (int d = 1; d < threads_; ++d)
            for (int k = from; k < to; ++k)
                for (std::int64_t first, last;
                     take(k * threads_ + (own + d) % threads_, false, first, last);)
                    body(first, last);
    }

    // Takes up to `grain` items from the front or the back of share j into [first, last);
    // false once the share is empty.
    bool take(int j, bool front, std::int64_t& first, std::int64_t& last) {
        std::atomic<std::uint64_t>& range = shares_[static_cast<std::size_t>(j)].range;
        std::uint64_t now = range.load(std::memory_order_relaxed);
        for (;;) {
            const auto f = static_cast<std::int64_t>(now & 0xffffffffu);
            const auto b = static_cast<std::int64_t>(now >> 32);
            if (f >= b) return false;
            first = front ? f : std::max(f, b - grain_);
            last = front ? std::min(b, f + grain_) : b;
            const std::uint64_t next = front ? pack(last, b) : pack(f, first);
            // (a failed exchange reloads `now`: another caller took from this share)
            if (range.compare_exchange_strong(now, next, std::memory_order_relaxed)) return true;
        }
    }

    std::int64_t items_ = 0, grain_;
    int threads_, shares_count_ = 0;
    std::unique_ptr<Share[]> shares_;
};

// Items a thread takes at a time in light per-item loops (a copy, a sum, a kick: about a
// microsecond of work, against some 10 ns to take the chunk)
constexpr std::int64_t light_items_per_chunk = 1024;

// body(i) for every i in [0, n), in parallel, shared out as above, laid out by `bounds`
// where they fit (for loops whose items each take a few nanoseconds; no reduction).
template <class Body>
void parallel_for_each_index(std::int64_t n, std::span<const std::int64_t> bounds, Body&& body) {
    ChunkShares shares(n, light_items_per_chunk, 1, bounds);
#pragma omp parallel
    shares.run([&](std::int64_t first, std::int64_t last) {
        for (std::int64_t i = first; i < last; ++i) body(i);
    });
}

} // namespace pedesis
