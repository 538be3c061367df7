#include "tribos/stack/RootGather.hpp"

namespace tribos::stack {

namespace {
// Gathers `mine` (count entries of `type` per rank) into `all` on rank 0, in rank order.
template <class T>
void gatherv(const std::vector<T>& mine, std::vector<T>& all, MPI_Datatype type, MPI_Comm comm) {
  int rank = 0, size = 1;
  MPI_Comm_rank(comm, &rank);
  MPI_Comm_size(comm, &size);
  const int count = static_cast<int>(mine.size());
  std::vector<int> counts(rank == 0 ? size : 0), offsets(rank == 0 ? size + 1 : 0, 0);
  MPI_Gather(&count, 1, MPI_INT, counts.data(), 1, MPI_INT, 0, comm);
  if (rank == 0) {
    for (int p = 0; p < size; ++p) offsets[p + 1] = offsets[p] + counts[p];
    all.resize(offsets[size]);
  }
  MPI_Gatherv(mine.data(), count, type, all.data(), counts.data(), offsets.data(), type, 0, comm);
}
}  // namespace

Records gatherToRoot(const Records& mine, MPI_Comm comm) {
  Records all;
  all.width = mine.width;
  gatherv(mine.index, all.index, MPI_LONG_LONG, comm);
  gatherv(mine.values, all.values, MPI_DOUBLE, comm);
  return all;
}

}  // namespace tribos::stack
