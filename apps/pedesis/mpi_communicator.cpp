#include "mpi_communicator.hpp"

#include "mpi_world.hpp"

#include <fmt/format.h>

#include <limits>
#include <numeric>
#include <stdexcept>

#ifdef PEDESIS_HAVE_MPI
#include <mpi.h>
#endif

namespace pedesis::cli {

#ifdef PEDESIS_HAVE_MPI
namespace {

// MPI counts are int: a message of more numbers than that is refused rather than cut.
int mpi_count(std::size_t n) {
    if (n > static_cast<std::size_t>(std::numeric_limits<int>::max()))
        throw RunError(fmt::format("MPI: a message of {} numbers is more than MPI's int counts "
                                   "allow; run on more processes",
                                   n));
    return static_cast<int>(n);
}

// Adds the seconds of its scope to a total.
class Timed {
  public:
    explicit Timed(double& total) : total_(total), start_(MPI_Wtime()) {}
    ~Timed() { total_ += MPI_Wtime() - start_; }
    Timed(const Timed&) = delete;
    Timed& operator=(const Timed&) = delete;

  private:
    double& total_;
    double start_;
};

class MpiCommunicator final : public Communicator {
  public:
    MpiCommunicator() {
        MPI_Comm_rank(MPI_COMM_WORLD, &rank_);
        MPI_Comm_size(MPI_COMM_WORLD, &size_);
    }
    int rank() const override { return rank_; }
    int size() const override { return size_; }

    void sum(std::span<double> v) override { reduce(v, MPI_SUM); }
    void max(std::span<double> v) override { reduce(v, MPI_MAX); }

    std::vector<double> exchange(const std::vector<std::vector<double>>& send,
                                 std::vector<std::size_t>& counts) override {
        const Timed timed(seconds_);
        const auto p = static_cast<std::size_t>(size_);
        std::vector<int> send_counts(p), recv_counts(p), send_at(p), recv_at(p);
        for (std::size_t q = 0; q < p; ++q) send_counts[q] = mpi_count(send[q].size());
        MPI_Alltoall(send_counts.data(), 1, MPI_INT, recv_counts.data(), 1, MPI_INT,
                     MPI_COMM_WORLD);
        std::vector<double> flat;
        flat.reserve(std::accumulate(send.begin(), send.end(), std::size_t{0},
                                     [](std::size_t n, const auto& b) { return n + b.size(); }));
        for (std::size_t q = 0; q < p; ++q) {
            send_at[q] = mpi_count(flat.size());
            flat.insert(flat.end(), send[q].begin(), send[q].end());
        }
        std::size_t total = 0;
        counts.resize(p);
        for (std::size_t q = 0; q < p; ++q) {
            recv_at[q] = mpi_count(total);
            counts[q] = static_cast<std::size_t>(recv_counts[q]);
            total += counts[q];
        }
        std::vector<double> in(total);
        MPI_Alltoallv(flat.data(), send_counts.data(), send_at.data(), MPI_DOUBLE, in.data(),
                      recv_counts.data(), recv_at.data(), MPI_DOUBLE, MPI_COMM_WORLD);
        bytes_ +=
            8.0 * static_cast<double>(flat.size() - send[static_cast<std::size_t>(rank_)].size());
        return in;
    }

    std::vector<double> exchange_with(const std::vector<int>& partners,
                                      const std::vector<std::vector<double>>& send,
                                      std::vector<std::size_t>& counts) override {
        const Timed timed(seconds_);
        const std::size_t k = partners.size();
        // the counts first (one number each way), then the numbers themselves
        std::vector<unsigned long long> out(k), in(k);
        std::vector<MPI_Request> requests(2 * k);
        for (std::size_t q = 0; q < k; ++q) {
            out[q] = send[q].size();
            MPI_Irecv(&in[q], 1, MPI_UNSIGNED_LONG_LONG, partners[q], 0, MPI_COMM_WORLD,
                      &requests[q]);
            MPI_Isend(&out[q], 1, MPI_UNSIGNED_LONG_LONG, partners[q], 0, MPI_COMM_WORLD,
                      &requests[k + q]);
        }
        MPI_Waitall(static_cast<int>(2 * k), requests.data(), MPI_STATUSES_IGNORE);
        counts.assign(in.begin(), in.end());
        std::vector<double> received(std::accumulate(counts.begin(), counts.end(), std::size_t{0}));
        std::size_t at = 0;
        for (std::size_t q = 0; q < k; ++q) {
            MPI_Irecv(received.data() + at, mpi_count(counts[q]), MPI_DOUBLE, partners[q], 1,
                      MPI_COMM_WORLD, &requests[q]);
            MPI_Isend(send[q].data(), mpi_count(send[q].size()), MPI_DOUBLE, partners[q], 1,
                      MPI_COMM_WORLD, &requests[k + q]);
            at += counts[q];
            bytes_ += 8.0 * static_cast<double>(send[q].size());
        }
        MPI_Waitall(static_cast<int>(2 * k), requests.data(), MPI_STATUSES_IGNORE);
        return received;
    }

    std::vector<double> gather(const std::vector<double>& send) override {
        const Timed timed(seconds_);
        int n = mpi_count(send.size());
        std::vector<int> counts(static_cast<std::size_t>(size_)), at(counts.size());
        MPI_Gather(&n, 1, MPI_INT, counts.data(), 1, MPI_INT, 0, MPI_COMM_WORLD);
        std::vector<double> all;
        if (rank_ == 0) {
            std::size_t total = 0;
            for (std::size_t q = 0; q < counts.size(); ++q) {
                at[q] = mpi_count(total);
                total += static_cast<std::size_t>(counts[q]);
            }
            all.resize(total);
        }
        MPI_Gatherv(send.data(), n, MPI_DOUBLE, all.data(), counts.data(), at.data(), MPI_DOUBLE, 0,
                    MPI_COMM_WORLD);
        if (rank_ != 0) bytes_ += 8.0 * n;
        return all;
    }

    void broadcast(std::vector<double>& values, int root) override {
        const Timed timed(seconds_);
        unsigned long long n = values.size();
        MPI_Bcast(&n, 1, MPI_UNSIGNED_LONG_LONG, root, MPI_COMM_WORLD);
        values.resize(n);
        MPI_Bcast(values.data(), mpi_count(n), MPI_DOUBLE, root, MPI_COMM_WORLD);
        if (rank_ == root) bytes_ += 8.0 * static_cast<double>(n) * (size_ - 1);
    }

    double bytes_sent() const override { return bytes_; }
    double seconds() const override { return seconds_; }

  private:
    void reduce(std::span<double> v, MPI_Op op) {
        const Timed timed(seconds_);
        MPI_Allreduce(MPI_IN_PLACE, v.data(), mpi_count(v.size()), MPI_DOUBLE, op, MPI_COMM_WORLD);
    }
    int rank_ = 0, size_ = 1;
    double bytes_ = 0.0;
    double seconds_ = 0.0;
};

} // namespace
#endif

std::unique_ptr<Communicator> world_communicator() {
#ifdef PEDESIS_HAVE_MPI
    if (MpiWorld::get().size() > 1) return std::make_unique<MpiCommunicator>();
#endif
    return nullptr;
}

} // namespace pedesis::cli
