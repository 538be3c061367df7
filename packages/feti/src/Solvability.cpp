#include "tribos/feti/Solvability.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <stdexcept>
#include <utility>

#include <Teuchos_CommHelpers.hpp>

#include "tribos/core/Errors.hpp"
#include "tribos/core/Format.hpp"
#include "tribos/core/ReproducibleSum.hpp"
#include "SymmetricEigen.hpp"

namespace tribos::feti {

namespace {

constexpr int kModes = 6;
const char* const kModeNames[kModes] = {"translation x",     "translation y",     "translation z",
                                        "rotation about x", "rotation about y", "rotation about z"};

/// A kernel eigenvalue of C^T C, relative to max(lambda_max, 1). Why 1e-10: every row of B
/// has unit norm and every mode column has entries of order one at each node (rotations
/// are scaled by 1/L_b), so a row that restrains a mode adds about (its share of the mode)^2
/// to C^T C — 1 for a translation, (lever arm / L_b)^2 for a rotation. A body held by one
/// such row while another body has 1e5 rows sits at about 1e-5 of lambda_max, 1e-8 if that
/// row holds a rotation at a lever arm of L_b / 30. A motion that no row restrains gets only
/// round-off: rows that vanish on it exactly (gluing, a normal row against a tangential
/// translation) leave O(eps) in C, and forming and diagonalising C^T C adds
/// O(eps * lambda_max), ~1e-16 relative. 1e-10 lies between (on the two bricks, structured
/// and METIS, tilted or not: restrained >= 8e-3, free <= 3e-16). The floor 1 keeps the test
/// absolute when no row restrains anything (then lambda_max itself is round-off).
constexpr double kKernelTolerance = 1e-10;

/// Where body b's rotations are measured from, and its length L_b (RMS distance of its
/// nodes to the centroid) that scales them to the size of the translations.
struct BodyFrame {
  std::array<double, 3> centroid{};
  double length = 1.0;
};

std::vector<BodyFrame> bodyFrames(const mesh::Mesh& mesh) {
  std::vector<BodyFrame> frames(mesh.numBlocks());
  std::vector<int> seenBy(mesh.numNodes(), -1);  // each node once per body
  for (int b = 0; b < mesh.numBlocks(); ++b) {
    std::vector<LO> nodes;
    const auto& block = mesh.blocks[b];
    for (LO e = block.first; e < block.first + block.count; ++e)
      for (LO n : mesh.elementNodes(e))
        if (seenBy[n] != b) {
          seenBy[n] = b;
          nodes.push_back(n);
        }
    if (nodes.empty()) continue;
    BodyFrame& f = frames[b];
    for (LO n : nodes)
      for (int d = 0; d < 3; ++d) f.centroid[d] += mesh.coords[n][d] / static_cast<double>(nodes.size());
    double sum = 0.0;
    for (LO n : nodes)
      for (int d = 0; d < 3; ++d) sum += std::pow(mesh.coords[n][d] - f.centroid[d], 2);
    const double rms = std::sqrt(sum / static_cast<double>(nodes.size()));
    f.length = rms > 0.0 ? rms : 1.0;
  }
  return frames;
}

/// Component `component` of rigid mode `mode` of a body at point x (fem::rigidBodyModes'
/// order: translations, then e_i x (x - centroid), here scaled by 1 / L_b).
double modeValue(int mode, int component, const std::array<double, 3>& x, const BodyFrame& f) {
  if (mode < 3) return mode == component ? 1.0 : 0.0;
  const int axis = mode - 3;
  const double r[3] = {(x[0] - f.centroid[0]) / f.length, (x[1] - f.centroid[1]) / f.length,
                       (x[2] - f.centroid[2]) / f.length};
  // (e_axis x r)_component: nonzero for the two components other than the axis.
  const int next = (axis + 1) % 3, last = (axis + 2) % 3;
  if (component == next) return -r[last];
  if (component == last) return r[next];
  return 0.0;
}

/// The part of one row of C = B R that comes from one subdomain block (one body).
struct RowPart {
  GO row;
  int body;
  std::array<double, kModes> c;
};

/// A component eliminated from K_s (SubdomainBlock::eliminated) restrains its body as a
/// Dirichlet row would: one part each, counted by the owner of its subdomain (`ranks`: this
/// rank and the number of ranks), numbered after B's rows.
void addEliminatedParts(const mesh::Mesh& mesh, const mesh::Decomposition& decomposition, const ConstraintMatrix& B,
                        const std::vector<BodyFrame>& frames, const std::pair<int, int>& ranks,
                        std::vector<RowPart>& parts) {
  GO next = B.numRows;
  for (int s = 0; s < decomposition.numSubdomains(); ++s) {
    const auto& sub = decomposition.subdomains[s];
    const bool mine = mesh::ownerRank(s, decomposition.numSubdomains(), ranks.second) == ranks.first;
    for (LO dof : B.blocks[s].eliminated) {
      RowPart part{next++, sub.body, {}};
      if (!mine) continue;
      for (int j = 0; j < kModes; ++j) part.c[j] = modeValue(j, dof % 3, mesh.coords[sub.nodes[dof / 3]], frames[sub.body]);
      parts.push_back(part);
    }
  }
}

/// Every (row, body) part of C for the rows [firstRow, endRow), summed over the blocks: a row
/// touches a few subdomains, possibly of different bodies (contact), and only the sum over its
/// copies is the row. The parts are stored once (counted first, no growth by doubling): at
/// 4 000 subdomains every rank held ~100 MB here, the largest item of its set-up
/// (doc/measurements/scalability.md); now a rank holds the parts of its own rows.
std::vector<RowPart> rowsOfC(const mesh::Mesh& mesh, const mesh::Decomposition& decomposition,
                             const ConstraintMatrix& B, const std::vector<BodyFrame>& frames, GO firstRow,
                             GO endRow, const std::pair<int, int>& ranks) {
  auto mine = [&](GO row) { return row >= firstRow && row < endRow; };
  size_t count = 0;
  for (int s = 0; s < decomposition.numSubdomains(); ++s)
    for (GO row : B.blocks[s].rows) count += mine(row) ? 1 : 0;
  std::vector<RowPart> parts;
  parts.reserve(count);
  for (int s = 0; s < decomposition.numSubdomains(); ++s) {
    const auto& sub = decomposition.subdomains[s];
    const auto& block = B.blocks[s];
    for (size_t i = 0; i < block.rows.size(); ++i) {
      if (!mine(block.rows[i])) continue;
      RowPart part{block.rows[i], sub.body, {}};
      for (LO k = block.rowPtr[i]; k < block.rowPtr[i + 1]; ++k) {
        const auto& x = mesh.coords[sub.nodes[block.dof[k] / 3]];
        for (int j = 0; j < kModes; ++j)
          part.c[j] += block.value[k] * modeValue(j, block.dof[k] % 3, x, frames[sub.body]);
      }
      parts.push_back(part);
    }
  }
  addEliminatedParts(mesh, decomposition, B, frames, ranks, parts);
  // Merge the parts of the same (row, body), in subdomain order (a stable sort: the sums do
  // not depend on which rank does them).
  std::stable_sort(parts.begin(), parts.end(),
                   [](const RowPart& a, const RowPart& b) { return a.row != b.row ? a.row < b.row : a.body < b.body; });
  size_t kept = 0;
  for (size_t i = 0; i < parts.size(); ++i)
    if (kept > 0 && parts[kept - 1].row == parts[i].row && parts[kept - 1].body == parts[i].body)
      for (int j = 0; j < kModes; ++j) parts[kept - 1].c[j] += parts[i].c[j];
    else
      parts[kept++] = parts[i];
  parts.resize(kept);
  return parts;
}

/// C^T C (dense, n = 6 * bodies, row-major), summing c_r c_r^T row by row over the rows of
/// every rank (`parts` sorted by row, so the parts of one row are consecutive) with
/// reproducible sums: the same bits on any number of ranks. Every kind of row is included:
/// gluing rows vanish on the rigid motions of one body (up to round-off), and where two
/// blocks share nodes they are what ties the blocks' motions together.
std::vector<double> gramMatrix(const std::vector<RowPart>& parts, int numBodies, const Teuchos::Comm<int>* comm) {
  const int n = kModes * numBodies;
  // The bound and count of the reproducible sums, the same on every rank: the largest |c|
  // (a MAX, exact) and (all parts) x (most parts of one row), integers summed exactly.
  double largest = 0.0;
  long long localCount = static_cast<long long>(parts.size()), perRow = 1;
  for (size_t first = 0; first < parts.size();) {
    size_t last = first;
    while (last < parts.size() && parts[last].row == parts[first].row) ++last;
    perRow = std::max(perRow, static_cast<long long>(last - first));
    first = last;
  }
  for (const RowPart& p : parts)
    for (double c : p.c) largest = std::max(largest, std::abs(c));
  largest = core::globalMax(comm, largest);
  const double maxPerRow = core::globalMax(comm, static_cast<double>(perRow));
  long long allParts = localCount;
  if (comm && comm->getSize() > 1) Teuchos::reduceAll(*comm, Teuchos::REDUCE_SUM, 1, &localCount, &allParts);
  const core::SumBins bins(largest * largest, std::max(1LL, allParts * static_cast<long long>(maxPerRow)));
  constexpr int kSlots = core::SumBins::kSlices;
  std::vector<double> slots(static_cast<size_t>(n) * n * kSlots, 0.0);
  for (size_t first = 0; first < parts.size();) {
    size_t last = first;
    while (last < parts.size() && parts[last].row == parts[first].row) ++last;
    for (size_t a = first; a < last; ++a)
      for (size_t b = first; b < last; ++b)
        for (int i = 0; i < kModes; ++i)
          for (int j = 0; j < kModes; ++j)
            bins.deposit(parts[a].c[i] * parts[b].c[j],
                         &slots[kSlots * (static_cast<size_t>(kModes * parts[a].body + i) * n + kModes * parts[b].body + j)]);
    first = last;
  }
  core::allReduceSlots(comm, slots);
  std::vector<double> gram(static_cast<size_t>(n) * n);
  for (size_t k = 0; k < gram.size(); ++k) gram[k] = core::SumBins::combine(&slots[kSlots * k]);
  return gram;
}

/// Orthonormal basis of the kernel of C (eigenvectors of C^T C below the tolerance).
std::vector<std::vector<double>> kernelBasis(std::vector<double> gram, int n) {
  std::vector<double> vectors;
  const std::vector<double> values = symmetricEigen(gram, n, vectors);
  double largest = 1.0;  // floor: see kKernelTolerance
  for (double v : values) largest = std::max(largest, v);
  std::vector<std::vector<double>> basis;
  for (int j = 0; j < n; ++j)
    if (values[j] <= kKernelTolerance * largest) {
      std::vector<double> v(n);
      for (int i = 0; i < n; ++i) v[i] = vectors[static_cast<size_t>(i) * n + j];
      basis.push_back(v);
    }
  return basis;
}

/// Brings a kernel basis to reduced echelon form (Gauss-Jordan with full pivoting), scales
/// each vector to unit norm and orders the vectors by their pivot (body, then mode). The
/// eigenvectors of a multiple eigenvalue are any basis of its space — (x + y)/sqrt(2) and
/// (x - y)/sqrt(2) for two free translations — whereas in this form each vector owns one
/// mode that the others lack, so a kernel spanned by single modes reads as those modes.
void toEchelonForm(std::vector<std::vector<double>>& basis) {
  const size_t k = basis.size();
  std::vector<std::pair<size_t, std::vector<double>>> byPivot;
  for (size_t i = 0; i < k; ++i) {
    size_t pivotRow = i, pivotColumn = 0;
    double best = -1.0;
    for (size_t r = i; r < k; ++r)
      for (size_t j = 0; j < basis[r].size(); ++j)
        if (std::abs(basis[r][j]) > best) {
          best = std::abs(basis[r][j]);
          pivotRow = r;
          pivotColumn = j;
        }
    std::swap(basis[i], basis[pivotRow]);
    const double pivot = basis[i][pivotColumn];
    for (double& v : basis[i]) v /= pivot;
    for (size_t r = 0; r < k; ++r)
      if (r != i) {
        const double factor = basis[r][pivotColumn];
        for (size_t j = 0; j < basis[r].size(); ++j) basis[r][j] -= factor * basis[i][j];
      }
    byPivot.emplace_back(pivotColumn, std::vector<double>());
  }
  for (size_t i = 0; i < k; ++i) {
    double norm = 0.0;
    for (double x : basis[i]) norm += x * x;
    for (double& x : basis[i]) x /= std::sqrt(norm);
    byPivot[i].second = std::move(basis[i]);
  }
  std::sort(byPivot.begin(), byPivot.end(), [](const auto& a, const auto& b) { return a.first < b.first; });
  for (size_t i = 0; i < k; ++i) basis[i] = std::move(byPivot[i].second);
}

/// "body "steel": translation x" or, for a mix, "body "steel": translation x - 0.5 rotation
/// about z" (coefficients relative to the vector's largest; rotations scaled by 1/L_b).
FreeMotion describe(const std::vector<double>& v, const mesh::Mesh& mesh) {
  double largest = 0.0;
  for (double x : v) largest = std::max(largest, std::abs(x));
  FreeMotion motion;
  for (int b = 0; b < mesh.numBlocks(); ++b) {
    std::string modes;
    for (int j = 0; j < kModes; ++j) {
      const double x = v[kModes * b + j] / largest;
      if (std::abs(x) <= 1e-6) continue;  // round-off left by the elimination
      char coefficient[32] = "";
      if (std::abs(std::abs(x) - 1.0) > 1e-6) std::snprintf(coefficient, sizeof coefficient, "%.3g ", std::abs(x));
      modes += std::string(modes.empty() ? (x < 0 ? "-" : "") : (x < 0 ? " - " : " + ")) + coefficient + kModeNames[j];
    }
    if (modes.empty()) continue;
    motion.description += std::string(motion.bodies.empty() ? "" : ", together with ") + "body \"" +
                          mesh.blocks[b].name + "\": " + modes;
    motion.bodies.push_back(b);
  }
  return motion;
}

}  // namespace

std::vector<FreeMotion> freeRigidMotions(const mesh::Mesh& mesh, const mesh::Decomposition& decomposition,
                                         const ConstraintMatrix& B, const Teuchos::Comm<int>* comm) {
  if (B.blocks.size() != static_cast<size_t>(decomposition.numSubdomains()))
    throw std::invalid_argument("tribos::feti::freeRigidMotions: B has " + std::to_string(B.blocks.size()) +
                                " subdomain blocks, the decomposition " +
                                std::to_string(decomposition.numSubdomains()) + " subdomains");
  const int numBodies = mesh.numBlocks();
  // Each rank the rows it owns in B (B split for comm); without comm every row.
  GO firstRow = 0, endRow = B.numRows;
  if (comm) {
    if (B.firstRowOfRank.size() != static_cast<size_t>(comm->getSize()) + 1)
      throw std::invalid_argument("tribos::feti::freeRigidMotions: B is split for " +
                                  std::to_string(B.firstRowOfRank.size() - 1) + " ranks, the communicator has " +
                                  std::to_string(comm->getSize()));
    firstRow = B.firstRowOfRank[comm->getRank()];
    endRow = B.firstRowOfRank[comm->getRank() + 1];
  }
  const std::pair<int, int> ranks = comm ? std::pair<int, int>{comm->getRank(), comm->getSize()} : std::pair<int, int>{0, 1};
  const auto parts = rowsOfC(mesh, decomposition, B, bodyFrames(mesh), firstRow, endRow, ranks);
  auto basis = kernelBasis(gramMatrix(parts, numBodies, comm), kModes * numBodies);
  toEchelonForm(basis);
  std::vector<FreeMotion> motions;
  for (const auto& v : basis) motions.push_back(describe(v, mesh));
  return motions;
}

/// A body is often free because its contact found nothing: bodies farther apart (or overlapping
/// deeper) than Contact/Search Distance get no contact rows. Empty when every slave node paired.
namespace {
std::string unpairedContactNote(const ConstraintMatrix& B) {
  std::string note;
  for (const auto& found : B.interfaces) {
    if (found.unpairedSlaveNodes == 0) continue;
    std::string nodes;
    for (LO n : found.unpairedSample) nodes += (nodes.empty() ? "" : ", ") + std::to_string(n + 1);
    if (static_cast<GO>(found.unpairedSample.size()) < found.unpairedSlaveNodes) nodes += ", ...";
    note += "\n" + found.label + ": " + std::to_string(found.unpairedSlaveNodes) + " slave node" +
            (found.unpairedSlaveNodes == 1 ? "" : "s") + " found no master face within " + found.list + "/Search Distance = " +
            core::formatNumber(found.searchDistance) + " (nodes " + nodes +
            ", numbered from 1 as in the mesh file), so they have no contact rows: if the bodies are apart (or "
            "overlap) by more than that, move them or raise that distance.";
  }
  return note;
}
}  // namespace

void requireRestrainedBodies(const mesh::Mesh& mesh, const mesh::Decomposition& decomposition,
                             const ConstraintMatrix& B, const Teuchos::Comm<int>* comm) {
  const auto motions = freeRigidMotions(mesh, decomposition, B, comm);
  if (motions.empty()) return;
  std::string message = "the constraints cannot hold every body: " + std::to_string(motions.size()) +
                        " rigid motion" + (motions.size() == 1 ? " is" : "s are") +
                        " free of every Dirichlet and contact row, so the problem has no unique solution";
  for (const auto& m : motions) message += "\n  " + m.description;
  message += unpairedContactNote(B);
  message +=
      "\nHold each of these bodies: clamp a node set of it (Boundary/Dirichlet Node Sets), prescribe the free "
      "components on a node set (Boundary/<name>: Node Set, Components, e.g. a symmetry plane), add friction to "
      "its contact (Contact/Friction Model other than \"None\": a frictionless contact holds it only along "
      "the normals), or give it a contact surface against a held body (Contact/Slave Side Set, Master Side Set).";
  throw core::InputError(message);
}

}  // namespace tribos::feti
