#include "mpi_world.hpp"

#include "pedesis/core/error.hpp"

#include <cstdlib>
#include <string>

#ifdef PEDESIS_HAVE_MPI
#include <mpi.h>
#endif

namespace pedesis::cli {

namespace {

// The number of processes a launcher started, from its environment: OpenMPI's mpirun, a
// PMI launcher (MPICH's Hydra, srun --mpi=pmi2); 1 for a PMIx launcher (srun --mpi=pmix),
// which gives the size only after MPI_Init; 0 when no launcher did. (Not SLURM_NTASKS: a
// batch script has it without srun.)
int launched_size() {
    for (const char* var : {"OMPI_COMM_WORLD_SIZE", "PMI_SIZE"})
        if (const char* v = std::getenv(var)) return std::atoi(v);
    return std::getenv("PMIX_RANK") ? 1 : 0;
}

MpiWorld* the_world = nullptr;

} // namespace

MpiWorld::MpiWorld() {
    const int launched = launched_size();
#ifdef PEDESIS_HAVE_MPI
    if (launched > 0) {
        int provided = 0;
        // FUNNELED: only the main thread calls MPI; OpenMP threads compute in between
        MPI_Init_thread(nullptr, nullptr, MPI_THREAD_FUNNELED, &provided);
        initialised_ = true;
        MPI_Comm_rank(MPI_COMM_WORLD, &rank_);
        MPI_Comm_size(MPI_COMM_WORLD, &size_);
    }
#else
    if (launched > 1)
        throw InputError("this pedesis was built without MPI, and a launcher started " +
                         std::to_string(launched) +
                         " copies of it; install libopenmpi-dev and rebuild (make build), or "
                         "run it without mpirun");
#endif
}

MpiWorld::~MpiWorld() {
#ifdef PEDESIS_HAVE_MPI
    if (initialised_) MPI_Finalize();
#endif
}

MpiWorld& MpiWorld::get() {
    static MpiWorld world;
    the_world = &world;
    return world;
}

void MpiWorld::barrier() const {
#ifdef PEDESIS_HAVE_MPI
    if (initialised_) MPI_Barrier(MPI_COMM_WORLD);
#endif
}

int MpiWorld::max(int value) const {
#ifdef PEDESIS_HAVE_MPI
    if (initialised_) {
        int out = value;
        MPI_Allreduce(&value, &out, 1, MPI_INT, MPI_MAX, MPI_COMM_WORLD);
        return out;
    }
#endif
    return value;
}

int rank_for_messages() {
    return the_world ? the_world->rank() : 0;
}

} // namespace pedesis::cli
