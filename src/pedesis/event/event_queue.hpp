#pragma once
// The event calendar: one pending event per particle, held in an indexed binary
// min-heap keyed by (time, particle). Ties break on the particle index so the order
// of processing is a function of the events alone, never of the heap's history;
// that is what lets a checkpointed run continue bit for bit.
#include <cstdint>
#include <limits>
#include <vector>

namespace pedesis {

class EventQueue {
  public:
    void build(const std::vector<double>& times) {
        const auto n = static_cast<std::uint32_t>(times.size());
        heap_.resize(n);
        pos_.resize(n);
        for (std::uint32_t i = 0; i < n; ++i) {
            heap_[i] = {times[i], i};
            pos_[i] = i;
        }
        for (std::uint32_t k = n / 2; k-- > 0;) sift_down(k);
    }

    bool empty() const { return heap_.empty(); }
    std::uint32_t top() const { return heap_[0].who; }
    double top_time() const { return heap_[0].t; }

    void update(std::uint32_t who, double t) {
        const std::uint32_t k = pos_[who];
        const double old = heap_[k].t;
        heap_[k].t = t;
        if (t < old)
            sift_up(k);
        else
            sift_down(k);
    }

    std::size_t memory_bytes() const {
        return heap_.capacity() * sizeof(Entry) + pos_.capacity() * sizeof(std::uint32_t);
    }

  private:
    struct Entry {
        double t;
        std::uint32_t who;
    };
    static bool before(const Entry& a, const Entry& b) {
        return a.t < b.t || (a.t == b.t && a.who < b.who);
    }
    void place(std::uint32_t k, const Entry& e) {
        heap_[k] = e;
        pos_[e.who] = k;
    }
    void sift_up(std::uint32_t k) {
        const Entry e = heap_[k];
        while (k > 0) {
            const std::uint32_t parent = (k - 1) / 2;
            if (!before(e, heap_[parent])) break;
            place(k, heap_[parent]);
            k = parent;
        }
        place(k, e);
    }
    void sift_down(std::uint32_t k) {
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

    std::vector<Entry> heap_;
    std::vector<std::uint32_t> pos_;
};

} // namespace pedesis
