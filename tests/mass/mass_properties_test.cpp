#include "rigid/mass/mass_properties.hpp"

#include <cmath>
#include <limits>
#include <optional>
#include <string>
#include <vector>

#include <Eigen/Geometry>
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "rigid/lie/se3.hpp"
#include "rigid/lie/so3.hpp"
#include "support/expect_error.hpp"
#include "support/tolerance.hpp"

namespace rigid {
namespace {

using test::ulps;

// A generic valid body: principal moments (1, 2, 2.5) in a rotated frame, COM off origin.
MassProperties generic_body() {
  const Eigen::Matrix3d R =
      Eigen::AngleAxisd(0.7, Eigen::Vector3d(1, 2, 3).normalized()).toRotationMatrix();
  const Eigen::Matrix3d I = R * Eigen::Vector3d(1.0, 2.0, 2.5).asDiagonal() * R.transpose();
  return MassProperties(3.0, Eigen::Vector3d(0.1, -0.2, 0.3), I);
}

TEST(MassProperties, ConstructorKeepsValues) {
  const Eigen::Matrix3d I = Eigen::Vector3d(1, 2, 3).asDiagonal();
  const MassProperties mp(2.0, Eigen::Vector3d(1, 2, 3), I);
  EXPECT_EQ(mp.mass(), 2.0);
  EXPECT_EQ(mp.com(), Eigen::Vector3d(1, 2, 3));
  EXPECT_EQ(mp.inertia_com(), I);
  EXPECT_FALSE(mp.invalidity_report().has_value());
}

TEST(MassProperties, RejectsBadMass) {
  const Eigen::Matrix3d I = Eigen::Matrix3d::Identity();
  EXPECT_RIGID_ERROR(MassProperties(0.0, Eigen::Vector3d::Zero(), I),
                     "MassProperties(): mass must be positive and finite, got 0 kg");
  EXPECT_RIGID_ERROR(MassProperties(-1.0, Eigen::Vector3d::Zero(), I), "got -1 kg");
  EXPECT_RIGID_ERROR(MassProperties(std::nan(""), Eigen::Vector3d::Zero(), I), "got nan kg");
  EXPECT_RIGID_ERROR(
      MassProperties(std::numeric_limits<double>::infinity(), Eigen::Vector3d::Zero(), I),
      "got inf kg");
}

TEST(MassProperties, RejectsNonFiniteComAndInertia) {
  EXPECT_RIGID_ERROR(MassProperties(1.0, Eigen::Vector3d(0, std::nan(""), 0),
                                    Eigen::Matrix3d::Identity()),
                     "center of mass must be finite, got [0, nan, 0] m");
  Eigen::Matrix3d I = Eigen::Matrix3d::Identity();
  I(1, 1) = std::numeric_limits<double>::infinity();
  EXPECT_RIGID_ERROR(MassProperties(1.0, Eigen::Vector3d::Zero(), I), "inertia tensor must be finite");
}

TEST(MassProperties, RejectsATensorWhoseTraceOverflows) {
  // every entry is finite, but tr I = 3.5e308 is not: the tolerance 1e-10·tr I would be inf and
  // accept anything (a URDF inertial of 1e308 kg·m² rotated by rpy came out with ixx = inf)
  const Eigen::Matrix3d I = Eigen::Vector3d(1e308, 1e308, 1.5e308).asDiagonal();
  EXPECT_RIGID_ERROR(MassProperties(1.0, Eigen::Vector3d::Zero(), I),
                     "inertia tensor is too large: the sum of its diagonal elements overflows");
}

TEST(MassProperties, HugeProductsOfInertiaAreRefusedNotOverflowed) {
  // tr I = 3 is fine, but I₁₂ = 1e308 makes the tensor indefinite (eigenvalues 1 ± 1e308);
  // ½ (I + Iᵀ) computed as a sum overflowed to inf, the eigenvalues became NaN and the
  // NaN comparisons let the tensor through
  Eigen::Matrix3d I = Eigen::Matrix3d::Identity();
  I(0, 1) = I(1, 0) = 1e308;
  EXPECT_RIGID_ERROR(MassProperties(1.0, Eigen::Vector3d::Zero(), I),
                     "not positive semidefinite: principal moments (-1e+308");
}

TEST(MassProperties, LargeValidTensorIsKeptExactly) {
  // a valid tensor near the top of the double range (tr I = 1.795e308, I₃ ≤ I₁ + I₂) is stored
  // as given: ½ I + ½ Iᵀ is exact
  const Eigen::Matrix3d I = Eigen::Vector3d(4.5e307, 4.5e307, 8.95e307).asDiagonal();
  EXPECT_EQ(MassProperties(1.0, Eigen::Vector3d::Zero(), I).inertia_com(), I);
}

TEST(MassProperties, RejectsAsymmetric) {
  Eigen::Matrix3d I = Eigen::Matrix3d::Identity();
  I(0, 1) = 0.1;
  EXPECT_RIGID_ERROR(MassProperties(1.0, Eigen::Vector3d::Zero(), I),
                     "inertia tensor is not symmetric: |I(0,1) − I(1,0)| = 0.1 kg·m²");
}

TEST(MassProperties, RejectsIndefiniteWithMargin) {
  // products of inertia with the wrong sign convention can make the tensor indefinite:
  // [[1, 2, 0], [2, 1, 0], [0, 0, 2]] has eigenvalues −1, 2, 3.
  Eigen::Matrix3d I;
  I << 1, 2, 0, 2, 1, 0, 0, 0, 2;
  EXPECT_RIGID_ERROR(MassProperties(1.0, Eigen::Vector3d::Zero(), I),
                     "not positive semidefinite: principal moments (-1");
  EXPECT_RIGID_ERROR(MassProperties(1.0, Eigen::Vector3d::Zero(), I), "below 0 by 1");
}

TEST(MassProperties, RejectsTriangleInequalityWithMargin) {
  const Eigen::Matrix3d I = Eigen::Vector3d(1, 2, 4).asDiagonal();
  EXPECT_RIGID_ERROR(MassProperties(1.0, Eigen::Vector3d::Zero(), I),
                     "principal moments (1, 2, 4) kg·m² violate I₁ + I₂ ≥ I₃ by 1 kg·m²");
  // the boundary case (a flat plate) is legal.
  const Eigen::Matrix3d plate = Eigen::Vector3d(1, 2, 3).asDiagonal();
  EXPECT_NO_THROW(MassProperties(1.0, Eigen::Vector3d::Zero(), plate));
}

TEST(MassProperties, ToleranceBoundaryIsTheStatedOne) {
  // tol = 1e-10·tr I ≈ 6e-10 here. Rotated so that the check cannot rely on a diagonal.
  const Eigen::Matrix3d R =
      Eigen::AngleAxisd(1.1, Eigen::Vector3d(1, -1, 2).normalized()).toRotationMatrix();
  auto tensor = [&](double I3) {
    return Eigen::Matrix3d(R * Eigen::Vector3d(1, 2, I3).asDiagonal() * R.transpose());
  };
  EXPECT_FALSE(MassProperties::check(1.0, Eigen::Vector3d::Zero(), tensor(3.0 + 1e-10)).has_value());
  EXPECT_THAT(MassProperties::check(1.0, Eigen::Vector3d::Zero(), tensor(3.0 + 2e-9)).value_or(""),
              ::testing::HasSubstr("violate I₁ + I₂ ≥ I₃ by 2e-09 kg·m²"));
  // a smallest moment of −1e-10 is inside the tolerance, −1e-8 is not
  const Eigen::Matrix3d near_zero = R * Eigen::Vector3d(-1e-10, 2, 2).asDiagonal() * R.transpose();
  EXPECT_FALSE(MassProperties::check(1.0, Eigen::Vector3d::Zero(), near_zero).has_value());
  const Eigen::Matrix3d negative = R * Eigen::Vector3d(-1e-8, 2, 2).asDiagonal() * R.transpose();
  EXPECT_THAT(MassProperties::check(1.0, Eigen::Vector3d::Zero(), negative).value_or(""),
              ::testing::HasSubstr("not positive semidefinite"));
}

TEST(MassProperties, PointMassHasZeroInertia) {
  EXPECT_NO_THROW(MassProperties(1.0, Eigen::Vector3d(1, 1, 1), Eigen::Matrix3d::Zero()));
}

TEST(MassProperties, ParallelAxisClosedForm) {
  // point-like body (I_C = 0) of mass 2 at (1, 2, 3): I_O = m (|c|² 1 − c cᵀ).
  const MassProperties mp(2.0, Eigen::Vector3d(1, 2, 3), Eigen::Matrix3d::Zero());
  const Eigen::Matrix3d I_O = mp.inertia_about(Eigen::Vector3d::Zero());
  Eigen::Matrix3d expected;
  expected << 2 * 13, -2 * 2, -2 * 3, -2 * 2, 2 * 10, -2 * 6, -2 * 3, -2 * 6, 2 * 5;
  EXPECT_TRUE(I_O.isApprox(expected, ulps(4))) << I_O;
}

TEST(MassProperties, ParallelAxisRoundTrip) {
  const MassProperties mp = generic_body();
  const Eigen::Vector3d q(0.5, 1.5, -2.0);
  // I_Q = I_C + m(...); going back from I_Q with the opposite offset recovers I_C.
  const Eigen::Matrix3d I_Q = mp.inertia_about(q);
  const Eigen::Vector3d d = mp.com() - q;
  const Eigen::Matrix3d back =
      I_Q - mp.mass() * (d.squaredNorm() * Eigen::Matrix3d::Identity() - d * d.transpose());
  // round-off at the scale of m|d|² ≈ 3·6.5 ≈ 20.
  EXPECT_TRUE(back.isApprox(mp.inertia_com(), ulps(64, 20.0))) << back;
}

TEST(MassProperties, InertiaAboutAxis) {
  // solid-sphere-like isotropic body: about a parallel axis at distance 2, I = I₀ + m·4.
  const MassProperties mp(1.5, Eigen::Vector3d::Zero(), 0.4 * Eigen::Matrix3d::Identity());
  const double I = mp.inertia_about_axis(Eigen::Vector3d(2, 0, 0), Eigen::Vector3d::UnitZ());
  EXPECT_NEAR(I, 0.4 + 1.5 * 4.0, ulps(4, 6.4));
  // an axis through the point along the offset: no parallel-axis contribution.
  EXPECT_NEAR(mp.inertia_about_axis(Eigen::Vector3d(2, 0, 0), Eigen::Vector3d::UnitX()), 0.4,
              ulps(4));
  EXPECT_RIGID_ERROR((void)mp.inertia_about_axis(Eigen::Vector3d::Zero(), Eigen::Vector3d(1, 1, 0)),
                     "axis direction must be a unit vector");
}

TEST(MassProperties, RotationKeepsPrincipalMoments) {
  const MassProperties mp = generic_body();
  const Eigen::Matrix3d R =
      Eigen::AngleAxisd(-2.1, Eigen::Vector3d(-1, 0.3, 0.2).normalized()).toRotationMatrix();
  const MassProperties rot = mp.rotated(R);
  EXPECT_TRUE(rot.principal_axes().moments.isApprox(Eigen::Vector3d(1, 2, 2.5), ulps(32)));
  EXPECT_TRUE(rot.com().isApprox(R * mp.com(), ulps(8)));
  EXPECT_RIGID_ERROR((void)mp.rotated(2.0 * R), "R_AB must be a rotation matrix");
}

TEST(MassProperties, TransformMovesCom) {
  const MassProperties mp = generic_body();
  const Eigen::Matrix3d R = Eigen::AngleAxisd(0.5, Eigen::Vector3d::UnitZ()).toRotationMatrix();
  const Eigen::Vector3d p(1, 2, 3);
  const MassProperties t = mp.transformed(R, p);
  EXPECT_TRUE(t.com().isApprox(R * mp.com() + p, ulps(8)));
  EXPECT_TRUE(t.inertia_com().isApprox(R * mp.inertia_com() * R.transpose(), ulps(16)));
  const MassProperties s = mp.shifted(p);
  EXPECT_TRUE(s.com().isApprox(mp.com() + p, ulps(4)));
  EXPECT_EQ(s.inertia_com(), mp.inertia_com());
}

TEST(MassProperties, TransformBySE3MatchesMatrixForm) {
  const MassProperties mp = generic_body();
  const Eigen::Matrix3d R = Eigen::AngleAxisd(0.7, Eigen::Vector3d(1, 2, 3).normalized()).toRotationMatrix();
  const Eigen::Vector3d p(-1, 0.5, 2);
  const SE3d X(SO3d::from_matrix(R), p);
  const MassProperties t = mp.transformed(X);
  // The quaternion round trip perturbs R by a few ulps; compare with the closed form.
  EXPECT_TRUE(t.com().isApprox(R * mp.com() + p, ulps(16)));
  EXPECT_TRUE(t.inertia_com().isApprox(R * mp.inertia_com() * R.transpose(), ulps(32)));
  EXPECT_TRUE(mp.rotated(SO3d::from_matrix(R)).com().isApprox(R * mp.com(), ulps(16)));
}

TEST(MassProperties, PrincipalAxesGeneric) {
  const MassProperties mp = generic_body();
  const PrincipalAxes pa = mp.principal_axes();
  EXPECT_TRUE(pa.moments.isApprox(Eigen::Vector3d(1, 2, 2.5), ulps(32)));
  EXPECT_NEAR(pa.R_BP.determinant(), 1.0, ulps(16));
  const Eigen::Matrix3d rebuilt = pa.R_BP * pa.moments.asDiagonal() * pa.R_BP.transpose();
  EXPECT_TRUE(rebuilt.isApprox(mp.inertia_com(), ulps(64)));
}

TEST(MassProperties, PrincipalAxesSphericalIsIdentity) {
  const MassProperties mp(1.0, Eigen::Vector3d::Zero(), 0.4 * Eigen::Matrix3d::Identity());
  const PrincipalAxes pa = mp.principal_axes();
  EXPECT_EQ(pa.R_BP, Eigen::Matrix3d::Identity());
}

TEST(MassProperties, PrincipalAxesAxisymmetricIsStable) {
  // cylinder-like: I = diag(2, 2, 1) about z. Distinct (smallest) axis z, other two x, y.
  const MassProperties mp(1.0, Eigen::Vector3d::Zero(), Eigen::Vector3d(2, 2, 1).asDiagonal());
  const PrincipalAxes pa = mp.principal_axes();
  EXPECT_TRUE(pa.moments.isApprox(Eigen::Vector3d(1, 2, 2), ulps(8)));
  EXPECT_TRUE(pa.R_BP.col(0).isApprox(Eigen::Vector3d::UnitZ(), ulps(8)));
  EXPECT_NEAR(pa.R_BP.determinant(), 1.0, ulps(8));
  // the in-plane axes are B's own x or y (up to order/sign), never a round-off direction.
  EXPECT_NEAR(std::abs(pa.R_BP.col(1).dot(Eigen::Vector3d::UnitZ())), 0.0, ulps(8));
  EXPECT_NEAR(pa.R_BP.col(1).cwiseAbs().maxCoeff(), 1.0, ulps(8));
}

TEST(MassProperties, CombineTwoPointMasses) {
  // two unit masses at ±x: COM at 0, I = diag(0, 2, 2).
  const MassProperties a(1.0, Eigen::Vector3d(1, 0, 0), Eigen::Matrix3d::Zero());
  const MassProperties b(1.0, Eigen::Vector3d(-1, 0, 0), Eigen::Matrix3d::Zero());
  const MassProperties c = combine(a, b);
  EXPECT_EQ(c.mass(), 2.0);
  EXPECT_TRUE(c.com().isZero(ulps(1)));
  EXPECT_TRUE(c.inertia_com().isApprox(Eigen::Vector3d(0, 2, 2).asDiagonal().toDenseMatrix(), ulps(4)));
  EXPECT_RIGID_ERROR((void)combine(std::span<const MassProperties>{}), "needs at least one body");
}

TEST(MassProperties, SubtractUndoesCombine) {
  const MassProperties a = generic_body();
  const MassProperties b(1.0, Eigen::Vector3d(2, 0, 0), Eigen::Vector3d(0.1, 0.2, 0.25).asDiagonal());
  const MassProperties back = subtract(combine(a, b), b);
  EXPECT_NEAR(back.mass(), a.mass(), ulps(4, 4));
  EXPECT_TRUE(back.com().isApprox(a.com(), 1e-14));  // round-off of m·|c| ≈ 2 over m = 3
  EXPECT_TRUE(back.inertia_com().isApprox(a.inertia_com(), ulps(256, 10)));
}

TEST(MassProperties, SubtractRefusesNonPhysical) {
  const MassProperties a(1.0, Eigen::Vector3d::Zero(), 0.1 * Eigen::Matrix3d::Identity());
  const MassProperties heavy(2.0, Eigen::Vector3d::Zero(), 0.1 * Eigen::Matrix3d::Identity());
  EXPECT_RIGID_ERROR((void)subtract(a, heavy), "subtract(): the hole (2 kg) is at least as heavy");
  // a lighter "hole" with far more inertia than the body: negative moments remain.
  const MassProperties wide(0.5, Eigen::Vector3d::Zero(), Eigen::Matrix3d::Identity());
  EXPECT_RIGID_ERROR((void)subtract(a, wide), "the body minus the hole is not physical");
}

TEST(MassProperties, Formatter) {
  const MassProperties mp(2.0, Eigen::Vector3d(0, 0, 0.5), Eigen::Vector3d(1, 2, 3).asDiagonal());
  EXPECT_EQ(fmt::format("{}", mp),
            "MassProperties{mass: 2 kg, com: [0, 0, 0.5] m, inertia_com: [1, 0, 0; 0, 2, 0; 0, 0, 3] "
            "kg·m²}");
}

TEST(MassProperties, RefusesResultsThatOverflow) {
  const MassProperties heavy(1e308, Eigen::Vector3d(1, 0, 0), Eigen::Matrix3d::Identity());
  // m |d|² = 1e308 · 100 overflows
  EXPECT_RIGID_ERROR((void)heavy.inertia_about(Eigen::Vector3d(-9, 0, 0)),
                     "inertia_about(): the inertia about the point [-9, 0, 0] m overflows a double");
  EXPECT_RIGID_ERROR((void)heavy.inertia_about_axis(Eigen::Vector3d(0, 10, 0), Eigen::Vector3d::UnitX()),
                     "overflows a double");
  const MassProperties far(1.0, Eigen::Vector3d(1e308, 0, 0), Eigen::Matrix3d::Identity());
  EXPECT_RIGID_ERROR((void)far.shifted(Eigen::Vector3d(1e308, 0, 0)),
                     "shifted(): the shifted center of mass [1e+308, 0, 0] + [1e+308, 0, 0] m "
                     "overflows a double");
  EXPECT_RIGID_ERROR((void)far.transformed(Eigen::Matrix3d::Identity(), Eigen::Vector3d(1e308, 0, 0)),
                     "transformed(): the result overflows a double");
  // two bodies of 1e308 kg: the total mass overflows
  EXPECT_RIGID_ERROR((void)combine(heavy, heavy), "combine(): the result overflows a double");
}

// check_rotational_moments passes moments clear of the bounds without the tensor check: its
// verdict and message must be those of the full check (MassProperties::check of diag(moments),
// then a moment above 1e-10·ΣI) for moments on, near and far from every bound.
TEST(RotationalMoments, TheFastPathGivesTheFullChecksVerdict) {
  auto full = [](const Eigen::Vector3d& m) -> std::optional<std::string> {
    if (!m.allFinite()) return "not finite";
    if (auto r = MassProperties::check(1.0, Eigen::Vector3d::Zero(), m.asDiagonal().toDenseMatrix())) return r;
    if (!(m.minCoeff() > MassProperties::kRelativeTolerance * m.sum())) return "zero moment";
    return std::nullopt;
  };
  std::vector<Eigen::Vector3d> cases = {{1, 2, 3}, {1, 1, 1}, {0, 1, 1}, {-1, 2, 3}, {1, 1, 2}, {1, 1, 2.1}};
  // I₃ = I₁ + I₂ + k·1e-10·ΣI·s and a smallest moment of k·1e-10·ΣI·s, for k around the
  // tolerances of both paths (1 and 2 in units of 1e-10·ΣI) and scales s from 1e-200 to 1e200
  for (const double scale : {1e-200, 1e-3, 1.0, 7.0, 1e5, 1e200}) {
    for (const double k : {-3.0, -1.0, -0.5, 0.0, 0.5, 0.99, 1.0, 1.01, 1.5, 1.99, 2.0, 2.01, 3.0, 1e3}) {
      const double a = 1.0 * scale;
      const double b = 2.0 * scale;
      const double sum = 2 * (a + b);
      cases.push_back({a, b, a + b + k * 1e-10 * sum});
      cases.push_back({k * 1e-10 * (2 * b), b, b});
    }
  }
  for (const Eigen::Vector3d& m : cases) {
    const std::optional<std::string> fast = check_rotational_moments(m);
    const std::optional<std::string> reference = full(m);
    ASSERT_EQ(fast.has_value(), reference.has_value()) << m.transpose();
    if (fast && *reference != "zero moment") {
      EXPECT_EQ(*fast, *reference) << m.transpose();
    }
  }
}

}  // namespace
}  // namespace rigid
