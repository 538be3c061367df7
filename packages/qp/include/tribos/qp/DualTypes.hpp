#pragma once
/// \file DualTypes.hpp
/// What qp/ sees of the world: distributed vectors (Tpetra, each entry owned by one rank)
/// and symmetric operators on them. qp/ knows nothing of meshes or FETI.
#include <Tpetra_Map_decl.hpp>
#include <Tpetra_Vector_decl.hpp>

namespace tribos::qp {

using Map = Tpetra::Map<int, long long>;
using Vector = Tpetra::Vector<double, int, long long>;

/// y = A x for a symmetric positive semidefinite A. Implementations count their applications.
class SymmetricOperator {
 public:
  virtual ~SymmetricOperator() = default;
  virtual void apply(const Vector& x, Vector& y) const = 0;
};

/// The orthogonal projector Q onto Im G^T (so that P = I - Q projects onto Ker G) of the
/// equality constraint G x = 0. With G's rows orthonormalised, ||G x|| = ||Q x||.
class EqualityProjector {
 public:
  virtual ~EqualityProjector() = default;
  virtual void applyQ(const Vector& x, Vector& y) const = 0;
};

}  // namespace tribos::qp
