#pragma once
// Internal to feti/: a component of T-FETI (BlockKernels.hpp lists them): the coarse space,
// G = R^T B^T on this rank's rows of B in its compact form (CoarseRows; paper Sec. 4.2), G x
// and G^T a, the coarse problem G G^T (CoarseProblem.hpp) and the projector
// P = I - G^T (G G^T)^-1 G with SMALSE-M's coarse coordinates.
#include <memory>
#include <vector>

#include "SubdomainSet.hpp"

namespace tribos::feti {

class CoarseProblem;

/// One entry (row r, subdomain s) of G in the geometric basis of s (CoarseRows): g'_{s,r} =
/// c [e_d; e_k x p~] when row r of B_s has the single term c at component d of a node with
/// scaled coordinates p~ = coords[slot] (code = 4 slot + d), else the 6 numbers full[slot]
/// (code = 4 slot + 3; contact rows with several terms). `index`: the row (G^T a) or x's
/// index on the overlap (G x). 16 bytes instead of 6 doubles and an index.
struct CoarseTerm {
  double c;
  std::uint32_t code;
  LO index;
};
static_assert(sizeof(CoarseTerm) == 16, "one entry of G in 16 bytes");

/// G on this rank's owned rows of B: one entry = one row r and one subdomain s it touches.
/// Stored compactly (issue 9): R_s = R~_s M_s, with R~_s the geometric rigid modes of s
/// (translations e_d and rotations e_k x p~ at the scaled node coordinates p~ = (x - centre_s)
/// / scale_s, fem::rigidBodyModes before its Gram-Schmidt) and M_s (6 x 6) the change of
/// basis, so g_{s,r} = R_s^T b_{s,r}^T = M_s^T g'_{s,r} with g'_{s,r} = R~_s^T b_{s,r}^T. A
/// row of B_s with one term c at (node, d) has g'_{s,r} = c [e_d; (e_k x p~)_d]: a
/// CoarseTerm of 16 bytes (c, slot of p~ and d, row) instead of 6 doubles and an index; the
/// others (contact rows with several terms) keep their 6 numbers g' in `full`. G x applies
/// M_s^T once per subdomain to the sum of g' x_r, G^T a multiplies each g' by M_s a_s: the
/// same G in exact arithmetic, hence the same projector, e, alpha and G G^T; only the
/// rounding changes (doc/measurements/coarse_problem.md).
/// Threads work on fixed chunks of kRowChunk rows; inside a chunk the entries are stored by
/// subdomain ("runs"), then by kind (one loop without branches per kind), then by row, so
/// that G^T a adds each entry's g_{s,r} . a_s into its row's sum in a chunk-sized buffer,
/// runs in ascending subdomain order: every row sums its entries in ascending subdomain
/// order (the rows of one run are distinct, so there is no chain of dependent updates). G x
/// is summed by subdomain instead (ownedTerm, applyGOwnedSubdomains): a subdomain's rows are
/// owned by different ranks on different layouts, its owner has them all (its own block) and
/// reads the same coordinate slots.
/// The by-row view (rowStart, rowSubdomain, rowEntry) serves the set-up (G G^T).
struct CoarseRows {
  GO firstRow = 0;
  LO numRows = 0;
  std::vector<LO> rowStart;       ///< numRows + 1; a row's entries in ascending subdomain order
  std::vector<int> rowSubdomain;  ///< per entry in row order
  std::vector<LO> rowEntry;       ///< per entry in row order: its index in the stored order
  // Stored order: chunk, subdomain, kind (d = 0, 1, 2, full), row.
  std::vector<CoarseTerm> term;   ///< per entry (index: the owned row)
  std::vector<double> coords;     ///< 3 per slot: p~ of a (subdomain, node) that a term reads
  std::vector<double> full;       ///< 6 per slot: g' of an entry with several terms
  std::vector<double> basis;      ///< M_s, 36 per subdomain (row-major: R_s = R~_s M_s)
  std::vector<LO> runStart;       ///< per run + 1: its entries
  std::vector<LO> runGroupStart;  ///< 4 per run + 1: the entries of kind g of run j from 4 j + g
  std::vector<int> runSubdomain;  ///< per run
  std::vector<int> chunkRunStart;  ///< per chunk + 1: its runs
  mutable std::vector<double> rowSum;  ///< numRows: G^T a's sums, each chunk its own rows
  /// G x's terms of the owned subdomains (index: x's index on the overlap; every row of the
  /// subdomain's own block, whichever rank owns the row), one subdomain after the other in
  /// one array, and per owned subdomain its id and where its kinds start
  /// (ownedStart[6 i .. 6 i + 4] into ownedTerm, ownedStart[6 i + 5] = s): G x streams
  /// through two arrays instead of starting a new allocation at every subdomain
  /// (doc/measurements/performance.md, "G x and B_s each in one stream").
  std::vector<CoarseTerm> ownedTerm;
  std::vector<LO> ownedStart;
  int numChunks() const { return static_cast<int>(chunkRunStart.size()) - 1; }
  const double* M(int s) const { return &basis[36 * static_cast<size_t>(s)]; }
  /// g'_{s,r} of a term (the geometric basis).
  void geometric(const CoarseTerm& t, double* g) const;
  /// g_{s,r} = M_s^T g'_{s,r} of the entry `rowOrderEntry` (row view), for G G^T.
  void rowG(LO rowOrderEntry, double* g) const;
};


namespace detail {
/// Subdomains per task of G x (applyGOwnedSubdomains).
constexpr int kGxSubdomains = 8;
/// Slots per entry of the reproducible sums of G G^T.
constexpr int kSlots = core::SumBins::kSlices;
/// A subdomain's frame as it travels: centre (3), scale, M_s (36).
constexpr int kFrame = 40;

/// Row d of the geometric modes at the scaled point p: [e_d; (e_0 x p)_d, (e_1 x p)_d,
/// (e_2 x p)_d] (fem::rigidBodyModes' order, before orthonormalisation).
inline void geometricRow(int d, const double* p, double* v) {
  for (int j = 0; j < 3; ++j) v[j] = j == d ? 1.0 : 0.0;
  const double rotation[3][3] = {{0.0, p[2], -p[1]}, {-p[2], 0.0, p[0]}, {p[1], -p[0], 0.0}};
  for (int k = 0; k < 3; ++k) v[3 + k] = rotation[d][k];
}

/// p~ = (x - centre) / scale: one function, so that every rank computes the same bits.
inline void scaledPoint(const double* frame, const std::array<double, 3>& x, double* p) {
  for (int j = 0; j < 3; ++j) p[j] = (x[j] - frame[j]) / frame[3];
}

/// The frame of a subdomain from its nodes and R (6 columns of n = 3 nodes): centroid, rms
/// radius (the scaled coordinates are O(1), so that R~ is well conditioned), and M with
/// R = R~ M, by the normal equations (R~^T R~) M = R~^T R (R lies in the span of R~ to
/// round-off; R~^T R~ is 6 x 6 and well conditioned after the scaling).
inline void subdomainFrame(const mesh::Mesh& mesh, const std::vector<LO>& nodes, const std::vector<double>& R, double* frame) {
  const size_t count = nodes.size(), n = 3 * count;
  for (int j = 0; j < 4; ++j) frame[j] = 0.0;
  for (LO node : nodes)
    for (int j = 0; j < 3; ++j) frame[j] += mesh.coords[node][j] / static_cast<double>(count);
  double sum = 0.0;
  for (LO node : nodes)
    for (int j = 0; j < 3; ++j) sum += std::pow(mesh.coords[node][j] - frame[j], 2);
  frame[3] = sum > 0.0 ? std::sqrt(sum / static_cast<double>(count)) : 1.0;
  double A[36] = {}, C[36] = {}, v[6], p[3];
  for (size_t k = 0; k < count; ++k) {
    scaledPoint(frame, mesh.coords[nodes[k]], p);
    for (int d = 0; d < 3; ++d) {
      geometricRow(d, p, v);
      for (int i = 0; i < 6; ++i)
        for (int j = 0; j < 6; ++j) {
          A[6 * i + j] += v[i] * v[j];
          C[6 * i + j] += v[i] * R[j * n + 3 * k + d];
        }
    }
  }
  // Cholesky A = L L^T (lower, in place), then M = L^-T L^-1 C column by column.
  for (int j = 0; j < 6; ++j) {
    for (int k = 0; k < j; ++k) A[6 * j + j] -= A[6 * j + k] * A[6 * j + k];
    A[6 * j + j] = std::sqrt(A[6 * j + j]);
    for (int i = j + 1; i < 6; ++i) {
      for (int k = 0; k < j; ++k) A[6 * i + j] -= A[6 * i + k] * A[6 * j + k];
      A[6 * i + j] /= A[6 * j + j];
    }
  }
  double* M = frame + 4;
  for (int c = 0; c < 6; ++c) {
    double y[6];
    for (int i = 0; i < 6; ++i) {
      y[i] = C[6 * i + c];
      for (int k = 0; k < i; ++k) y[i] -= A[6 * i + k] * y[k];
      y[i] /= A[6 * i + i];
    }
    for (int i = 5; i >= 0; --i) {
      for (int k = i + 1; k < 6; ++k) y[i] -= A[6 * k + i] * y[k];
      y[i] /= A[6 * i + i];
    }
    for (int i = 0; i < 6; ++i) M[6 * i + c] = y[i];
  }
}

/// The kind of row i of block b: its component d when it has one term, else 3.
inline int termKind(const SubdomainBlock& b, LO i) { return b.rowPtr[i + 1] - b.rowPtr[i] == 1 ? b.dof[b.rowPtr[i]] % 3 : 3; }

/// y = M^T x (6 x 6, row-major M).
inline void transposedProduct(const double* M, const double* x, double* y) {
  for (int j = 0; j < 6; ++j) {
    double s = 0.0;
    for (int i = 0; i < 6; ++i) s += M[6 * i + j] * x[i];
    y[j] = s;
  }
}

/// y := x - G^T a on the owned rows: the G^T pass of a projection.
void subtractGt(const CoarseRows& G, const double* a, const double* x, double* y);
}  // namespace detail

class CoarseSpace {
 public:
  /// G on the owned rows from the owned subdomains' R_s (their owners send each entry's data to
  /// the row's owner; with several ranks `subdomains` sums its dual products by the same
  /// entries: SubdomainSet::sumEntriesAtRowOwners). Counts into `profile`.
  CoarseSpace(SubdomainSet& subdomains, const mesh::Mesh& mesh, const mesh::Decomposition& decomposition,
              OperatorProfile& profile);
  ~CoarseSpace();
  /// G G^T assembled and factorised (CoarseProblem), once F's traffic is known (the choice of
  /// its precision compares the two). `settings` must outlive this object.
  void setUpProblem(double subdomainBytesPerF, const TotalFetiSettings& settings, std::vector<char> pinnedModes);

