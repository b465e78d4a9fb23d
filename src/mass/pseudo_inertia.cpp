#include "rigid/mass/pseudo_inertia.hpp"

#include <cmath>

#include <Eigen/Cholesky>
#include <Eigen/Eigenvalues>

#include "rigid/common/error.hpp"
#include "rigid/common/format.hpp"

namespace rigid::mass {

Eigen::Matrix4d pseudo_inertia(const MassProperties& mp) {
  // [Wensing2017, eq. 9]: Σ about O from I_O (the parallel-axis theorem, as inertia_about), h = m c
  const Eigen::Vector3d& c = mp.com();
  const Eigen::Matrix3d I_O =
      mp.inertia_com() +
      mp.mass() * (c.squaredNorm() * Eigen::Matrix3d::Identity() - c * c.transpose());
  Eigen::Matrix4d J;
  J.topLeftCorner<3, 3>() = 0.5 * I_O.trace() * Eigen::Matrix3d::Identity() - I_O;
  J.topRightCorner<3, 1>() = mp.mass() * c;
  J.bottomLeftCorner<1, 3>() = mp.mass() * c.transpose();
  J(3, 3) = mp.mass();
  RIGID_REQUIRE(J.allFinite(),
                "the pseudo-inertia of the body (mass {} kg, center of mass {} m from the origin) "
                "overflows a double; expected finite entries (state the body in smaller units, or "
                "about an origin nearer its center of mass)",
                mp.mass(), to_string(c.transpose()));
  return J;
}

MassProperties from_pseudo_inertia(const Eigen::Matrix4d& J) {
  RIGID_REQUIRE(J.allFinite(), "pseudo-inertia J must be finite, got {}", to_string(J));
  const double scale = J.cwiseAbs().maxCoeff();
  const double asym = (J - J.transpose()).cwiseAbs().maxCoeff();
  RIGID_REQUIRE(asym <= 1e-12 * scale,
                "pseudo-inertia J must be symmetric: its largest |J(i,j) − J(j,i)| is {} (above "
                "1e-12 of its largest element {}); J = {}",
                asym, scale, to_string(J));
  const Eigen::Matrix4d S = 0.5 * (J + J.transpose());
  const double m = S(3, 3);
  RIGID_REQUIRE(m > 0.0,
                "pseudo-inertia J is not positive semidefinite: its mass J(3,3) must be positive, "
                "got {} kg",
                m);
  const Eigen::Vector3d c = S.topRightCorner<3, 1>() / m;
  // the second moment about the COM is the Schur complement Σ − h hᵀ/m; J ⪰ 0 ⇔ m > 0 and
  // Σ_C ⪰ 0, and Σ_C ⪰ 0 ⇔ the principal moments of I_C = tr(Σ_C) 1 − Σ_C satisfy the
  // triangle inequalities, which MassProperties::check reports with the margin
  const Eigen::Matrix3d Sigma_C = S.topLeftCorner<3, 3>() - m * c * c.transpose();
  const Eigen::Matrix3d I_C = Sigma_C.trace() * Eigen::Matrix3d::Identity() - Sigma_C;
  // the eigenvalues σ of Σ_C give the principal moments I_k = tr σ − σ_k, and
  // I_i + I_j − I_k = 2 σ_k: a negative σ_k is the triangle inequality failing by 2|σ_k|
  const Eigen::Vector3d sigma =
      Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d>(Sigma_C, Eigen::EigenvaluesOnly).eigenvalues();
  const double tol = MassProperties::kRelativeTolerance * std::abs(I_C.trace());
  if (!(sigma(0) >= -tol)) {
    const Eigen::Vector3d moments = (sigma.sum() - sigma.array()).matrix();
    RIGID_THROW("pseudo-inertia J is not positive semidefinite (not a physical body): the second "
                "moments about the center of mass, eigenvalues of Σ − h hᵀ/m, are ({:.6g}, {:.6g}, "
                "{:.6g}) kg·m² and must not be negative; the principal moments ({:.6g}, {:.6g}, "
                "{:.6g}) kg·m² violate the triangle inequality I₁ + I₂ ≥ I₃ by {:.6g} kg·m²",
                sigma(0), sigma(1), sigma(2), moments(2), moments(1), moments(0), -2.0 * sigma(0));
  }
  return MassProperties(m, c, I_C);
}

namespace {

// J = U Uᵀ with U upper triangular: reversing rows and columns turns it into the usual
// lower Cholesky factor, P J P = (P U P)(P U P)ᵀ with P the reversal
Eigen::Matrix4d upper_cholesky(const Eigen::Matrix4d& J, bool& ok) {
  const Eigen::Matrix4d P = Eigen::Matrix4d::Identity().rowwise().reverse();
  const Eigen::LLT<Eigen::Matrix4d> llt(P * J * P);
  ok = llt.info() == Eigen::Success;
  const Eigen::Matrix4d L = llt.matrixL();
  return P * L * P;
}

}  // namespace

LogCholesky log_cholesky(const MassProperties& mp) {
  const Eigen::Matrix4d J = pseudo_inertia(mp);
  // a flat or a line body (plate, rod, point) has a zero second moment about its COM: J is
  // singular and U has a zero on its diagonal, whose logarithm does not exist
  const Eigen::Matrix3d Sigma_C =
      0.5 * mp.inertia_com().trace() * Eigen::Matrix3d::Identity() - mp.inertia_com();
  const Eigen::Vector3d sigma =
      Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d>(Sigma_C, Eigen::EigenvaluesOnly).eigenvalues();
  RIGID_REQUIRE(sigma(0) > 1e-12 * sigma.sum(),
                "log-Cholesky parameters need a positive definite pseudo-inertia, but this body's "
                "second moments about its center of mass are ({:.6g}, {:.6g}, {:.6g}) kg·m²: the "
                "smallest is not above 1e-12 of their sum (a flat, line or point body: plate, "
                "rod, hoop, disk, point mass), so J is singular and has no logarithm",
                sigma(0), sigma(1), sigma(2));
  bool ok = false;
  const Eigen::Matrix4d U = upper_cholesky(J, ok);
  // (J is finite and, by the check above, positive definite; a factorisation that fails
  // anyway has lost it in rounding: entries of very different magnitudes)
  RIGID_REQUIRE(ok && U(3, 3) > 0.0 && U.allFinite(),
                "the Cholesky factorisation of the pseudo-inertia J = {} failed in rounding "
                "(mass {} kg, center of mass {} m from the origin); expected a J whose entries "
                "are of comparable magnitudes (state the body in other units, or about an origin "
                "nearer its center of mass)",
                to_string(J), mp.mass(), to_string(mp.com().transpose()));
  // [Rucker2022, eq. 8]: U = e^α [[e^d₁, s₁₂, s₁₃, t₁], [0, e^d₂, s₂₃, t₂], [0, 0, e^d₃, t₃], [0, 0, 0, 1]]
  const double ea = U(3, 3);
  const Eigen::Matrix4d V = U / ea;
  LogCholesky theta;
  theta << std::log(ea), std::log(V(0, 0)), std::log(V(1, 1)), std::log(V(2, 2)), V(0, 1), V(1, 2), V(0, 2),
      V(0, 3), V(1, 3), V(2, 3);
  RIGID_REQUIRE(theta.allFinite(),
                "the log-Cholesky parameters of the body (mass {} kg, center of mass {} m from "
                "the origin) overflow a double; expected finite parameters (state the body in "
                "other units)",
                mp.mass(), to_string(mp.com().transpose()));
  return theta;
}

Eigen::Matrix4d pseudo_inertia_from_log_cholesky(const LogCholesky& theta) {
  RIGID_REQUIRE(theta.allFinite(), "log-Cholesky parameters must be finite, got {}", to_string(theta.transpose()));
  Eigen::Matrix4d U;
  U << std::exp(theta(1)), theta(4), theta(6), theta(7),  //
      0.0, std::exp(theta(2)), theta(5), theta(8),        //
      0.0, 0.0, std::exp(theta(3)), theta(9),             //
      0.0, 0.0, 0.0, 1.0;
  U *= std::exp(theta(0));
  const Eigen::Matrix4d J = U * U.transpose();
  RIGID_REQUIRE(J.allFinite(),
                "log-Cholesky parameters {} give a pseudo-inertia that overflows a double",
                to_string(theta.transpose()));
  return J;
}

MassProperties from_log_cholesky(const LogCholesky& theta) {
  return from_pseudo_inertia(pseudo_inertia_from_log_cholesky(theta));
}

}  // namespace rigid::mass
