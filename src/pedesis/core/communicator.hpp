#pragma once
// The processes one run is shared among (MPI ranks), as the engines see them: a few
// collective operations on plain numbers. The engines know nothing of MPI; the CLI
// provides the MPI implementation (apps/pedesis/mpi_communicator), and a run without
// one is a run on one process. Every call is collective: every process of the run must
// make it, in the same order.
#include "pedesis/core/error.hpp"

#include <cstddef>
#include <exception>
#include <span>
#include <string>
#include <vector>

namespace pedesis {

class Communicator {
  public:
    virtual ~Communicator() = default;
    virtual int rank() const = 0;
    virtual int size() const = 0;

    // Element-wise over processes, in place.
    virtual void sum(std::span<double> values) = 0;
    virtual void max(std::span<double> values) = 0;

    // Every process sends send[q] to process q (empty: nothing); returns what each
    // process sent to this one, concatenated in rank order, and each one's count.
    virtual std::vector<double> exchange(const std::vector<std::vector<double>>& send,
                                         std::vector<std::size_t>& counts) = 0;
    // The same among partners only: send[k] goes to partners[k], and what partners[k]
    // sent comes back in that order. Point to point, so it costs O(partners), not O(P):
    // every process must name as partners exactly those that name it.
    virtual std::vector<double> exchange_with(const std::vector<int>& partners,
                                              const std::vector<std::vector<double>>& send,
                                              std::vector<std::size_t>& counts) = 0;
    // Every process's `send`, concatenated in rank order, on process 0 (empty elsewhere).
    virtual std::vector<double> gather(const std::vector<double>& send) = 0;
    // Process `root`'s values, on every process (resized to root's length).
    virtual void broadcast(std::vector<double>& values, int root) = 0;

    // Since construction (for benchmarks): bytes this process sent to others, and the
    // seconds it spent in these calls, waiting for the others included.
    virtual double bytes_sent() const = 0;
    virtual double seconds() const = 0;

    double max(double v) {
        max(std::span<double>(&v, 1));
        return v;
    }
    double sum(double v) {
        sum(std::span<double>(&v, 1));
        return v;
    }
    // A string from process `root`, on every process.
    std::string broadcast(const std::string& text, int root) {
        std::vector<double> v(text.begin(), text.end());
        broadcast(v, root);
        return std::string(v.begin(), v.end());
    }
};

// Runs `act` (which only process 0 performs: writing files) and makes every process
// agree on its outcome: if it threw, process 0 throws it again and every other process
// throws an error of the same kind (InputError, RunError, else std::runtime_error) whose
// message says process 0 reported it. No process can then wait for one that has stopped.
// Without a communicator (one process) it is act().
template <class Act> void on_process_zero(Communicator* comm, Act&& act) {
    if (!comm || comm->size() == 1) {
        act();
        return;
    }
    std::exception_ptr failure;
    double kind = 0.0; // 1 other, 2 input, 3 run
    if (comm->rank() == 0) {
        try {
            act();
        } catch (const InputError&) {
            failure = std::current_exception();
            kind = exit_input_error;
        } catch (const RunError&) {
            failure = std::current_exception();
            kind = exit_run_error;
        } catch (...) {
            failure = std::current_exception();
            kind = 1.0;
        }
    }
    kind = comm->max(kind);
    if (failure) std::rethrow_exception(failure);
    const std::string note = "(reported by process 0)";
    if (kind == exit_input_error) throw InputError(note);
    if (kind == exit_run_error) throw RunError(note);
    if (kind != 0.0) throw std::runtime_error(note);
}

} // namespace pedesis
