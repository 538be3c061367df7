#include "DirectSolve.hpp"

#include <Amesos2.hpp>
#include <Teuchos_DefaultMpiComm.hpp>
#include <Tpetra_CrsMatrix.hpp>
#include <Tpetra_MultiVector.hpp>

#include <map>
#include <numeric>
#include <stdexcept>

namespace tribos::test {

std::vector<std::array<double, 3>> directSolve(const mesh::Mesh& mesh, const std::vector<fem::Material>& materials,
                                               const fem::Loads& loads, const std::vector<LO>& fixedNodes,
                                               const std::vector<std::pair<LO, LO>>& tied,
                                               const std::vector<std::pair<LO, LO>>& tiedZ) {
  const auto global = fem::assembleGlobal(mesh, materials, loads);
  const LO numNodes = mesh.numNodes();
  // Representative of every dof (tied pairs merged), then unknown numbering.
  const LO numDofs = 3 * numNodes;
  std::vector<LO> rep(numDofs);
  std::iota(rep.begin(), rep.end(), 0);
  for (const auto& [a, b] : tied)
    for (int c = 0; c < 3; ++c) rep[3 * b + c] = rep[3 * a + c];
  for (const auto& [a, b] : tiedZ) rep[3 * b + 2] = rep[3 * a + 2];
  std::vector<char> fixed(numDofs, 0);
  for (LO node : fixedNodes)
    for (int c = 0; c < 3; ++c) fixed[3 * node + c] = 1;
  for (LO d = 0; d < numDofs; ++d)
    if (fixed[d]) fixed[rep[d]] = 1;
  std::vector<LO> unknown(numDofs, -1);
  LO count = 0;
  for (LO d = 0; d < numDofs; ++d)
    if (rep[d] == d && !fixed[d]) unknown[d] = count++;
  auto dofOf = [&](LO dof) -> LO { return unknown[rep[dof]]; };
  const LO n = count;
  std::vector<std::map<LO, double>> rows(n);
  std::vector<double> rhs(n, 0.0);
  for (LO i = 0; i < global.K.n; ++i) {
    const LO ri = dofOf(i);
    if (ri < 0) continue;
    rhs[ri] += global.f[i];
    for (LO k = global.K.rowPtr[i]; k < global.K.rowPtr[i + 1]; ++k) {
      const LO cj = dofOf(global.K.colInd[k]);
      if (cj >= 0) rows[ri][cj] += global.K.values[k];
    }
  }

  using Matrix = Tpetra::CrsMatrix<double, LO, GO>;
  using MultiVector = Tpetra::MultiVector<double, LO, GO>;
  auto comm = Teuchos::rcp(new Teuchos::MpiComm<int>(MPI_COMM_SELF));
  auto map = Teuchos::rcp(new Tpetra::Map<LO, GO>(n, 0, comm));
  auto A = Teuchos::rcp(new Matrix(map, 81));
  for (LO i = 0; i < n; ++i) {
    std::vector<GO> cols;
    std::vector<double> vals;
    for (const auto& [j, v] : rows[i]) {
      cols.push_back(j);
      vals.push_back(v);
    }
    A->insertGlobalValues(i, Teuchos::ArrayView<const GO>(cols), Teuchos::ArrayView<const double>(vals));
  }
  A->fillComplete();
  auto X = Teuchos::rcp(new MultiVector(map, 1)), Bv = Teuchos::rcp(new MultiVector(map, 1));
  {
    auto b = Bv->getLocalViewHost(Tpetra::Access::OverwriteAll);
    for (LO i = 0; i < n; ++i) b(i, 0) = rhs[i];
  }
  auto solver = Amesos2::create<Matrix, MultiVector>("KLU2", A, X, Bv);
  solver->symbolicFactorization().numericFactorization().solve();

  std::vector<std::array<double, 3>> u(numNodes, {0.0, 0.0, 0.0});
  auto x = X->getLocalViewHost(Tpetra::Access::ReadOnly);
  for (LO node = 0; node < numNodes; ++node)
    for (int c = 0; c < 3; ++c) {
      const LO d = dofOf(3 * node + c);
      u[node][c] = d < 0 ? 0.0 : x(d, 0);
    }
  return u;
}

std::vector<std::array<double, 3>> directFrictionlessContact(const mesh::Mesh& mesh,
                                                             const std::vector<fem::Material>& materials,
                                                             const fem::Loads& loads, const std::vector<LO>& fixedNodes,
                                                             const std::vector<std::pair<LO, LO>>& pairs,
                                                             int* iterations) {
  const auto global = fem::assembleGlobal(mesh, materials, loads);
  std::vector<char> active(pairs.size(), 1);
  std::vector<std::array<double, 3>> u;
  for (int it = 1; it <= 50; ++it) {
    std::vector<std::pair<LO, LO>> tiedZ;
    for (size_t i = 0; i < pairs.size(); ++i)
      if (active[i]) tiedZ.push_back(pairs[i]);
    u = directSolve(mesh, materials, loads, fixedNodes, {}, tiedZ);
    // Contact force on the slave: (K u - f) at its z dof; compression pushes it down (< 0).
    std::vector<double> flat(3 * u.size()), Ku(flat.size());
    for (size_t k = 0; k < u.size(); ++k)
      for (int c = 0; c < 3; ++c) flat[3 * k + c] = u[k][c];
    global.K.apply(flat.data(), Ku.data());
    std::vector<char> next(pairs.size(), 0);
    for (size_t i = 0; i < pairs.size(); ++i) {
      const auto [s, m] = pairs[i];
      const double pressure = -(Ku[3 * s + 2] - global.f[3 * s + 2]);
      const double penetration = u[s][2] - u[m][2];
      next[i] = active[i] ? pressure > 0.0 : penetration > 0.0;
    }
    if (next == active) {
      if (iterations) *iterations = it;
      return u;
    }
    active = next;
  }
  throw std::runtime_error("directFrictionlessContact: the active set did not settle in 50 iterations");
}

}  // namespace tribos::test
