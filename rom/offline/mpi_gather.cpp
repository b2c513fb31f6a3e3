#include "rom/offline/mpi_gather.hpp"

#include <limits>

#include "common/error.hpp"

namespace mastrom::rom {

void communicatorRankSize(MPI_Comm comm, int& rank, int& size) {
  rank = 0;
  size = 1;
  if (comm == MPI_COMM_NULL) return;
  MPI_Comm_rank(comm, &rank);
  MPI_Comm_size(comm, &size);
}

void throwIfAnyRankFailed(MPI_Comm comm, const std::string& error, bool numerical) {
  if (comm == MPI_COMM_NULL) {
    if (error.empty()) return;
    if (numerical) throw NumericalError(error);
    throw InputError(error);
  }
  int rank = 0, size = 1;
  communicatorRankSize(comm, rank, size);
  const int none = std::numeric_limits<int>::max();
  int mine = error.empty() ? none : rank, first = none;
  MPI_Allreduce(&mine, &first, 1, MPI_INT, MPI_MIN, comm);
  if (first == none) return;
  int info[2] = {static_cast<int>(error.size()), numerical ? 1 : 0};
  MPI_Bcast(info, 2, MPI_INT, first, comm);
  std::string message = rank == first ? error : std::string(static_cast<std::size_t>(info[0]), ' ');
  MPI_Bcast(message.data(), info[0], MPI_CHAR, first, comm);
  if (info[1]) throw NumericalError(message);
  throw InputError(message);
}

std::vector<double> gatherToRoot(MPI_Comm comm, const std::vector<double>& local) {
  if (comm == MPI_COMM_NULL) return local;
  int rank = 0, size = 1;
  communicatorRankSize(comm, rank, size);
  MASTROM_REQUIRE(local.size() < static_cast<std::size_t>(std::numeric_limits<int>::max()),
                  InputError, "MPI gather: block of ", local.size(), " values is too large");
  const int count = static_cast<int>(local.size());
  std::vector<int> counts(size), displs(size);
  MPI_Gather(&count, 1, MPI_INT, counts.data(), 1, MPI_INT, 0, comm);
  std::vector<double> all;
  if (rank == 0) {
    long total = 0;
    for (int r = 0; r < size; ++r) {
      displs[r] = static_cast<int>(total);
      total += counts[r];
    }
    MASTROM_REQUIRE(total < std::numeric_limits<int>::max(), InputError, "MPI gather: ", total,
                    " values in total is too many");
    all.resize(static_cast<std::size_t>(total));
  }
  MPI_Gatherv(local.data(), count, MPI_DOUBLE, all.data(), counts.data(), displs.data(), MPI_DOUBLE,
              0, comm);
  return all;
}

std::vector<double> gatherToAll(MPI_Comm comm, const std::vector<double>& local) {
  if (comm == MPI_COMM_NULL) return local;
  int rank = 0, size = 1;
  communicatorRankSize(comm, rank, size);
  MASTROM_REQUIRE(local.size() < static_cast<std::size_t>(std::numeric_limits<int>::max()),
                  InputError, "MPI gather: block of ", local.size(), " values is too large");
  const int count = static_cast<int>(local.size());
  std::vector<int> counts(size), displs(size);
  MPI_Allgather(&count, 1, MPI_INT, counts.data(), 1, MPI_INT, comm);
  long total = 0;
  for (int r = 0; r < size; ++r) {
    displs[r] = static_cast<int>(total);
    total += counts[r];
  }
  MASTROM_REQUIRE(total < std::numeric_limits<int>::max(), InputError, "MPI gather: ", total,
                  " values in total is too many");
  std::vector<double> all(static_cast<std::size_t>(total));
  MPI_Allgatherv(local.data(), count, MPI_DOUBLE, all.data(), counts.data(), displs.data(),
                 MPI_DOUBLE, comm);
  return all;
}

}  // namespace mastrom::rom
