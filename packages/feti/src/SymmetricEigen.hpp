#pragma once
// Internal to feti/: the eigen decomposition of a small dense symmetric matrix (the rigid-body
// Gram matrices of Solvability.cpp and EliminatedComponents.cpp, at most 6 x bodies square).
#include <vector>

namespace tribos::feti {

/// Cyclic Jacobi rotations: returns the eigenvalues of the n x n row-major symmetric A (which
/// it overwrites) and the eigenvectors as the columns of `vectors` (row-major, orthonormal).
std::vector<double> symmetricEigen(std::vector<double>& A, int n, std::vector<double>& vectors);

}  // namespace tribos::feti
