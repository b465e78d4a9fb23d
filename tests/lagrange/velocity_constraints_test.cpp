// Velocity (nonholonomic) constraints A(q, t) q̇ + a(q, t) = 0 (src/lagrange/velocity_constraints.cpp):
// the Chaplygin sleigh and the rolling disk against their closed forms, energy, the residual
// and its Baumgarte decay, the multipliers as contact forces, and the refusals.
#include "rigid/lagrange/system.hpp"

#include <cmath>
#include <numbers>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "support/expect_error.hpp"
#include "support/tolerance.hpp"

namespace rigid::lagrange {
namespace {

using integrate::Method;
using ::testing::HasSubstr;

// ---- the Chaplygin sleigh --------------------------------------------------------------------
// Contact point (x, y), heading θ, centre of mass a ahead of the contact on the blade's line:
// c = (x + a cos θ, y + a sin θ), T = ½ m |ċ|² + ½ I θ̇², blade: −sin θ ẋ + cos θ ẏ = 0.
// With v = ẋ cos θ + ẏ sin θ and ω = θ̇ [Bloch2015, ch. 1]: v̇ = a ω², ω̇ = −(m a/J) v ω, J = I + m a².
struct Sleigh {
  double m = 1.0, I = 0.1, a = 0.3, v0 = 0.5, w0 = 2.0;
  [[nodiscard]] double J() const { return I + m * a * a; }
  [[nodiscard]] double V() const { return std::sqrt(v0 * v0 + J() * w0 * w0 / m); }
  [[nodiscard]] double s(double t) const { return a * m * V() / J() * t + std::atanh(v0 / V()); }
  [[nodiscard]] double v(double t) const { return V() * std::tanh(s(t)); }
  [[nodiscard]] double w(double t) const { return w0 * std::cosh(s(0)) / std::cosh(s(t)); }
  // θ(t) = sgn(ω0) √(J/m)/a (gd s − gd s0), gd s = 2 atan(tanh(s/2)) = ∫₀ˢ sech
  [[nodiscard]] double theta(double t) const {
    auto gd = [](double x) { return 2 * std::atan(std::tanh(x / 2)); };
    return std::copysign(1.0, w0) * std::sqrt(J() / m) / a * (gd(s(t)) - gd(s(0)));
  }

