#pragma once
// Eigenvalues of symmetric matrices, behind one translation unit (src/core/eigenvalues.cpp).
// GCC 12 spends about 10 s instantiating Eigen's SelfAdjointEigenSolver for each matrix type, and
// every file that used it paid that again, in both CI builds (CONTRIBUTING.md, "Build time").
#include "roller/core/types.hpp"

namespace roller {

// Ascending eigenvalues of a symmetric matrix (its lower triangle is read).
Vec4 symmetric_eigenvalues(const Mat4& a);
VecX symmetric_eigenvalues(const MatX& a);

enum class Eigenvectors { skip, compute };

// A x = lambda B x with A symmetric and B symmetric positive definite: ascending eigenvalues and,
// if asked for, the B-normalised eigenvectors as columns.
struct GeneralizedEigen {
  VecX values;
  MatX vectors;
};

// Throws NumericalError when the decomposition fails (B not positive definite).
GeneralizedEigen generalized_symmetric_eigen(const MatX& a, const MatX& b, Eigenvectors vectors);

}  // namespace roller
