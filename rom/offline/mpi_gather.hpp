// The two MPI patterns the ROM's distributed loops share (database build, screening): every rank
// learns when any rank failed (so no rank waits forever in a collective), and rank 0 gathers
// variable-length blocks of doubles in rank order (or every rank does). With MPI_COMM_NULL both
// work serially without calling MPI at all.
#pragma once

#include <mpi.h>

#include <string>
#include <vector>

namespace mastrom::rom {

/// Rank and size of `comm` (0 and 1 for MPI_COMM_NULL).
void communicatorRankSize(MPI_Comm comm, int& rank, int& size);

/// Collective: when any rank's `error` is non-empty, every rank throws the lowest failing rank's
/// message — NumericalError if that rank set `numerical`, InputError otherwise.
void throwIfAnyRankFailed(MPI_Comm comm, const std::string& error, bool numerical);

/// Collective: rank 0 receives the concatenation of every rank's `local` in rank order (returned);
/// the other ranks get an empty vector.
std::vector<double> gatherToRoot(MPI_Comm comm, const std::vector<double>& local);

/// Collective: every rank receives the concatenation of every rank's `local` in rank order.
std::vector<double> gatherToAll(MPI_Comm comm, const std::vector<double>& local);

}  // namespace mastrom::rom
