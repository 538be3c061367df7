#include "PatchRecovery.hpp"

#include <algorithm>
#include <cmath>

#include "tribos/fem/ElementKernels.hpp"

namespace tribos::stack {

namespace {
using mesh::ElementType;
using Vec3 = std::array<double, 3>;
constexpr int kTerms = 9;  // the non-constant monomials of a quadratic in 3 variables

/// The elements of block b around each node (CSR over all nodes; other blocks' nodes empty).
struct NodeElements {
  std::vector<LO> ptr, elements;
  const LO* begin(LO n) const { return elements.data() + ptr[n]; }
  const LO* end(LO n) const { return elements.data() + ptr[n + 1]; }
};

NodeElements nodeElements(const mesh::Mesh& mesh, int b) {
  NodeElements out;
  out.ptr.assign(static_cast<size_t>(mesh.numNodes()) + 1, 0);
  const auto& block = mesh.blocks[b];
  for (LO e = block.first; e < block.first + block.count; ++e)
    for (LO n : mesh.elementNodes(e)) ++out.ptr[n + 1];
  for (LO n = 0; n < mesh.numNodes(); ++n) out.ptr[n + 1] += out.ptr[n];
  out.elements.resize(out.ptr.back());
  std::vector<LO> next(out.ptr.begin(), out.ptr.end() - 1);
  for (LO e = block.first; e < block.first + block.count; ++e)
    for (LO n : mesh.elementNodes(e)) out.elements[next[n]++] = e;
  return out;
}

/// The nodes of block b on its surface: those of the faces that no other element of b shares
/// (faces keyed by their sorted vertices).
std::vector<char> surfaceNodes(const mesh::Mesh& mesh, int b) {
  std::vector<std::pair<std::array<LO, 4>, std::pair<LO, int>>> faces;
  const auto& block = mesh.blocks[b];
  for (LO e = block.first; e < block.first + block.count; ++e)
    for (int s = 0; s < mesh::elementShape(mesh.elementType(e)).numFaces; ++s) {
      const mesh::FaceNodes face = mesh.faceNodes(e, s);
      std::array<LO, 4> key{-1, -1, -1, -1};
      std::copy(face.node, face.node + face.numVertices, key.begin());
      std::sort(key.begin(), key.begin() + face.numVertices);
      faces.push_back({key, {e, s}});
    }
  std::sort(faces.begin(), faces.end());
  std::vector<char> surface(mesh.numNodes(), 0);
  for (size_t i = 0; i < faces.size();) {
    size_t j = i + 1;
    while (j < faces.size() && faces[j].first == faces[i].first) ++j;
    if (j == i + 1) {
      const mesh::FaceNodes face = mesh.faceNodes(faces[i].second.first, faces[i].second.second);
      for (LO n : face) surface[n] = 1;
    }
    i = j;
  }
  return surface;
}

/// The non-constant quadratic monomials at d, and their derivatives d/dd_j.
void monomials(const Vec3& d, double m[kTerms]) {
  const double v[kTerms] = {d[0], d[1], d[2], d[0] * d[0], d[1] * d[1], d[2] * d[2], d[0] * d[1], d[1] * d[2], d[0] * d[2]};
  std::copy(v, v + kTerms, m);
}
void monomialDerivatives(const Vec3& d, double g[kTerms][3]) {
  const double v[kTerms][3] = {{1, 0, 0},        {0, 1, 0},        {0, 0, 1},        {2 * d[0], 0, 0}, {0, 2 * d[1], 0},
                               {0, 0, 2 * d[2]}, {d[1], d[0], 0}, {0, d[2], d[1]}, {d[2], 0, d[0]}};
  for (int k = 0; k < kTerms; ++k) std::copy(v[k], v[k] + 3, g[k]);
}

/// Solves M x = rhs (3 columns) for the symmetric positive definite 9 x 9 M, in place (Cholesky).
void solveSpd(double M[kTerms][kTerms], double rhs[kTerms][3]) {
  for (int j = 0; j < kTerms; ++j) {
    for (int k = 0; k < j; ++k) M[j][j] -= M[j][k] * M[j][k];
    M[j][j] = std::sqrt(M[j][j]);
    for (int i = j + 1; i < kTerms; ++i) {
      for (int k = 0; k < j; ++k) M[i][j] -= M[i][k] * M[j][k];
      M[i][j] /= M[j][j];
    }
  }
  for (int c = 0; c < 3; ++c) {
    for (int i = 0; i < kTerms; ++i) {
      for (int k = 0; k < i; ++k) rhs[i][c] -= M[i][k] * rhs[k][c];
      rhs[i][c] /= M[i][i];
    }
    for (int i = kTerms - 1; i >= 0; --i) {
      for (int k = i + 1; k < kTerms; ++k) rhs[i][c] -= M[k][i] * rhs[k][c];
      rhs[i][c] /= M[i][i];
    }
  }
}

/// du_c/dx_j at `at` from the least-squares quadratic through the displacements of `samples`:
/// coordinates centred on their mean and scaled by their largest offset, the columns of the
/// monomials centred too (so an unresolved monomial, z^2 in a one-layer slab, is a zero
/// column, which the regularisation gives no coefficient instead of trading it against the
/// constant). False when the fit has nothing to stand on.
bool fittedGradient(const mesh::Mesh& mesh, const std::vector<std::array<double, 3>>& u, const std::vector<LO>& samples,
                    LO at, double grad[3][3]) {
  const double count = static_cast<double>(samples.size());
  Vec3 centre{0, 0, 0}, meanU{0, 0, 0};
  for (LO n : samples)
    for (int c = 0; c < 3; ++c) {
      centre[c] += mesh.coords[n][c] / count;
      meanU[c] += u[n][c] / count;
    }
  double scale = 0.0;
  for (LO n : samples)
    for (int c = 0; c < 3; ++c) scale = std::max(scale, std::abs(mesh.coords[n][c] - centre[c]));
  if (!(scale > 0.0)) return false;
  auto local = [&](LO n) { return Vec3{(mesh.coords[n][0] - centre[0]) / scale, (mesh.coords[n][1] - centre[1]) / scale,
                                       (mesh.coords[n][2] - centre[2]) / scale}; };
  double mean[kTerms] = {}, m[kTerms];
  for (LO n : samples) {
    monomials(local(n), m);
    for (int k = 0; k < kTerms; ++k) mean[k] += m[k] / count;
  }
  double M[kTerms][kTerms] = {}, rhs[kTerms][3] = {};
  for (LO n : samples) {
    monomials(local(n), m);
    for (int k = 0; k < kTerms; ++k) m[k] -= mean[k];
    for (int i = 0; i < kTerms; ++i) {
      for (int j = 0; j <= i; ++j) M[i][j] += m[i] * m[j];
      for (int c = 0; c < 3; ++c) rhs[i][c] += m[i] * (u[n][c] - meanU[c]);
    }
  }
  double trace = 0.0;
  for (int i = 0; i < kTerms; ++i) trace += M[i][i];
  if (!(trace > 0.0)) return false;
  // An unresolved monomial (a column of round-off after centring) gets a unit-sized diagonal:
  // its coefficient is then round-off, not round-off over round-off. The rest a bias of 1e-12,
  // so that a quadratic is still reproduced to ~1e-12.
  for (int i = 0; i < kTerms; ++i)
    M[i][i] += (M[i][i] <= 1e-10 * trace / kTerms ? 1.0 : 1e-12) * trace / kTerms;
  solveSpd(M, rhs);
  double g[kTerms][3];
  monomialDerivatives(local(at), g);
  for (int c = 0; c < 3; ++c)
    for (int j = 0; j < 3; ++j) {
      double sum = 0.0;
      for (int k = 0; k < kTerms; ++k) sum += rhs[k][c] * g[k][j];
      grad[c][j] = sum / scale;
    }
  return true;
}

bool isLinear(ElementType type) { return type != ElementType::Tet10; }

/// The patch of node n in its body: the nodes of its elements, and of the elements around
/// those on the surface. `mark` holds per node/element the last patch that took it.
struct PatchBuilder {
  const mesh::Mesh& mesh;
  const NodeElements& around;
  const std::vector<char>& surface;
  std::vector<LO> nodeMark, elementMark;
  std::vector<LO> elements, nodes;

