#pragma once
// The engines' Communicator (core/communicator.hpp) over MPI_COMM_WORLD. Only in a
// build with MPI, and only made under a launcher with several processes (MpiWorld).
#include "pedesis/core/communicator.hpp"

#include <memory>

namespace pedesis::cli {

// The communicator of this MPI job, or null for one process (or a build without MPI).
std::unique_ptr<Communicator> world_communicator();

} // namespace pedesis::cli
