#include "pedesis/event/event_queue.hpp"

#include <algorithm>
#include <bit>
#include <stdexcept>

namespace pedesis {

// Chooses the width from the pending times so that a bucket holds about
// target_per_bucket events, and files every event again.
void EventQueue::rebuild() {
    list_head_.assign(slots_ + 2, none);
    heap_.clear();
    listed_ = 0;
    choose_width();
    double first = std::numeric_limits<double>::infinity();
    for (const Node& e : node_) first = std::min(first, e.t);
    current_ = std::isfinite(first) ? bucket_of(first) : 0;
    if (current_ == std::numeric_limits<std::int64_t>::max()) current_ = 0;
    for (std::uint32_t i = 0; i < node_.size(); ++i) {
        node_[i].where = none;
        insert(i, node_[i].t);
    }
    updates_ = buckets_advanced_ = 0;
    retune_after_ = std::max<std::uint64_t>(4 * node_.size(), 1024);
}

// The events due within the next T are about N T / mean_wait (each particle's next event
// comes on average mean_wait after the earliest one): w = target * mean_wait / N.
void EventQueue::choose_width() {
    double first = std::numeric_limits<double>::infinity();
    for (const Node& e : node_) first = std::min(first, e.t);
    double sum = 0.0;
    std::size_t finite = 0;
    for (const Node& e : node_)
        if (std::isfinite(e.t)) {
            sum += e.t - first;
            ++finite;
        }
    double w = finite > 1 ? target_per_bucket * (sum / static_cast<double>(finite)) /
                                static_cast<double>(finite)
                          : 1.0;
    if (!(w > 0.0) || !std::isfinite(w)) w = 1.0;
    // a width far below the resolution of the times would make each bucket a handful of
    // floating-point values and the bucket numbers overflow
    if (std::isfinite(first)) w = std::max(w, 1e-12 * std::abs(first));
    width_ = w;
    inverse_width_ = 1.0 / w;
}

// After a few N updates: if the current buckets hold far more or far fewer events than
// the target, the event rate has changed since the width was chosen.
void EventQueue::maybe_retune() {
    const double per_bucket = static_cast<double>(updates_) /
                              static_cast<double>(std::max<std::uint64_t>(1, buckets_advanced_));
    if (per_bucket > 8.0 * target_per_bucket || per_bucket < target_per_bucket / 8.0)
        rebuild();
    else
        updates_ = buckets_advanced_ = 0;
}

void EventQueue::insert(std::uint32_t who, double t) {
    node_[who].t = t;
    if (!std::isfinite(t)) {
        push_list(slots_ + 1, who);
        node_[who].where = in_never;
        return;
    }
    const std::int64_t k = bucket_of(t);
    if (k <= current_) {
        heap_push(who, t);
    } else if (k - current_ < static_cast<std::int64_t>(slots_)) {
        const auto slot = static_cast<std::uint32_t>(k & (slots_ - 1));
        push_list(slot, who);
        node_[who].where = slot;
        ++listed_;
    } else {
        push_list(slots_, who);
        node_[who].where = in_overflow;
    }
}

void EventQueue::remove(std::uint32_t who) {
    const std::uint32_t w = node_[who].where;
    if (w == in_heap) {
        heap_erase(who);
    } else if (w != none) {
        unlink(who);
        if (w < slots_) --listed_;
    }
    node_[who].where = none;
}

void EventQueue::push_list(std::uint32_t list, std::uint32_t who) {
    const std::uint32_t head = list_head_[list];
    node_[who].next = head;
    node_[who].prev = none;
    if (head != none) node_[head].prev = who;
    list_head_[list] = who;
}

void EventQueue::unlink(std::uint32_t who) {
    const Node& e = node_[who];
    const std::uint32_t list =
        e.where < slots_ ? e.where : (e.where == in_overflow ? slots_ : slots_ + 1);
    if (e.prev != none)
        node_[e.prev].next = e.next;
    else
        list_head_[list] = e.next;
    if (e.next != none) node_[e.next].prev = e.prev;
}

// Moves to the next bucket that holds an event and sorts it into the heap.
void EventQueue::advance() {
    // A rebuild starts the calendar at the earliest event's bucket, so the one after it
    // lists that event; a second rebuild in a row means the calendar cannot hold the times
    // (an internal error, not a reason to go round again).
    int rebuilds_in_a_row = 0;
    while (heap_.empty()) {
        if (listed_ == 0) {
            if (list_head_[slots_] == none) return; // nothing finite is pending
            if (++rebuilds_in_a_row > 2)
                throw std::logic_error("event calendar: rebuilt twice without listing the "
                                       "earliest event (its time cannot be placed in a bucket)");
            // only far events are left: the width no longer fits the event rate
            rebuild();
            continue;
        }
        ++current_;
        ++buckets_advanced_;
        if ((current_ & (slots_ - 1)) == 0) redistribute_overflow();
        const auto slot = static_cast<std::uint32_t>(current_ & (slots_ - 1));
        std::uint32_t who = list_head_[slot];
        list_head_[slot] = none;
        while (who != none) {
            const std::uint32_t after = node_[who].next;
            --listed_;
            heap_push(who, node_[who].t);
            who = after;
        }
    }
}

// Once per turn of the B buckets: overflow events that now fall within reach move to
// their bucket (those due in the current bucket go straight into the heap).
void EventQueue::redistribute_overflow() {
    std::uint32_t who = list_head_[slots_];
    list_head_[slots_] = none;
    while (who != none) {
        const std::uint32_t after = node_[who].next;
        insert(who, node_[who].t);
        who = after;
    }
}

void EventQueue::heap_push(std::uint32_t who, double t) {
    node_[who].where = in_heap;
    heap_.push_back({t, who});
    sift_up(static_cast<std::uint32_t>(heap_.size() - 1));
}

void EventQueue::heap_erase(std::uint32_t who) {
    const std::uint32_t k = node_[who].heap_pos;
    const Entry last = heap_.back();
    heap_.pop_back();
    node_[who].heap_pos = none;
    if (k == heap_.size()) return;
    place(k, last);
    if (k > 0 && before(last, heap_[(k - 1) / 2]))
        sift_up(k);
    else
        sift_down(k);
}

void EventQueue::sift_up(std::uint32_t k) {
    const Entry e = heap_[k];
    while (k > 0) {
        const std::uint32_t parent = (k - 1) / 2;
        if (!before(e, heap_[parent])) break;
        place(k, heap_[parent]);
        k = parent;
    }
    place(k, e);
}

void EventQueue::sift_down(std::uint32_t k) {
    const Entry e = heap_[k];
    const auto n = static_cast<std::uint32_t>(heap_.size());
    while (true) {
        std::uint32_t child = 2 * k + 1;
        if (child >= n) break;
        if (child + 1 < n && before(heap_[child + 1], heap_[child])) ++child;
        if (!before(heap_[child], e)) break;
        place(k, heap_[child]);
        k = child;
    }
    place(k, e);
}

std::size_t EventQueue::memory_bytes() const {
    auto bytes = [](const auto& v) { return v.capacity() * sizeof(v[0]); };
    return bytes(node_) + bytes(list_head_) + bytes(heap_);
}

} // namespace pedesis
