#include "rigid/lie/son.hpp"

#include <algorithm>
#include <cmath>
#include <functional>
#include <limits>
#include <numbers>
#include <vector>

#include <Eigen/Eigenvalues>  // RealSchur
#include <Eigen/LU>
#include <Eigen/QR>
#include <unsupported/Eigen/MatrixFunctions>

#include "rigid/common/error.hpp"
#include "rigid/common/format.hpp"
#include "rigid/lie/orthogonal.hpp"
#include "lie/detail/interpolation.hpp"
#include "lie/detail/phi.hpp"

namespace rigid {

namespace {

using Eigen::Index;
using Eigen::MatrixXd;
using Eigen::VectorXd;

// One basis element of so(n): W(j, i) = sign, W(i, j) = −sign, i < j.
struct Plane {
  int i, j;
  double sign;
};

// The basis of so(n) in the documented order: pairs (i, j), i < j, in reverse lexicographic
// order, sign (−1)^{i+j+1}. For n = 3 this yields (1,2,+), (0,2,−), (0,1,+), i.e. SO3's hat.
std::vector<Plane> planes(int n) {
  std::vector<Plane> p;
  p.reserve(static_cast<std::size_t>(n * (n - 1) / 2));
  for (int i = n - 2; i >= 0; --i)
    for (int j = n - 1; j > i; --j) p.push_back({i, j, (i + j) % 2 == 1 ? 1.0 : -1.0});
  return p;
}

// The angles and the rotation planes of R from its real Schur form R = Q T Qᵀ. An orthogonal
// matrix is normal, so T is block diagonal up to rounding: 2×2 blocks [[c, −s], [s, c]]
// (a rotation by atan2(s, c) in the plane of two columns of Q) and 1×1 blocks ±1. The −1
// blocks come in pairs when det R = +1; each pair is a rotation by π in its plane.
struct SchurAngles {
  MatrixXd Q;
  MatrixXd Lambda;  // block diagonal skew matrix with the angles: log R = Q Λ Qᵀ
  std::vector<double> angles;
};

SchurAngles schur_angles(const MatrixXd& R) {
  const Index n = R.rows();
  const Eigen::RealSchur<MatrixXd> schur(R);
  RIGID_REQUIRE_AS("SOn::log", schur.info() == Eigen::Success, "the real Schur decomposition of {} did not converge",
                to_string(R));
  const MatrixXd& T = schur.matrixT();
  SchurAngles out{schur.matrixU(), MatrixXd::Zero(n, n), {}};
  std::vector<Index> minus_one;
  Index i = 0;
  while (i < n) {
    if (i + 1 < n && T(i + 1, i) != 0.0) {
      // The closest c + i s to the block (average of its two copies); atan2 keeps full accuracy
      // near 0 and near π, unlike acos of the trace.
      const double c = 0.5 * (T(i, i) + T(i + 1, i + 1));
      const double s = 0.5 * (T(i + 1, i) - T(i, i + 1));
      const double theta = std::atan2(s, c);
      out.Lambda(i + 1, i) = theta;
      out.Lambda(i, i + 1) = -theta;
      out.angles.push_back(std::abs(theta));
      i += 2;
    } else {
      if (T(i, i) < 0.0) minus_one.push_back(i);
      i += 1;
    }
  }
  RIGID_ASSERT(minus_one.size() % 2 == 0);  // det R = +1
  for (std::size_t k = 0; k + 1 < minus_one.size(); k += 2) {
    const Index a = minus_one[k], b = minus_one[k + 1];
    out.Lambda(b, a) = std::numbers::pi;
    out.Lambda(a, b) = -std::numbers::pi;
    out.angles.push_back(std::numbers::pi);
  }
  out.angles.resize(static_cast<std::size_t>(n / 2), 0.0);  // the remaining planes: angle 0
  std::sort(out.angles.begin(), out.angles.end(), std::greater<>());
  return out;
}

void require_same_n(int a, int b, const char* what) {
  RIGID_REQUIRE_AS("SOn", a == b, "{}: SO({}) and SO({}) differ, expected the same n", what, a, b);
}

}  // namespace

int SOn::n_from_dimension(Index m) {
  // n(n−1)/2 = m ⇔ n = (1 + √(1 + 8m))/2; round, then check exactly in integers.
  const int n = static_cast<int>(std::lround(0.5 * (1.0 + std::sqrt(1.0 + 8.0 * static_cast<double>(m)))));
  RIGID_REQUIRE(m >= 1 && n * (n - 1) / 2 == m,
                "tangent vector has {} components, expected n(n−1)/2 for some n ≥ 2 (1, 3, 6, 10, …)",
                m);
  return n;
}

SOn SOn::identity(int n) {
  RIGID_REQUIRE(n >= 2, "n = {}, expected n ≥ 2", n);
  return SOn(MatrixXd::Identity(n, n));
}

SOn SOn::from_matrix(const MatrixXd& R, double tol) {
  RIGID_REQUIRE(R.rows() == R.cols() && R.rows() >= 2,
                "matrix is {}x{}, expected a square matrix of size n ≥ 2", R.rows(), R.cols());
  RIGID_REQUIRE(R.allFinite(), "matrix {} has a non-finite entry", to_string(R));
  const OrthogonalityReport r = check_orthogonal(R, tol);
  RIGID_REQUIRE(r.rotation,
                "matrix {} is not a rotation: orthonormality defect max|RᵀR − I| = {:.3g} "
                "(tolerance {:.3g}), determinant {:.17g} (expected +1)",
                to_string(R), r.defect, tol, r.determinant);
  // Within tol but not to rounding: project, so that the class invariant holds to rounding.
  const double rounding = 8.0 * std::numeric_limits<double>::epsilon() * static_cast<double>(R.rows());
  return SOn(r.defect <= rounding ? R : nearest_rotation(R));
}

MatrixXd SOn::hat(const Tangent& omega) {
  const int n = n_from_dimension(omega.size());
  MatrixXd W = MatrixXd::Zero(n, n);
  const std::vector<Plane> p = planes(n);
  for (std::size_t k = 0; k < p.size(); ++k) {
    const double v = p[k].sign * omega(static_cast<Index>(k));
    W(p[k].j, p[k].i) = v;
    W(p[k].i, p[k].j) = -v;
  }
  return W;
}

SOn::Tangent SOn::vee(const MatrixXd& W, double tol) {
  RIGID_REQUIRE(W.rows() == W.cols() && W.rows() >= 2,
                "matrix is {}x{}, expected a square matrix of size n ≥ 2", W.rows(), W.cols());
  RIGID_REQUIRE(W.allFinite(), "matrix {} has a non-finite entry", to_string(W));
  const double asym = (W + W.transpose()).cwiseAbs().maxCoeff();
  RIGID_REQUIRE(asym <= tol, "matrix {} is not skew-symmetric: max|W + Wᵀ| = {:.3g} (tolerance {:.3g})",
                to_string(W), asym, tol);
  const int n = static_cast<int>(W.rows());
  const std::vector<Plane> p = planes(n);
  Tangent omega(static_cast<Index>(p.size()));
  for (std::size_t k = 0; k < p.size(); ++k) omega(static_cast<Index>(k)) = p[k].sign * W(p[k].j, p[k].i);
  return omega;
}

SOn SOn::exp(const Tangent& omega) {
  RIGID_REQUIRE(omega.allFinite(), "tangent vector {} has a non-finite component",
                to_string(omega.transpose()));
  // Padé 13 with scaling and squaring [Higham2005] rather than the Schur form of W: it is
  // backward stable, needs no eigenvectors (which are ill-determined for repeated angles) and,
  // for skew W, returns an orthogonal matrix (see the header).
  return SOn(MatrixXd(hat(omega).exp()));
}

SOn::Tangent SOn::log() const {
  const SchurAngles s = schur_angles(R_);
  MatrixXd L = s.Q * s.Lambda * s.Q.transpose();
  L = 0.5 * (L - L.transpose());  // exactly skew
  return vee(L);
}

Eigen::VectorXd SOn::angles() const {
  const SchurAngles s = schur_angles(R_);
  return Eigen::Map<const VectorXd>(s.angles.data(), static_cast<Index>(s.angles.size()));
}

MatrixXd SOn::homogeneous() const {
  const Index n = R_.rows();
  MatrixXd T = MatrixXd::Identity(n + 1, n + 1);
  T.topLeftCorner(n, n) = R_;
  return T;
}

// Column l of Ad is vee(R E_l Rᵀ), E_l = σ_l (e_j e_iᵀ − e_i e_jᵀ); its component k (plane
// (p, q), sign σ_k) is σ_k (R E_l Rᵀ)(q, p) = σ_k σ_l (R(q,j) R(p,i) − R(q,i) R(p,j)).
MatrixXd SOn::adjoint() const {
  const std::vector<Plane> pl = planes(n());
  const Index m = static_cast<Index>(pl.size());
  MatrixXd A(m, m);
  for (Index k = 0; k < m; ++k) {
    const Plane& a = pl[static_cast<std::size_t>(k)];
    for (Index l = 0; l < m; ++l) {
      const Plane& b = pl[static_cast<std::size_t>(l)];
      A(k, l) = a.sign * b.sign * (R_(a.j, b.j) * R_(a.i, b.i) - R_(a.j, b.i) * R_(a.i, b.j));
    }
  }
  return A;
}

MatrixXd SOn::ad(const Tangent& omega) {
  const MatrixXd W = hat(omega);
  const Index m = omega.size();
  MatrixXd A(m, m);
  for (Index l = 0; l < m; ++l) {
    const MatrixXd E = hat(Tangent::Unit(m, l));
    A.col(l) = vee(W * E - E * W);
  }
  return A;
}

MatrixXd SOn::right_jacobian(const Tangent& omega) { return detail::phi(-ad(omega)); }
MatrixXd SOn::left_jacobian(const Tangent& omega) { return detail::phi(ad(omega)); }
MatrixXd SOn::right_jacobian_inverse(const Tangent& omega) {
  return right_jacobian(omega).partialPivLu().inverse();
}
MatrixXd SOn::left_jacobian_inverse(const Tangent& omega) {
  return left_jacobian(omega).partialPivLu().inverse();
}

SOn SOn::sample(int n, std::mt19937_64& rng) {
  RIGID_REQUIRE(n >= 2, "n = {}, expected n ≥ 2", n);
  std::normal_distribution<double> normal(0.0, 1.0);
  MatrixXd G(n, n);
  for (Index k = 0; k < G.size(); ++k) G(k) = normal(rng);
  const Eigen::HouseholderQR<MatrixXd> qr(G);
  MatrixXd Q = qr.householderQ();
  const MatrixXd& QR = qr.matrixQR();
  // Householder QR leaves the signs of R's diagonal arbitrary, which biases Q; moving them
  // into Q makes the factorisation unique and Q Haar-distributed on O(n) [Mezzadri2007].
  for (Index i = 0; i < n; ++i)
    if (QR(i, i) < 0.0) Q.col(i) *= -1.0;
  if (Q.determinant() < 0.0) Q.col(0) *= -1.0;
  return SOn(std::move(Q));
}

SOn SOn::interpolate(const SOn& b, double s) const {
  detail::require_finite_fraction("SOn::interpolate", s);
  const Tangent omega = s * (inverse() * b).log();
  // the largest plane angle bounds each tangent entry and is at most √2 times the largest
  const double largest = omega.cwiseAbs().maxCoeff();
  detail::require_interpolated_turn("SOn::interpolate", s, largest, largest);
  return *this * exp(omega);
}

SOn SOn::operator*(const SOn& b) const {
  require_same_n(n(), b.n(), "compose");
  return SOn(R_ * b.R_);
}

VectorXd SOn::operator*(const VectorXd& v) const {
  RIGID_REQUIRE(v.size() == R_.rows(), "vector has {} components, expected {} for SO({})", v.size(),
                R_.rows(), n());
  return R_ * v;
}

bool SOn::is_approx(const SOn& b, double tol) const {
  require_same_n(n(), b.n(), "is_approx");
  return (R_ - b.R_).cwiseAbs().maxCoeff() <= tol;
}

}  // namespace rigid
