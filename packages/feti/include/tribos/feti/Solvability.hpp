#pragma once
/// \file Solvability.hpp
/// Before the solve: can the constraints B hold every body? A rigid motion u = R alpha of
/// the bodies with B u = 0 is a direction in which neither the stiffness (K R = 0) nor any
/// row of B acts, so G = R^T B^T loses rank, G G^T is singular and the coarse problem (and
/// with it the solve) fails. Such a motion is an input error — a body that no Dirichlet row
/// and no contact row can hold (a frictionless block free to slide, a cylinder free to
/// spin) — and is reported here, naming the body and the free modes, instead of as an
/// internal error after the solve.
///
/// A contact normal row restrains a body in one sense only (unilateral: the body may still
/// lift off), but that is a question for the QP, whose solution may or may not exist. For
/// the discrete T-FETI problem to be well posed G_I G_I^T must be regular, which is a
/// linear-rank question: a direction in the kernel of B R is exactly one in the kernel of
/// G^T. So the test below treats every row, contact rows included, as bilateral.
///
/// Method: per body b (element block), 6 rigid modes at its nodes — translations e_x, e_y,
/// e_z and rotations e_i x (x - centroid_b) / L_b with L_b the RMS distance of its nodes to
/// the centroid, so that all columns have entries of order one. C = B R (rows x 6 bodies)
/// and the kernel of C is found from the eigenvectors of the small Gram matrix C^T C.
#include <string>
#include <vector>

#include "tribos/feti/ConstraintMatrix.hpp"
#include "tribos/mesh/Decomposition.hpp"

namespace Teuchos {
template <class Ordinal>
class Comm;
}

namespace tribos::feti {

/// Rigid motions of the bodies that no row of B restrains (the kernel of B restricted to the
/// bodies' rigid body modes): one entry per direction of that kernel.
struct FreeMotion {
  std::vector<int> bodies;  ///< element block indices involved, ascending
  /// e.g. `body "steel": translation x`; rotations are about axes through the body's
  /// centroid, and a combination gives coefficients relative to its largest (rotations in
  /// radians times L_b, the body's RMS radius).
  std::string description;
};

/// The kernel of B R, R the 6 rigid modes of every body (above). Its basis is brought to
/// reduced echelon form and ordered by body, then mode, so a kernel spanned by single modes
/// reads as those modes.
///
/// With a communicator each rank forms the products of the rows it owns in B (B split for
/// that many ranks) and the Gram matrix is summed reproducibly: every rank gets the same
/// answer, with the same bits on any number of ranks. Collective. Null: this process, every row.
std::vector<FreeMotion> freeRigidMotions(const mesh::Mesh& mesh, const mesh::Decomposition& decomposition,
                                         const ConstraintMatrix& B, const Teuchos::Comm<int>* comm = nullptr);

/// Throws core::InputError naming the bodies and their free motions if there are any; the
/// message also says what to add: a Dirichlet condition on a node set of the body, friction,
/// or a contact surface against a held body.
void requireRestrainedBodies(const mesh::Mesh& mesh, const mesh::Decomposition& decomposition,
                             const ConstraintMatrix& B, const Teuchos::Comm<int>* comm = nullptr);

}  // namespace tribos::feti
