#include "rigid/lie/orthogonal.hpp"

#include <Eigen/LU>
#include <Eigen/SVD>

#include "rigid/common/error.hpp"
#include "rigid/common/format.hpp"

namespace rigid {

namespace {
void require_square_finite(const Eigen::MatrixXd& M, const char* function) {
  RIGID_REQUIRE_AS(function, M.rows() == M.cols() && M.rows() > 0, "matrix is {}x{}, expected a non-empty square matrix",
                M.rows(), M.cols());
  RIGID_REQUIRE_AS(function, M.allFinite(), "matrix {} has a non-finite entry", to_string(M));
}
}  // namespace

OrthogonalityReport check_orthogonal(const Eigen::MatrixXd& M, double tol) {
  require_square_finite(M, __func__);
  OrthogonalityReport r;
  const Eigen::MatrixXd I = Eigen::MatrixXd::Identity(M.rows(), M.cols());
  r.defect = (M.transpose() * M - I).cwiseAbs().maxCoeff();
  r.determinant = M.determinant();
  r.orthogonal = r.defect <= tol;
  r.rotation = r.orthogonal && r.determinant > 0.0;
  return r;
}

Eigen::MatrixXd nearest_rotation(const Eigen::MatrixXd& M) {
  require_square_finite(M, __func__);
  const Eigen::JacobiSVD<Eigen::MatrixXd> svd(M, Eigen::ComputeFullU | Eigen::ComputeFullV);
  Eigen::MatrixXd U = svd.matrixU();
  const Eigen::MatrixXd& V = svd.matrixV();
  // argmin over SO(n) of |R − M|_F is U diag(1, …, 1, det(U Vᵀ)) Vᵀ (singular values descending).
  if ((U * V.transpose()).determinant() < 0.0) U.col(U.cols() - 1) *= -1.0;
  return U * V.transpose();
}

}  // namespace rigid