  [[nodiscard]] SystemSpec spec() const {
    SystemSpec spec;
    spec.parameters = {{"m", m}, {"I", I}, {"a", a}};
    spec.coordinates = {{"x", 0.0, v0}, {"y", 0.0, 0.0}, {"theta", 0.0, w0}};
    spec.lagrangian = "m/2*((x_dot - a*sin(theta)*theta_dot)^2 + (y_dot + a*cos(theta)*theta_dot)^2)"
                      " + I/2*theta_dot^2";
    spec.velocity_constraints = {{"blade", {{"x", "-sin(theta)"}, {"y", "cos(theta)"}}, "", {}}};
    return spec;
  }
};

TEST(VelocityConstraints, ChaplyginSleighMatchesItsClosedForm) {
  const Sleigh sl;
  const System sys(sl.spec());
  EXPECT_EQ(sys.num_velocity_constraints(), 1);
  EXPECT_EQ(sys.velocity_constraint_names(), std::vector<std::string>{"blade"});
  // x and y appear in the blade's row: their momenta are not conserved
  EXPECT_TRUE(sys.cyclic_coordinates().empty());
  const Trajectory tr = sys.simulate({.t_end = 3.0, .tolerance = 1e-12, .output_dt = 0.05});
  ASSERT_EQ(tr.mu.cols(), 1);
  ASSERT_EQ(tr.velocity_constraint_names, std::vector<std::string>{"blade"});
  const double E0 = 0.5 * (sl.m * sl.v0 * sl.v0 + sl.J() * sl.w0 * sl.w0);
  for (Eigen::Index k = 0; k < tr.t.size(); ++k) {
    const double t = tr.t[k], th = tr.q(k, 2);
    const double v = tr.q_dot(k, 0) * std::cos(th) + tr.q_dot(k, 1) * std::sin(th);
    const double w = tr.q_dot(k, 2);
    // dopri5 at 1e-12 on O(1) values over 3 s: global errors of a few 1e-11; 1e-9 leaves room
    EXPECT_NEAR(v, sl.v(t), 1e-9) << "t = " << t;
    EXPECT_NEAR(w, sl.w(t), 1e-9) << "t = " << t;
    EXPECT_NEAR(th, sl.theta(t), 1e-9) << "t = " << t;
    // the blade's force on the body is sideways, μ (−sin θ, cos θ): it is m times the sideways
    // acceleration of the centre of mass, v ω + a ω̇ = v ω I/J
    EXPECT_NEAR(tr.mu(k, 0), sl.m * sl.I * v * w / sl.J(), 1e-9) << "t = " << t;
    // ideal constraint forces do no work: E = ½ (m v² + J ω²) is the initial one
    EXPECT_NEAR(tr.energy[k], E0, 1e-10 * E0) << "t = " << t;
    // the residual stays at the integrator's tolerance
    EXPECT_LE(tr.velocity_constraint_residual[k], 1e-10) << "t = " << t;
  }
  // the turning dies out: the heading tends to θ∞ = sgn(ω0) √(J/m)/a (π/2 − gd s0)
  EXPECT_LT(std::abs(tr.q_dot(tr.t.size() - 1, 2)), 0.05 * sl.w0);
}

TEST(VelocityConstraints, SleighWithItsCentreOnTheContactGoesRoundACircle) {
  // a = 0: v̇ = 0 and ω̇ = 0, so the contact point runs round a circle of radius v0/ω0
  Sleigh sl;
  sl.a = 0.0;
  const System sys(sl.spec());
  const Trajectory tr = sys.simulate({.t_end = 4.0, .tolerance = 1e-12, .output_dt = 0.1});
  const double R = sl.v0 / sl.w0;  // centre at (0, R): the motion starts along +x at the origin
  for (Eigen::Index k = 0; k < tr.t.size(); ++k) {
    const double t = tr.t[k];
    // tolerance as above (dopri5 at 1e-12, O(1) values)
    EXPECT_NEAR(tr.q(k, 0), R * std::sin(sl.w0 * t), 1e-9) << "t = " << t;
    EXPECT_NEAR(tr.q(k, 1), R * (1 - std::cos(sl.w0 * t)), 1e-9) << "t = " << t;
    EXPECT_NEAR(tr.q_dot(k, 2), sl.w0, 1e-9) << "t = " << t;
  }
}

TEST(VelocityConstraints, ResidualDecaysAtTwiceTheBaumgarteRate) {
  // at a state off the constraint, the accelerations make ċ = −2α c exactly (the holonomic
  // rows' g̈ + 2α ġ + α² g = 0 with g ≡ 0); c = −sin θ ẋ + cos θ ẏ, so
  // ċ = −sin θ ẍ + cos θ ÿ − θ̇ (cos θ ẋ + sin θ ẏ)
  const System sys(Sleigh{}.spec());
  const Eigen::Vector3d q(0.2, -0.1, 0.7), qd(0.4, 0.9, -1.1);
  const double c = -std::sin(q[2]) * qd[0] + std::cos(q[2]) * qd[1];
  ASSERT_GT(std::abs(c), 0.1);
  EXPECT_NEAR(sys.velocity_constraint_residual(0.0, q, qd)[0], c, test::ulps(8, 1.0));
  for (const double alpha : {0.0, 3.0, 10.0}) {
    Eigen::VectorXd qdd, mu;
    sys.accelerations(0.0, q, qd, qdd, mu, alpha);
    ASSERT_EQ(mu.size(), 1);
    const double c_dot = -std::sin(q[2]) * qdd[0] + std::cos(q[2]) * qdd[1] -
                         qd[2] * (std::cos(q[2]) * qd[0] + std::sin(q[2]) * qd[1]);
    // a solve of a 3 × 3 system with O(1) entries and a few products: some ulps of |α c| + 1
    EXPECT_NEAR(c_dot, -2 * alpha * c, test::ulps(64, 1.0 + 2 * alpha)) << "alpha = " << alpha;
  }
}

TEST(VelocityConstraints, InitialVelocitiesOffTheConstraintAreRefusedOrProjected) {
  SystemSpec spec = Sleigh{}.spec();
  spec.coordinates[1].velocity = 0.25;  // sideways: c = 0.25 m/s
  const System sys(spec);
  EXPECT_RIGID_ERROR((void)sys.simulate({.t_end = 0.1}),
                     "initial velocities violate velocity constraint 'blade': |A q̇ + a| = 0.25");
  const Trajectory tr = sys.simulate({.t_end = 0.1, .project_initial = true});
  // q̇ ← q̇ − Aᵀ (A Aᵀ)⁻¹ c with A = (0, 1, 0) at θ = 0: the sideways velocity is removed
  EXPECT_NEAR(tr.q_dot(0, 1), 0.0, test::ulps(4, 1.0));
  EXPECT_NEAR(tr.q_dot(0, 0), Sleigh{}.v0, test::ulps(4, 1.0));
  EXPECT_LE(tr.velocity_constraint_residual.maxCoeff(), 1e-9);
}

TEST(VelocityConstraints, FixedStepMethodsKeepTheResidualSmallAndVerletIsRefused) {
  const System sys(Sleigh{}.spec());
  // rk4 at h = 1e-3: local errors O(h⁵) ≈ 1e-15 per step, and the stabilisation pulls the
  // residual back at rate 2α = 20/s; 1e-10 bounds what accumulates over 2 s
  const Trajectory tr = sys.simulate({.t_end = 2.0, .method = Method::kRk4, .dt = 1e-3, .output_dt = 0.1});
  EXPECT_LE(tr.velocity_constraint_residual.maxCoeff(), 1e-10);
  EXPECT_RIGID_ERROR((void)sys.simulate({.t_end = 0.1, .method = Method::kStormerVerlet}),
                     "stormer_verlet needs");
}

// ---- the rolling disk ------------------------------------------------------------------------
// Contact point (x, y), heading ψ, lean θ (from the vertical, about the direction of travel),
// spin φ; centre r above the contact in the disk's plane; thin disk I1 = m r²/4, I3 = m r²/2.
// Rolling: ẋ = r cos ψ φ̇, ẏ = r sin ψ φ̇ (the disk's material contact point at rest).
struct Disk {
  double m = 0.5, r = 0.1, g = 9.81;
  [[nodiscard]] SystemSpec spec(double lean, double psi_dot, double phi_dot) const {
    SystemSpec spec;
    spec.parameters = {{"m", m}, {"r", r}, {"g", g}};
    spec.coordinates = {{"x", 0.0, r * phi_dot}, {"y", 0.0, 0.0}, {"psi", 0.0, psi_dot},
                        {"theta", lean, 0.0}, {"phi", 0.0, phi_dot}};
    Body coin;
    coin.name = "coin";
    // thin disk in its xy-plane (axis z), from its closed form, not the catalogue
    coin.mass.mass = "m";
    coin.mass.inertia = {Expression("m*r^2/4"), Expression("m*r^2/4"), Expression("m*r^2/2"),
                         Expression("0"), Expression("0"), Expression("0")};
    coin.position = {Expression("x + r*sin(psi)*sin(theta)"), Expression("y - r*cos(psi)*sin(theta)"),
                     Expression("r*cos(theta)")};
    coin.rotations = {{Eigen::Vector3d::UnitZ(), "psi"}, {Eigen::Vector3d::UnitX(), "theta - pi/2"},
                      {Eigen::Vector3d::UnitZ(), "phi"}};
    spec.bodies = {coin};
    spec.gravity_W = Eigen::Vector3d(0, 0, -g);
    spec.velocity_constraints = {{"roll_x", {{"x", "1"}, {"phi", "-r*cos(psi)"}}, "", {}},
                                 {"roll_y", {{"y", "1"}, {"phi", "-r*sin(psi)"}}, "", {}}};
    return spec;
  }
  // the spin about the axis w3 = φ̇ + Ω sin θ of the steady motion with lean θ and heading rate
  // Ω: I1 Ω² sin θ cos θ − (I3 + m r²) w3 Ω cos θ = m g r sin θ (angular momentum about the
  // centre against the contact force's torque; docs/lagrange.md)
  [[nodiscard]] double steady_w3(double lean, double Omega) const {
    const double I1 = m * r * r / 4, I3 = m * r * r / 2, s = std::sin(lean), c = std::cos(lean);
    return (I1 * Omega * Omega * s * c - m * g * r * s) / ((I3 + m * r * r) * Omega * c);
  }
};

TEST(VelocityConstraints, UprightDiskRollsStraight) {
  const Disk disk;
  const double phi_dot = 20.0;  // v = 2 m/s, above the upright disk's stability speed √(g r/3)
  const System sys(disk.spec(0.0, 0.0, phi_dot));
  const Trajectory tr = sys.simulate({.t_end = 2.0, .tolerance = 1e-12, .output_dt = 0.1});
  const double E0 = tr.energy[0];
  for (Eigen::Index k = 0; k < tr.t.size(); ++k) {
    const double t = tr.t[k];
    // x = r φ̇ t, everything else at rest (dopri5 at 1e-12: errors ≲ 1e-11 on O(1) values)
    EXPECT_NEAR(tr.q(k, 0), disk.r * phi_dot * t, 1e-9) << "t = " << t;
    EXPECT_NEAR(tr.q(k, 1), 0.0, 1e-9);
    EXPECT_NEAR(tr.q(k, 3), 0.0, 1e-9);
    EXPECT_NEAR(tr.q_dot(k, 4), phi_dot, 1e-9);
    // no force is needed to roll straight on
    EXPECT_NEAR(tr.mu(k, 0), 0.0, 1e-9);
    EXPECT_NEAR(tr.mu(k, 1), 0.0, 1e-9);
    EXPECT_NEAR(tr.energy[k], E0, 1e-10 * E0);
  }
}

TEST(VelocityConstraints, TiltedDiskKeepsItsSteadyCircle) {
  const Disk disk;
  const double lean = 0.3, Omega = -2.0;
  const double w3 = disk.steady_w3(lean, Omega), phi_dot = w3 - Omega * std::sin(lean);
  const System sys(disk.spec(lean, Omega, phi_dot));
  // two turns (2π/|Ω| = π s each)
  const Trajectory tr = sys.simulate({.t_end = 6.3, .tolerance = 1e-12, .output_dt = 0.05});
  const double E0 = tr.energy[0], rho = disk.r * phi_dot / Omega;  // signed radius
  for (Eigen::Index k = 0; k < tr.t.size(); ++k) {
    const double t = tr.t[k], psi = Omega * t;
    // dopri5 at 1e-12 over 6.3 s on O(1)–O(10) values: errors of 1e-10; 1e-8 leaves room
    EXPECT_NEAR(tr.q(k, 3), lean, 1e-8) << "t = " << t;
    EXPECT_NEAR(tr.q(k, 2), psi, 1e-8) << "t = " << t;
    EXPECT_NEAR(tr.q_dot(k, 4), phi_dot, 1e-8) << "t = " << t;
    // the contact point's circle: x = ρ sin ψ, y = ρ (1 − cos ψ)
    EXPECT_NEAR(tr.q(k, 0), rho * std::sin(psi), 1e-8) << "t = " << t;
    EXPECT_NEAR(tr.q(k, 1), rho * (1 - std::cos(psi)), 1e-8) << "t = " << t;
    // the contact force's horizontal part turns the centre (speed r w3) with the heading:
    // m r w3 Ω (−sin ψ, cos ψ), and the rows of A are the x and y directions, so μ is it
    EXPECT_NEAR(tr.mu(k, 0), -disk.m * disk.r * w3 * Omega * std::sin(psi), 1e-8) << "t = " << t;
    EXPECT_NEAR(tr.mu(k, 1), disk.m * disk.r * w3 * Omega * std::cos(psi), 1e-8) << "t = " << t;
    EXPECT_NEAR(tr.energy[k], E0, 1e-10 * E0) << "t = " << t;
    EXPECT_LE(tr.velocity_constraint_residual[k], 1e-10) << "t = " << t;
  }
}

TEST(VelocityConstraints, DiskOffTheSteadyRelationWobbles) {
  // the closed form discriminates: 2% more spin than the relation asks makes the lean oscillate
  // by far more than the 1e-8 the steady test allows
  const Disk disk;
  const double lean = 0.3, Omega = -2.0;
  const double phi_dot = 1.02 * (disk.steady_w3(lean, Omega) - Omega * std::sin(lean));
  const Trajectory tr = System(disk.spec(lean, Omega, phi_dot))
                            .simulate({.t_end = 2.0, .tolerance = 1e-10, .output_dt = 0.05});
  EXPECT_GT((tr.q.col(3).array() - lean).abs().maxCoeff(), 1e-4);
}

TEST(VelocityConstraints, EquationsShowTheMultipliersAndTheRows) {
  const Equations eq = System(Sleigh{}.spec()).equations();
  ASSERT_EQ(eq.text.size(), 3u);
  EXPECT_THAT(eq.text[0], HasSubstr("mu_blade"));
  EXPECT_THAT(eq.latex[0], HasSubstr("\\mu_{\\mathrm{blade}}"));
  ASSERT_EQ(eq.constraints_text.size(), 1u);
  EXPECT_THAT(eq.constraints_text[0], HasSubstr("x_dot"));
  EXPECT_THAT(eq.constraints_text[0], HasSubstr("= 0"));
}

// ---- refusals --------------------------------------------------------------------------------

SystemSpec plane_spec(std::vector<VelocityConstraint> rows) {
  SystemSpec spec;
  spec.coordinates = {{"x", 0.0, 0.0}, {"y", 0.0, 0.0}};
  spec.lagrangian = "x_dot^2/2 + y_dot^2/2";
  spec.velocity_constraints = std::move(rows);
  return spec;
}

TEST(VelocityConstraints, NonlinearInTheVelocitiesIsRefused) {
  EXPECT_RIGID_ERROR(System(plane_spec({{"k", {{"x", "y_dot"}}, "", {}}})),
                     "coefficient of 'x': depends on the velocity 'y_dot', so the constraint is "
                     "not linear in the velocities");
  EXPECT_RIGID_ERROR(System(plane_spec({{"k", {}, "x_dot^2 - 1", {}}})),
                     "term: is not linear in the velocities (∂²/∂x_dot∂x_dot = 2 ≠ 0)");
  EXPECT_RIGID_ERROR(System(plane_spec({{"k", {}, "sin(x_dot)", {}}})), "not linear in the velocities");
  // with a place: file:line:col of the offending velocity
  EXPECT_RIGID_ERROR(System(plane_spec({{"k", {{"x", Expression("2*y_dot", {"s.toml", 7, 10})}}, "", {}}})),
                     "s.toml:7:12: velocity constraint 'k' coefficient of 'x': depends on the velocity");
}

TEST(VelocityConstraints, LinearVelocitiesInTheTermAreTheSameRow) {
  // the whole row written as its term gives the same equations as coefficients + term
  const System by_term(plane_spec({{"k", {}, "x_dot - x*y_dot + 1", {}}}));
  const System by_row(plane_spec({{"k", {{"x", "1"}, {"y", "-x"}}, "1", {}}}));
  const Eigen::Vector2d q(0.3, 0.2), qd(0.7, -0.4);
  EXPECT_EQ(by_term.velocity_constraint_residual(0.0, q, qd), by_row.velocity_constraint_residual(0.0, q, qd));
  Eigen::VectorXd a1, a2, l1, l2;
  by_term.accelerations(0.0, q, qd, a1, l1, 5.0);
  by_row.accelerations(0.0, q, qd, a2, l2, 5.0);
  EXPECT_EQ(a1, a2);
  EXPECT_EQ(l1, l2);
}

TEST(VelocityConstraints, UnknownOrRepeatedCoordinatesAreRefused) {
  EXPECT_RIGID_ERROR(System(plane_spec({{"k", {{"xx", "1"}}, "", {}}})),
                     "velocity constraint 'k' coefficient of 'xx': no coordinate of that name; did "
                     "you mean 'x'?");
  EXPECT_RIGID_ERROR(System(plane_spec({{"k", {{"x", "1"}, {"x", "2"}}, "", {}}})),
                     "the coordinate has a coefficient already");
}

TEST(VelocityConstraints, RowsWithoutVelocitiesOrDependentRowsAreRefused) {
  EXPECT_RIGID_ERROR(System(plane_spec({{"k", {{"x", "0"}}, "y", {"s.toml", 3, 1}}})),
                     "s.toml:3:1: velocity constraint 'k': no velocity has a non-zero coefficient");
  // the same row twice, and a row that is a multiple of another for every q
  EXPECT_RIGID_ERROR(System(plane_spec({{"a", {{"x", "1"}}, "", {}}, {"b", {{"x", "1"}}, "-1", {"s.toml", 9, 1}}})),
                     "s.toml:9:1: velocity constraints 'a', 'b' are dependent for every q");
  EXPECT_RIGID_ERROR(System(plane_spec({{"a", {{"x", "cos(y)"}, {"y", "sin(y)"}}, "", {}},
                                        {"b", {{"x", "2*cos(y)"}, {"y", "2*sin(y)"}}, "", {}}})),
                     "velocity constraints 'a', 'b' are dependent for every q");
  // a name used twice
  EXPECT_RIGID_ERROR(System(plane_spec({{"a", {{"x", "1"}}, "", {}}, {"a", {{"y", "1"}}, "", {}}})),
                     "velocity constraint 'a': the name is already used");
}

TEST(VelocityConstraints, RowsDependentAtTheStartAreRefusedByTheRun) {
  // (1, x) and (1, 1) are independent but at x = 1; a holonomic x = 0 with ẋ = 0 is redundant
  SystemSpec spec = plane_spec({{"a", {{"x", "1"}, {"y", "x"}}, "", {}}, {"b", {{"x", "1"}, {"y", "1"}}, "", {}}});
  spec.coordinates[0].initial = 1.0;
  EXPECT_RIGID_ERROR((void)System(spec).simulate({.t_end = 0.1}),
                     "velocity constraints 'a', 'b' are redundant");
  SystemSpec both = plane_spec({{"still", {{"x", "1"}}, "", {}}});
  both.constraints = {{"fixed", "x"}};
  EXPECT_RIGID_ERROR((void)System(both).simulate({.t_end = 0.1}),
                     "constraints 'fixed' and velocity constraints 'still' are redundant");
  // rows that contradict each other for every q̇: ẋ + ẏ = 0, ẋ + ẏ = 1 at x = 1
  SystemSpec clash = plane_spec({{"a", {{"x", "1"}, {"y", "x"}}, "", {}}, {"b", {{"x", "1"}, {"y", "1"}}, "-1", {}}});
  clash.coordinates[0].initial = 1.0;
  EXPECT_RIGID_ERROR((void)System(clash).simulate({.t_end = 0.1}), "are inconsistent");
}

}  // namespace
}  // namespace rigid::lagrange
