#pragma once
// dem_server --mpi: one protocol server over the processes of an MPI run
// (issue "Beyond one machine"; docs/determinism.md §3). Every process holds a
// DemBackend over a DistributedEngine (distributed_engine.hpp). Rank 0 binds
// the socket and speaks the protocol; before each request reaches its
// backend, it sends the request to the other processes (an MPI broadcast),
// which run it on theirs: every process makes the same calls in the same
// order, so the engine's collectives meet, and the replies rank 0 sends are
// the whole body's. The others' replies are dropped.
//
// Errors: a request that fails on rank 0 fails alike on the others (the same
// inputs; an unstable step is made collective by the engine), and they wait
// for the next. At the end rank 0 sends "stop". If rank 0 ends with an
// error, the run is aborted (MPI_Abort), so no process is left waiting.
#include <functional>
#include <memory>

#include <mpi.h>

#include "dfc/protocol/server.hpp"
#include "dfc/protocol/solver_backend.hpp"

namespace dfc::dem {

/// Makes the backend of process `rank` of `processes`.
using RankBackendFactory = std::function<std::unique_ptr<protocol::SolverBackend>(int processes, int rank)>;

/// main() of `program` under `mpiexec -n N program --mpi ...`: initialises
/// MPI, runs the protocol server on rank 0 (argv without --mpi) and follows
/// it on the others; returns the exit status.
int run_mpi_server_main(int argc, char** argv, const protocol::ServerProgram& program, const RankBackendFactory& make_backend);

}  // namespace dfc::dem
