#pragma once
// The processes this pedesis runs among, when a launcher (mpirun, mpiexec, srun) started
// several: its rank and their number, and the few collective steps the commands need.
// MPI is initialised only under a launcher, so that a plain `pedesis run` works exactly
// as without MPI (no MPI start-up, nothing asked of the machine). A build without MPI
// started by a launcher with several processes refuses to run P copies of one job.
namespace pedesis::cli {

class MpiWorld {
  public:
    // The world of this process (initialises MPI on first use when launched).
    static MpiWorld& get();

    int rank() const { return rank_; }
    int size() const { return size_; }
    // Waits for every process.
    void barrier() const;
    // The largest of every process's `value`.
    int max(int value) const;

    ~MpiWorld(); // MPI_Finalize, if initialised
    MpiWorld(const MpiWorld&) = delete;
    MpiWorld& operator=(const MpiWorld&) = delete;

  private:
    MpiWorld();
    int rank_ = 0, size_ = 1;
    bool initialised_ = false;
};

// The rank of this process if MPI is up, else 0; never initialises MPI (for messages).
int rank_for_messages();

// Ends the command with `code` and no message: the other processes of an MPI job that
// all reached the same outcome, of which process 0 tells.
struct SilentExit {
    int code;
};

} // namespace pedesis::cli