  /// False when an element of the patch is not linear (the node keeps its extrapolated mean).
  bool build(LO n) {
    elements.clear();
    nodes.clear();
    auto addElement = [&](LO e) {
      if (elementMark[e] == n) return;
      elementMark[e] = n;
      elements.push_back(e);
    };
    for (const LO* e = around.begin(n); e != around.end(n); ++e) addElement(*e);
    for (LO e : elements)
      if (!isLinear(mesh.elementType(e))) return false;
    if (surface[n]) {
      const size_t ring = elements.size();
      for (size_t i = 0; i < ring; ++i)
        for (LO m : mesh.elementNodes(elements[i]))
          for (const LO* e = around.begin(m); e != around.end(m); ++e) addElement(*e);
    }
    for (LO e : elements)
      for (LO m : mesh.elementNodes(e))
        if (nodeMark[m] != n) {
          nodeMark[m] = n;
          nodes.push_back(m);
        }
    return true;
  }
};
}  // namespace

void recoverLinearElementStresses(const Scene& scene, const std::vector<std::array<double, 3>>& displacement,
                                  const std::vector<int>& body, StressResults& r) {
  const auto& mesh = scene.mesh;
  for (int b = 0; b < mesh.numBlocks(); ++b) {
    const NodeElements around = nodeElements(mesh, b);
    const std::vector<char> surface = surfaceNodes(mesh, b);
    PatchBuilder patch{mesh, around, surface, std::vector<LO>(mesh.numNodes(), -1),
                       std::vector<LO>(mesh.numElements(), -1), {}, {}};
    const auto& material = scene.materials[b];
    for (LO n = 0; n < mesh.numNodes(); ++n) {
      if (body[n] != b || around.ptr[n] == around.ptr[n + 1]) continue;
      double grad[3][3];
      if (!patch.build(n) || patch.nodes.size() < 10 || !fittedGradient(mesh, displacement, patch.nodes, n, grad))
        continue;
      constexpr int row[6] = {0, 1, 2, 0, 1, 0}, col[6] = {0, 1, 2, 1, 2, 2};
      double eps[6];
      for (int k = 0; k < 6; ++k) eps[k] = 0.5 * (grad[row[k]][col[k]] + grad[col[k]][row[k]]);
      const double trace = eps[0] + eps[1] + eps[2];
      double sigma[6];
      for (int k = 0; k < 6; ++k) r.nodal[k][n] = sigma[k] = 2.0 * material.mu * eps[k] + (k < 3 ? material.lambda * trace : 0.0);
      r.nodalVonMises[n] = fem::vonMisesStress(sigma);
    }
  }
}

}  // namespace tribos::stack
