#include "roller/core/eigenvalues.hpp"

#include <Eigen/Eigenvalues>

#include "roller/core/error.hpp"

namespace roller {

Vec4 symmetric_eigenvalues(const Mat4& a) {
  return Eigen::SelfAdjointEigenSolver<Mat4>(a, Eigen::EigenvaluesOnly).eigenvalues();
}

VecX symmetric_eigenvalues(const MatX& a) {
  return Eigen::SelfAdjointEigenSolver<MatX>(a, Eigen::EigenvaluesOnly).eigenvalues();
}

GeneralizedEigen generalized_symmetric_eigen(const MatX& a, const MatX& b, Eigenvectors vectors) {
  const int options = vectors == Eigenvectors::compute ? Eigen::ComputeEigenvectors : Eigen::EigenvaluesOnly;
  const Eigen::GeneralizedSelfAdjointEigenSolver<MatX> eig(a, b, options);
  if (eig.info() != Eigen::Success) {
    throw NumericalError("generalised symmetric eigenproblem A x = lambda B x failed: B is not positive definite");
  }
  GeneralizedEigen result{eig.eigenvalues(), {}};
  if (vectors == Eigenvectors::compute) result.vectors = eig.eigenvectors();
  return result;
}

}  // namespace roller
