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
                                               const std::vector<std::pair<LO, LO>>& tied) {
  const auto global = fem::assembleGlobal(mesh, materials, loads);
  const LO numNodes = mesh.numNodes();
  // Representative of every node (tied pairs merged), then unknown numbering.
  std::vector<LO> rep(numNodes);
  std::iota(rep.begin(), rep.end(), 0);
  for (const auto& [a, b] : tied) rep[b] = rep[a];
  std::vector<char> fixed(numNodes, 0);
  for (LO n : fixedNodes) fixed[n] = 1;
  for (LO n = 0; n < numNodes; ++n)
    if (fixed[n]) fixed[rep[n]] = 1;
  std::vector<LO> unknown(numNodes, -1);
  LO count = 0;
  for (LO n = 0; n < numNodes; ++n)
    if (rep[n] == n && !fixed[n]) unknown[n] = count++;
  auto dofOf = [&](LO dof) -> LO {
    const LO u = unknown[rep[dof / 3]];
    return u < 0 ? -1 : 3 * u + dof % 3;
  };
  const LO n = 3 * count;
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

}  // namespace tribos::test
