#pragma once
/// \file RootGather.hpp
/// Results go to rank 0 as records (a global index and a few values) of what each rank holds,
/// not as arrays over the whole mesh on every rank: a rank's part of the gathering is as large
/// as its own subdomains, and rank 0 holds the records once (issue 11).
#include <mpi.h>

#include <vector>

namespace tribos::stack {

/// Records of `width` values each: record k is index[k] and values[width k, width (k + 1)).
struct Records {
  int width = 1;
  std::vector<long long> index;
  std::vector<double> values;
  void add(long long i, const double* v) {
    index.push_back(i);
    values.insert(values.end(), v, v + width);
  }
  size_t size() const { return index.size(); }
};

/// Every rank's records, concatenated in rank order, on rank 0 (empty elsewhere). Collective.
Records gatherToRoot(const Records& mine, MPI_Comm comm);

}  // namespace tribos::stack
