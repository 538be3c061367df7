// The multipliers of one pairing carried to another (CarriedMultipliers.hpp).
#include "tribos/feti/CarriedMultipliers.hpp"

#include <array>
#include <unordered_map>

namespace tribos::feti {

namespace {
/// Every row's multiplier of `B` on every rank, in row order.
std::vector<double> gatherAll(const ConstraintMatrix& B, const std::vector<double>& mine, MPI_Comm comm) {
  int numRanks = 1;
  MPI_Comm_size(comm, &numRanks);
  std::vector<int> counts(numRanks), starts(numRanks);
  for (int r = 0; r < numRanks; ++r) {
    starts[r] = static_cast<int>(B.firstRowOfRank[r]);
    counts[r] = static_cast<int>(B.firstRowOfRank[r + 1] - B.firstRowOfRank[r]);
  }
  std::vector<double> all(static_cast<size_t>(B.numRows));
  MPI_Allgatherv(mine.data(), static_cast<int>(mine.size()), MPI_DOUBLE, all.data(), counts.data(), starts.data(),
                 MPI_DOUBLE, comm);
  return all;
}

/// The rows of one kind in row order.
std::vector<GO> rowsOfKind(const ConstraintMatrix& B, RowKind kind) {
  std::vector<GO> rows;
  for (GO r = 0; r < B.numRows; ++r)
    if (B.kind[static_cast<size_t>(r)] == kind) rows.push_back(r);
  return rows;
}

/// A contact node's force on the master (sum over its rows of direction x scale x lambda).
std::array<double, 3> nodeForce(const ContactNode& node, const std::vector<double>& all) {
  std::array<double, 3> force{};
  for (int d = 0; d < 3; ++d)
    if (const GO row = node.row(d); row >= 0)
      for (int c = 0; c < 3; ++c) force[c] += node.direction(d)[c] * node.scale(d) * all[static_cast<size_t>(row)];
  return force;
}
}  // namespace

std::vector<double> carryMultipliers(const ConstraintMatrix& from, const std::vector<double>& lambdaOfFrom,
                                     const ConstraintMatrix& to, MPI_Comm comm) {
  int rank = 0;
  MPI_Comm_rank(comm, &rank);
  const std::vector<double> all = gatherAll(from, lambdaOfFrom, comm);
  const GO first = to.firstRowOfRank[rank], end = to.firstRowOfRank[rank + 1];
  std::vector<double> out(static_cast<size_t>(end - first), 0.0);
  for (RowKind kind : {RowKind::Gluing, RowKind::Dirichlet}) {
    const std::vector<GO> before = rowsOfKind(from, kind), after = rowsOfKind(to, kind);
    if (before.size() != after.size()) continue;
    for (size_t i = 0; i < after.size(); ++i)
      if (after[i] >= first && after[i] < end) out[static_cast<size_t>(after[i] - first)] = all[before[i]];
  }
  std::unordered_map<LO, const ContactNode*> pairedBefore;
  for (const auto& node : from.contact) pairedBefore[node.slaveNode] = &node;
  for (const auto& node : to.contact) {
    if (node.normalRow < first || node.normalRow >= end) continue;  // its rows are another rank's
    const auto found = pairedBefore.find(node.slaveNode);
    if (found == pairedBefore.end()) continue;
    const std::array<double, 3> force = nodeForce(*found->second, all);
    for (int d = 0; d < 3; ++d) {
      const GO row = node.row(d);
      if (row < 0) continue;
      double along = 0.0;
      for (int c = 0; c < 3; ++c) along += node.direction(d)[c] * force[c];
      out[static_cast<size_t>(row - first)] = along / node.scale(d);
    }
  }
  return out;
}

std::vector<double> multipliersFromNodalForces(const ConstraintMatrix& B, const std::vector<double>& normal,
                                               const std::vector<double>& t1, const std::vector<double>& t2,
                                               int rank) {
  const GO first = B.firstRowOfRank[rank], end = B.firstRowOfRank[rank + 1];
  std::vector<double> out(static_cast<size_t>(end - first), 0.0);
  const std::vector<double>* forces[3] = {&normal, &t1, &t2};
  for (const auto& node : B.contact) {
    if (node.normalRow < first || node.normalRow >= end) continue;  // its rows are another rank's
    const size_t n = static_cast<size_t>(node.slaveNode);
    for (int d = 0; d < 3; ++d)
      if (const GO row = node.row(d); row >= 0 && n < forces[d]->size())
        out[static_cast<size_t>(row - first)] = (*forces[d])[n] / node.scale(d);
  }
  return out;
}

}  // namespace tribos::feti
