#pragma once
// The event calendar: one pending event per particle, ordered by (time, particle). Ties
// break on the particle index, so the order of processing is a function of the events
// alone, never of the calendar's history; that is what lets a checkpointed run continue
// bit for bit, and what makes this calendar process events in exactly the order of a
// binary heap over the same keys.
//
// Layout (the bucket calendar of Smallenburg's EDMD, Eur. Phys. J. E 45, 22 (2022),
// after Paul, J. Comput. Phys. 221, 615 (2007)): time is cut into buckets of width w;
// B buckets ahead of the current one hold unsorted doubly linked lists, later events
// wait in an overflow list, and only the current bucket is sorted, in a small indexed
// binary heap. Inserting and removing is O(1) outside the current bucket; the heap holds
// about `target_per_bucket` events instead of N, so it stays in cache at any N. The
// width follows the event rate: it is chosen from the pending times when the calendar
// is built and chosen again when the events per bucket drift far from the target (a
// cooling gas slows down, a compressed one speeds up). Processing order never depends on
// w, so re-tuning changes nothing in a trajectory.
#include <algorithm>
#include <bit>
#include <cmath>
#include <cstdint>
#include <limits>
#include <vector>

namespace pedesis {

class EventQueue {
  public:
    void build(const std::vector<double>& times) {
        build_from(times.size(), [&](std::uint32_t who) { return times[who]; });
    }
    // The same with particle who's time given by time_of(who), asked once per particle in
    // increasing order (the engine predicts into it without an array of its own).
    template <class TimeOf> void build_from(std::size_t n, TimeOf&& time_of) {
        node_.resize(n);
        for (std::uint32_t who = 0; who < n; ++who)
            node_[who] = {time_of(who), none, none, none, none};
        slots_ = std::bit_ceil(std::max<std::uint32_t>(static_cast<std::uint32_t>(n), 16));
        rebuild();
    }
    bool empty() const { return node_.empty(); }

    // The earliest event (after moving the next non-empty bucket into the heap). When no
    // event has a finite time, top_time() is +infinity and top() any particle.
    std::uint32_t top() {
        settle();
        return heap_.empty() ? never_head() : heap_[0].who;
    }
    double top_time() {
        settle();
        return heap_.empty() ? std::numeric_limits<double>::infinity() : heap_[0].t;
    }

    // Gives particle `who` the event time t (replacing its previous one).
    void update(std::uint32_t who, double t) {
        remove(who);
        insert(who, t);
        if (++updates_ >= retune_after_) maybe_retune();
    }

    // Particle who's pending event time (the engine keeps no copy).
    double time(std::uint32_t who) const { return node_[who].t; }
    double bucket_width() const { return width_; }
    std::size_t memory_bytes() const;

  private:
    struct Entry {
        double t;
        std::uint32_t who;
    };
    static constexpr std::uint32_t none = 0xffffffffu;
    // a Node's where below the bucket count is a bucket slot; otherwise one of these:
    static constexpr std::uint32_t in_heap = 0xfffffffcu;
    static constexpr std::uint32_t in_overflow = 0xfffffffdu;
    static constexpr std::uint32_t in_never = 0xfffffffeu;
    static constexpr double target_per_bucket = 16.0;

    static bool before(const Entry& a, const Entry& b) {
        return a.t < b.t || (a.t == b.t && a.who < b.who);
    }
    // Absolute bucket number of time t (monotone in t); huge for times far beyond
    // the calendar's reach.
    std::int64_t bucket_of(double t) const {
        const double k = std::floor(t * inverse_width_);
        return k < 4.0e18 ? static_cast<std::int64_t>(k) : std::numeric_limits<std::int64_t>::max();
    }
    // The lowest index among events that never happen, as a heap over (time, index) would
    // give (only asked for when nothing else is pending).
    std::uint32_t never_head() const {
        std::uint32_t best = none;
        for (std::uint32_t who = list_head_[slots_ + 1]; who != none; who = node_[who].next)
            best = std::min(best, who);
        return best;
    }

    void insert(std::uint32_t who, double t);
    void remove(std::uint32_t who);
    void push_list(std::uint32_t list, std::uint32_t who);
    void unlink(std::uint32_t who);
    void heap_push(std::uint32_t who, double t);
    void heap_erase(std::uint32_t who);
    void sift_up(std::uint32_t k);
    void sift_down(std::uint32_t k);
    void place(std::uint32_t k, const Entry& e) {
        heap_[k] = e;
        node_[e.who].heap_pos = k;
    }
    void settle() {
        if (heap_.empty()) advance();
    }
    void advance();
    void redistribute_overflow();
    void choose_width();
    void maybe_retune();
    void rebuild();

    // Everything the calendar keeps of one particle, in one record: at 10^6 particles a
    // particle's entry is a cache miss, one per record instead of one per array (five).
    struct Node {
        double t;
        std::uint32_t where, next, prev, heap_pos;
    };
    std::vector<Node> node_;
    // heads of the bucket lists, then of the overflow list and of the list of events
    // that never happen (slots_ and slots_ + 1)
    std::vector<std::uint32_t> list_head_;
    std::vector<Entry> heap_;
    std::uint32_t slots_ = 0; // B, a power of two
    double width_ = 1.0, inverse_width_ = 1.0;
    std::int64_t current_ = 0; // absolute number of the bucket in the heap
    std::size_t listed_ = 0;   // events in bucket lists
    std::uint64_t updates_ = 0, retune_after_ = 0, buckets_advanced_ = 0;
};

} // namespace pedesis
