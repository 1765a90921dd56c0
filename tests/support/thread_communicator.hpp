#pragma once
// A Communicator whose processes are threads of one test: run_processes(P, f) calls
// f(comm) on P threads, each with its own rank, and every collective call meets the
// others' at a barrier, exchanging numbers through shared mailboxes. Lets a test fake
// 2-8 MPI ranks (domain decomposition) without MPI. A process that throws drops out of
// the barrier so that the others cannot wait for it forever; its error is rethrown by
// run_processes after all have ended.
#include "pedesis/core/communicator.hpp"

#include <barrier>
#include <exception>
#include <functional>
#include <thread>
#include <vector>

namespace pedesis::test {

class ThreadHub {
  public:
    explicit ThreadHub(int size)
        : size_(size), barrier_(size),
          mail_(static_cast<std::size_t>(size),
                std::vector<std::vector<double>>(static_cast<std::size_t>(size))) {}
    int size() const { return size_; }
    void sync() { barrier_.arrive_and_wait(); }
    void drop() { barrier_.arrive_and_drop(); }
    // mail(from, to): what `from` posted for `to` in the current call
    std::vector<double>& mail(int from, int to) {
        return mail_[static_cast<std::size_t>(from)][static_cast<std::size_t>(to)];
    }

  private:
    int size_;
    std::barrier<> barrier_;
    std::vector<std::vector<std::vector<double>>> mail_;
};

class ThreadCommunicator : public Communicator {
  public:
    ThreadCommunicator(ThreadHub& hub, int rank) : hub_(hub), rank_(rank) {}
    int rank() const override { return rank_; }
    int size() const override { return hub_.size(); }

    void sum(std::span<double> values) override {
        reduce(values, [](double a, double b) { return a + b; });
    }
    void max(std::span<double> values) override {
        reduce(values, [](double a, double b) { return a > b ? a : b; });
    }

    std::vector<double> exchange(const std::vector<std::vector<double>>& send,
                                 std::vector<std::size_t>& counts) override {
        for (int q = 0; q < size(); ++q) hub_.mail(rank_, q) = send[static_cast<std::size_t>(q)];
        hub_.sync();
        std::vector<double> in;
        counts.assign(static_cast<std::size_t>(size()), 0);
        for (int q = 0; q < size(); ++q) {
            const auto& m = hub_.mail(q, rank_);
            counts[static_cast<std::size_t>(q)] = m.size();
            in.insert(in.end(), m.begin(), m.end());
        }
        hub_.sync();
        return in;
    }

    std::vector<double> exchange_with(const std::vector<int>& partners,
                                      const std::vector<std::vector<double>>& send,
                                      std::vector<std::size_t>& counts) override {
        for (int q = 0; q < size(); ++q) hub_.mail(rank_, q).clear();
        hub_.sync();
        for (std::size_t k = 0; k < partners.size(); ++k) hub_.mail(rank_, partners[k]) = send[k];
        hub_.sync();
        std::vector<double> in;
        counts.clear();
        for (int q : partners) {
            const auto& m = hub_.mail(q, rank_);
            counts.push_back(m.size());
            in.insert(in.end(), m.begin(), m.end());
        }
        hub_.sync();
        return in;
    }

    std::vector<double> gather(const std::vector<double>& send) override {
        hub_.mail(rank_, 0) = send;
        hub_.sync();
        std::vector<double> all;
        if (rank_ == 0)
            for (int q = 0; q < size(); ++q)
                all.insert(all.end(), hub_.mail(q, 0).begin(), hub_.mail(q, 0).end());
        hub_.sync();
        return all;
    }

    void broadcast(std::vector<double>& values, int root) override {
        if (rank_ == root) hub_.mail(root, root) = values;
        hub_.sync();
        if (rank_ != root) values = hub_.mail(root, root);
        hub_.sync();
    }

    double bytes_sent() const override { return 0.0; }
    double seconds() const override { return 0.0; }

  private:
    template <class Op> void reduce(std::span<double> values, Op op) {
        // in rank order on every process, so that all get the same rounding
        hub_.mail(rank_, 0).assign(values.begin(), values.end());
        hub_.sync();
        for (std::size_t k = 0; k < values.size(); ++k) {
            double v = hub_.mail(0, 0)[k];
            for (int q = 1; q < size(); ++q) v = op(v, hub_.mail(q, 0)[k]);
            values[k] = v;
        }
        hub_.sync();
    }

    ThreadHub& hub_;
    int rank_;
};

// Runs f(comm) as `processes` processes; rethrows the first error any of them threw.
inline void run_processes(int processes, const std::function<void(Communicator&)>& f) {
    ThreadHub hub(processes);
    std::vector<std::exception_ptr> errors(static_cast<std::size_t>(processes));
    std::vector<std::thread> threads;
    for (int r = 0; r < processes; ++r)
        threads.emplace_back([&, r] {
            ThreadCommunicator comm(hub, r);
            try {
                f(comm);
            } catch (...) {
                errors[static_cast<std::size_t>(r)] = std::current_exception();
                hub.drop();
            }
        });
    for (auto& t : threads) t.join();
    for (const auto& e : errors)
        if (e) std::rethrow_exception(e);
}

} // namespace pedesis::test
