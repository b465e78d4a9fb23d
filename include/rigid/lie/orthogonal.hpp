#pragma once

#include <Eigen/Core>

namespace rigid {

/// Result of testing a square matrix for membership in O(n) / SO(n).
struct OrthogonalityReport {
  double defect = 0.0;       ///< max |MᵀM − I| over the entries
  double determinant = 0.0;  ///< det M (±1 for a member of O(n))
  bool orthogonal = false;   ///< defect ≤ tol
  bool rotation = false;     ///< orthogonal and det > 0 (member of SO(n))
};

/// Tests M ∈ O(n) within `tol` on the orthonormality defect.
/// @throws rigid::Error if M is not square, empty, or has a non-finite entry.
[[nodiscard]] OrthogonalityReport check_orthogonal(const Eigen::MatrixXd& M, double tol = 1e-9);

/// The rotation nearest to M in the Frobenius norm (polar decomposition via SVD, with the
/// sign of the smallest singular direction flipped when det M < 0).
/// @throws rigid::Error if M is not square, is empty, or has a non-finite entry.
[[nodiscard]] Eigen::MatrixXd nearest_rotation(const Eigen::MatrixXd& M);

}  // namespace rigid