  int numCoarse() const { return 6 * subdomains_.numSubdomains(); }  ///< l
  const CoarseRows& rows() const { return *G_; }
  CoarseProblem& problem() const { return *problem_; }

  void applyG(const DualVector& x, std::vector<double>& gx) const;
  void applyGt(const std::vector<double>& a, DualVector& y) const;
  void solve(std::vector<double>& a) const;
  void solveExactly(std::vector<double>& a) const;
  void release() const;
  void keepFactor(bool keep) { keep_ = keep; }
  void project(const DualVector& x, DualVector& y, CoarseCoordinates* ofX = nullptr) const;
  void projectExactly(const DualVector& x, DualVector& y) const;
  void coordinates(const DualVector& x, std::vector<double>& gx, std::vector<double>& a) const;

 private:
  void applyGOwnedSubdomains(const double* xOverlap, double* gx) const;
  void reduce(std::vector<double>& local, double* gx) const;

  SubdomainSet& subdomains_;
  OperatorProfile& profile_;
  std::unique_ptr<CoarseRows> G_;
  std::unique_ptr<CoarseProblem> problem_;
  bool keep_ = false;  ///< release keeps the factor (keepFactor)
  mutable std::vector<double> local_, vector_;
  double gMax_ = 0.0;  ///< max |g_{s,r,j}| over all ranks
};

}  // namespace tribos::feti
