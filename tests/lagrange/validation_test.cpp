// Validation of the Lagrangian engine against closed forms: rolling on an incline, the
// Atwood machine with a massive pulley, physical pendulums, the double pendulum, the bead on
// a rotating hoop and the Kepler orbit. Expected values are derived here, in the test.
#include <cmath>

#include <boost/math/special_functions/ellint_1.hpp>
#include <gtest/gtest.h>

#include "rigid/lagrange/system.hpp"
#include "rigid/mass/primitives.hpp"
#include "support/tolerance.hpp"

namespace rigid::lagrange {
namespace {

using integrate::Method;
constexpr double kG = 9.81;

MassProperties point_mass(double m) {
  return MassProperties(m, Eigen::Vector3d::Zero(), Eigen::Matrix3d::Zero());
}

// ---------------------------------------------------------------------------------------------
// rolling without slipping down an incline of angle α: a = g sin α / (1 + I/(m R²)),
// friction F = m g sin α − m a. Coordinates s (down the slope) and φ (rolling angle), the
// rolling condition s − R φ = 0 as a constraint whose multiplier is the friction force.
struct RollingCase {
  const char* name;
  MassProperties body;
  double radius;
  double inertia_ratio;  // I/(m R²) from the textbook closed form
};

void expect_rolls(const RollingCase& c) {
  const double alpha = 0.3, m = c.body.mass(), R = c.radius;
  SystemSpec spec;
  spec.parameters = {{"alpha", alpha}, {"R", R}};
  spec.coordinates = {{"s", 0.0, 0.0}, {"phi", 0.0, 0.0}};
  // the body frame sits on the axis: p_WB = s (cos α, −sin α, 0) + R (sin α, cos α, 0),
  // turning clockwise (about −z) as it rolls down to +x
  spec.bodies.push_back(Body{c.name, c.body,
                             {"s*cos(alpha) + R*sin(alpha)", "-s*sin(alpha) + R*cos(alpha)", "0"},
                             {AxisRotation{-Eigen::Vector3d::UnitZ(), "phi"}}});
  spec.gravity_W = Eigen::Vector3d(0, -kG, 0);
  spec.constraints = {{"rolling", "s - R*phi"}};
  const System sys(spec);
  const double t_end = 1.5;
  const Trajectory tr = sys.simulate({.t_end = t_end, .tolerance = 1e-12, .output_dt = 0.5});
  const double a = kG * std::sin(alpha) / (1 + c.inertia_ratio);
  const Eigen::Index last = tr.t.size() - 1;
  // s = ½ a t² exactly (constant acceleration); dopri5 at 1e-12 integrates a quadratic to
  // round-off, the bound leaves room for the Baumgarte term acting on O(1e-15) drift
  EXPECT_NEAR(tr.q(last, 0), 0.5 * a * t_end * t_end, 1e-10) << c.name;
  EXPECT_NEAR(tr.q_dot(last, 0), a * t_end, 1e-10) << c.name;
  // multiplier λ on s: m s̈ = m g sin α + λ, so λ = −F = −m g sin α · ρ/(1 + ρ)
  const double friction = m * kG * std::sin(alpha) * c.inertia_ratio / (1 + c.inertia_ratio);
  EXPECT_NEAR(tr.lambda(last, 0), -friction, 1e-9 * m * kG) << c.name;
  EXPECT_LT(tr.residual.maxCoeff(), 1e-12) << c.name;
  // rolling without slipping conserves T + V
  EXPECT_NEAR(tr.energy(last), tr.energy(0), 1e-9 * m * kG) << c.name;
}

TEST(Rolling, SolidCylinder) {
  expect_rolls({"cylinder", mass::solid_cylinder_with_mass(2.0, 0.1, 0.3), 0.1, 0.5});
}
TEST(Rolling, SolidSphere) {
  expect_rolls({"sphere", mass::solid_sphere_with_mass(1.5, 0.2), 0.2, 0.4});
}
TEST(Rolling, ThinHoop) {
  expect_rolls({"hoop", mass::thin_cylindrical_shell_with_mass(0.7, 0.25, 0.01), 0.25, 1.0});
}
TEST(Rolling, ThickWalledTube) {
  const double r1 = 0.05, r2 = 0.12;
  expect_rolls({"tube", mass::thick_tube_with_mass(3.0, r1, r2, 0.2), r2,
                0.5 * (r1 * r1 + r2 * r2) / (r2 * r2)});
}

// ---------------------------------------------------------------------------------------------
// Atwood machine with a solid cylindrical pulley (mass M, radius R), ropes as constraints:
// a = (m2 − m1) g / (m1 + m2 + M/2), T1 = m1 (g + a), T2 = m2 (g − a)
TEST(Atwood, AccelerationAndBothTensionsFromTheMultipliers) {
  const double m1 = 1.0, m2 = 1.5, Mp = 0.8, R = 0.1;
  SystemSpec spec;
  spec.parameters = {{"R", R}};
  spec.coordinates = {{"y1"}, {"y2"}, {"phi"}};
  spec.bodies.push_back(Body{"left", point_mass(m1), {"-R", "y1", "0"}, {}});
  spec.bodies.push_back(Body{"right", point_mass(m2), {"R", "y2", "0"}, {}});
  spec.bodies.push_back(Body{"pulley", mass::solid_cylinder_with_mass(Mp, R, 0.02),
                             {"0", "0", "0"}, {AxisRotation{Eigen::Vector3d::UnitZ(), "phi"}}});
  spec.gravity_W = Eigen::Vector3d(0, -kG, 0);
  // turning the pulley by φ (counter-clockwise) lowers the left side and raises the right
  spec.constraints = {{"left_rope", "y1 + R*phi"}, {"right_rope", "y2 - R*phi"}};
  const System sys(spec);
  const Trajectory tr = sys.simulate({.t_end = 1.0, .tolerance = 1e-12, .output_dt = 0.25});
  const double a = (m2 - m1) * kG / (m1 + m2 + Mp / 2);
  for (Eigen::Index k = 0; k < tr.t.size(); ++k) {
    const double t = tr.t[k];
    // uniform acceleration: exact for the integrator up to its tolerance (1e-12 per unit)
    EXPECT_NEAR(tr.q(k, 0), 0.5 * a * t * t, 1e-10);
    EXPECT_NEAR(tr.q(k, 1), -0.5 * a * t * t, 1e-10);
    // multipliers are the rope forces on the masses (m ÿ = −m g + T)
    EXPECT_NEAR(tr.lambda(k, 0), m1 * (kG + a), 1e-9);
    EXPECT_NEAR(tr.lambda(k, 1), m2 * (kG - a), 1e-9);
  }
}

TEST(Atwood, InconsistentInitialConditionsAreRefusedOrProjected) {
  SystemSpec spec;
  spec.parameters = {{"R", 0.1}};
  spec.coordinates = {{"y1", 0.01}, {"y2"}, {"phi"}};
  spec.bodies.push_back(Body{"left", point_mass(1.0), {"-R", "y1", "0"}, {}});
  spec.bodies.push_back(Body{"right", point_mass(2.0), {"R", "y2", "0"}, {}});
  spec.bodies.push_back(Body{"pulley", mass::solid_cylinder_with_mass(1.0, 0.1, 0.02),
                             {"0", "0", "0"}, {AxisRotation{Eigen::Vector3d::UnitZ(), "phi"}}});
  spec.constraints = {{"left_rope", "y1 + R*phi"}, {"right_rope", "y2 - R*phi"}};
  const System sys(spec);
  try {
    (void)sys.simulate({.t_end = 0.1});
    ADD_FAILURE() << "expected an error";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("initial conditions violate constraint 'left_rope': "
                                         "|g| = 0.01"), std::string::npos) << e.what();
  }
  const Trajectory tr = sys.simulate({.t_end = 0.1, .project_initial = true});
  // the projection drives |g| below 1e-3 × the consistency tolerance (1e-9)
  EXPECT_LT(tr.residual[0], 1e-12);
  EXPECT_LT(tr.residual.maxCoeff(), 1e-11);
}

// ---------------------------------------------------------------------------------------------
// physical pendulums about a pivot at the origin, swinging about z; θ measured from hanging.
// A rod (m, ℓ): I_p = m ℓ²/3 (parallel axis: m ℓ²/12 + m (ℓ/2)²), m g d = m g ℓ/2.
System rod_pendulum(double theta0, double m, double l, bool with_disk, double md = 0,
                    double r = 0) {
  SystemSpec spec;
  spec.coordinates = {{"theta", theta0, 0.0}};
  // rod along −y of the body frame, COM at its middle; a thin rod has no moment about y
  spec.bodies.push_back(Body{"rod",
                             MassProperties(m, Eigen::Vector3d(0, -l / 2, 0),
                                            Eigen::Vector3d(m * l * l / 12, 0, m * l * l / 12)
                                                .asDiagonal()),
                             {"0", "0", "0"}, {AxisRotation{Eigen::Vector3d::UnitZ(), "theta"}}});
  if (with_disk) {
    // a disk in the swing plane, centred on the rod's end: I_zz = ½ m r²
    spec.bodies.push_back(Body{"disk",
                               MassProperties(md, Eigen::Vector3d(0, -l, 0),
                                              Eigen::Vector3d(md * r * r / 4, md * r * r / 4,
                                                              md * r * r / 2).asDiagonal()),
                               {"0", "0", "0"},
                               {AxisRotation{Eigen::Vector3d::UnitZ(), "theta"}}});
  }
  spec.gravity_W = Eigen::Vector3d(0, -kG, 0);
  return System(spec);
}

TEST(PhysicalPendulum, RodSmallAnglePeriod) {
  const double m = 0.4, l = 0.9, theta0 = 1e-5;
  const double T0 = 2 * M_PI * std::sqrt((m * l * l / 3) / (m * kG * l / 2));
  const Trajectory tr = rod_pendulum(theta0, m, l, false)
                            .simulate({.t_end = T0, .tolerance = 1e-13, .output_dt = T0 / 2});
  ASSERT_EQ(tr.t.size(), 3);
  // the true period exceeds T0 by T0 θ0²/16 ≈ 6e-12 T0, far below the 1e-6·θ0 bound; the
  // bound is the integrator's 1e-13 tolerance accumulated over ~100 steps, relative to θ0
  EXPECT_NEAR(tr.q(1, 0), -theta0, 1e-6 * theta0);
  EXPECT_NEAR(tr.q(2, 0), theta0, 1e-6 * theta0);
}

TEST(PhysicalPendulum, DiskOnRodSmallAnglePeriod) {
  const double m = 0.3, l = 0.8, md = 1.2, r = 0.15, theta0 = 1e-5;
  // parallel axis for both: I_p = m ℓ²/3 + ½ md r² + md ℓ², m g d = g (m ℓ/2 + md ℓ)
  const double Ip = m * l * l / 3 + 0.5 * md * r * r + md * l * l;
  const double T0 = 2 * M_PI * std::sqrt(Ip / (kG * (m * l / 2 + md * l)));
  const Trajectory tr = rod_pendulum(theta0, m, l, true, md, r)
                            .simulate({.t_end = T0, .tolerance = 1e-13, .output_dt = T0 / 2});
  EXPECT_NEAR(tr.q(1, 0), -theta0, 1e-6 * theta0);
  EXPECT_NEAR(tr.q(2, 0), theta0, 1e-6 * theta0);
}

TEST(PhysicalPendulum, LargeAmplitudePeriodFromEllipticK) {
  // T = 4 K(k) / ω0, k = sin(θ0/2), ω0² = m g d / I_p  [Landau1976, §11, problem 1]
  const double m = 0.4, l = 0.9, theta0 = 2.5;
  const double omega0 = std::sqrt((m * kG * l / 2) / (m * l * l / 3));
  const double T = 4 * boost::math::ellint_1(std::sin(theta0 / 2)) / omega0;
  const Trajectory tr = rod_pendulum(theta0, m, l, false)
                            .simulate({.t_end = T, .tolerance = 1e-13, .output_dt = T / 2});
  // at a turning point θ(t) is quadratic in the timing error, so 1e-8 rad is a strict test
  EXPECT_NEAR(tr.q(1, 0), -theta0, 1e-8);
  EXPECT_NEAR(tr.q(2, 0), theta0, 1e-8);
  EXPECT_NEAR(tr.q_dot(2, 0), 0.0, 1e-7);
}

// ---------------------------------------------------------------------------------------------
// double pendulum of two point masses on massless rods
constexpr double kM1 = 1.0, kM2 = 0.7, kL1 = 1.0, kL2 = 0.8;

System double_pendulum(double th1, double th2) {
  SystemSpec spec;
  spec.parameters = {{"l1", kL1}, {"l2", kL2}};
  spec.coordinates = {{"theta1", th1}, {"theta2", th2}};
  spec.bodies.push_back(Body{"bob1", point_mass(kM1), {"l1*sin(theta1)", "-l1*cos(theta1)", "0"}, {}});
  spec.bodies.push_back(Body{"bob2", point_mass(kM2),
                             {"l1*sin(theta1) + l2*sin(theta2)",
                              "-l1*cos(theta1) - l2*cos(theta2)", "0"}, {}});
  spec.gravity_W = Eigen::Vector3d(0, -kG, 0);
  return System(spec);
}

// the textbook closed-form accelerations, written out independently of the engine
Eigen::Vector2d double_pendulum_accelerations(const Eigen::Vector4d& y) {
  const double t1 = y[0], t2 = y[1], w1 = y[2], w2 = y[3], d = t1 - t2;
  const double den = 2 * kM1 + kM2 - kM2 * std::cos(2 * d);
  const double a1 = (-kG * (2 * kM1 + kM2) * std::sin(t1) - kM2 * kG * std::sin(t1 - 2 * t2) -
                     2 * std::sin(d) * kM2 * (w2 * w2 * kL2 + w1 * w1 * kL1 * std::cos(d))) /
                    (kL1 * den);
  const double a2 = 2 * std::sin(d) *
                    (w1 * w1 * kL1 * (kM1 + kM2) + kG * (kM1 + kM2) * std::cos(t1) +
                     w2 * w2 * kL2 * kM2 * std::cos(d)) /
                    (kL2 * den);
  return {a1, a2};
}

TEST(DoublePendulum, AccelerationsMatchTheClosedForm) {
  const System sys = double_pendulum(0, 0);
  Eigen::VectorXd qdd, lambda;
  for (const Eigen::Vector4d& y : {Eigen::Vector4d(0.3, -1.2, 0.5, 2.0),
                                  Eigen::Vector4d(2.0, 2.9, -3.0, 1.0),
                                  Eigen::Vector4d(-0.1, 0.4, 0.0, -0.2)}) {
    sys.accelerations(0.0, y.head(2), y.tail(2), qdd, lambda);
    const Eigen::Vector2d expected = double_pendulum_accelerations(y);
    // both are a few dozen flops from the same inputs: agreement to ~100 ulps of |a|
    EXPECT_NEAR(qdd[0], expected[0], test::ulps(200, 10 + std::abs(expected[0])));
    EXPECT_NEAR(qdd[1], expected[1], test::ulps(200, 10 + std::abs(expected[1])));
  }
}

TEST(DoublePendulum, StateAtFiveSecondsAgreesWithAnIndependentAdaptiveRun) {
  const System sys = double_pendulum(1.0, -0.5);
  const Trajectory ours = sys.simulate({.t_end = 5.0, .method = Method::kRk4, .dt = 1e-3});
  // reference: dopri5 at 1e-13 on the closed-form right-hand side above
  integrate::Problem p;
  p.rhs = [](double, const Eigen::VectorXd& y, Eigen::VectorXd& d) {
    d.head(2) = y.tail(2);
    d.tail(2) = double_pendulum_accelerations(Eigen::Vector4d(y));
  };
  p.y0 = Eigen::Vector4d(1.0, -0.5, 0.0, 0.0);
  p.t_end = 5.0;
  const integrate::Solution ref =
      integrate::integrate(p, {.method = Method::kDopri5, .rtol = 1e-13, .atol = 1e-13});
  const Eigen::Index last = ours.t.size() - 1;
  // RK4 at dt = 1e-3: global error ~ C dt⁴ with C ~ 1e2 for this moderately excited motion
  for (int i = 0; i < 2; ++i) {
    EXPECT_NEAR(ours.q(last, i), ref.y.back()[i], 1e-8);
    EXPECT_NEAR(ours.q_dot(last, i), ref.y.back()[2 + i], 1e-8);
  }
}

TEST(DoublePendulum, ImplicitMidpointEnergyErrorStaysBoundedOver1e4Periods) {
  // small-oscillation periods are ≈ 1.3 s and 2.6 s; 10⁴ of the longer one ≈ 2.6e4 s
  const System sys = double_pendulum(0.6, 0.3);
  const double t_end = 2.6e4;
  const Trajectory tr = sys.simulate(
      {.t_end = t_end, .method = Method::kImplicitMidpoint, .dt = 0.05, .output_dt = 5.0});
  const double E0 = tr.energy[0];
  double early = 0, late = 0;
  const Eigen::Index rows = tr.t.size();
  for (Eigen::Index k = 0; k < rows; ++k) {
    const double err = std::abs(tr.energy[k] - E0);
    (k < rows / 10 ? early : late) = std::max(k < rows / 10 ? early : late, err);
  }
  // a symplectic method keeps a modified energy: the error oscillates at O(dt²) ≈ 1e-2 |E|
  // without drifting, so the last 90% never exceeds twice the worst of the first 10%
  EXPECT_LT(late, 2 * early + 1e-12);
  EXPECT_LT(late, 2e-2 * std::abs(E0));
}

// ---------------------------------------------------------------------------------------------
// bead (point mass) on a hoop of radius R turning at ω about the vertical z axis:
// T = ½ m R² (θ̇² + ω² sin²θ), V = −m g R cos θ; h = ½ m R² θ̇² − ½ m R² ω² sin²θ − m g R cos θ
// is conserved, E = T + V is not (the motor does work)
TEST(BeadOnRotatingHoop, JacobiIntegralConservedEnergyNot) {
  const double m = 0.2, R = 0.5, omega = 7.0;
  SystemSpec spec;
  spec.parameters = {{"omega", omega}};
  spec.coordinates = {{"theta", 0.4, 0.0}};
  spec.bodies.push_back(Body{"bead", MassProperties(m, Eigen::Vector3d(0, 0, -R),
                                                    Eigen::Matrix3d::Zero()),
                             {"0", "0", "0"},
                             {AxisRotation{Eigen::Vector3d::UnitZ(), "omega*t"},
                              AxisRotation{Eigen::Vector3d::UnitY(), "theta"}}});
  spec.gravity_W = Eigen::Vector3d(0, 0, -kG);
  const System sys(spec);
  const Trajectory tr = sys.simulate({.t_end = 5.0, .tolerance = 1e-12, .output_dt = 0.05});
  double h_err = 0, e_min = 1e300, e_max = -1e300;
  for (Eigen::Index k = 0; k < tr.t.size(); ++k) {
    const double th = tr.q(k, 0), thd = tr.q_dot(k, 0);
    const double s = std::sin(th);
    const double h = 0.5 * m * R * R * (thd * thd - omega * omega * s * s) - m * kG * R * std::cos(th);
    const double E = 0.5 * m * R * R * (thd * thd + omega * omega * s * s) - m * kG * R * std::cos(th);
    EXPECT_NEAR(tr.jacobi[k], h, test::ulps(100, 1.0));  // same formula, independent flops
    EXPECT_NEAR(tr.energy[k], E, test::ulps(100, 1.0));
    h_err = std::max(h_err, std::abs(h - tr.jacobi[0]));
    e_min = std::min(e_min, E);
    e_max = std::max(e_max, E);
  }
  EXPECT_LT(h_err, 1e-9);               // tolerance 1e-12 per unit time over 5 s
  EXPECT_GT(e_max - e_min, 1e-2);        // the energy swings by O(m R² ω²) ≈ 0.1 J
}

TEST(BeadOnRotatingHoop, TimeDependentConstraintWithMultiplier) {
  // the same bead with the hoop angle as a coordinate and φ − ω t = 0 as a constraint;
  // the multiplier is the motor torque λ = d/dt(m R² sin²θ φ̇) = 2 m R² ω sin θ cos θ θ̇
  const double m = 0.2, R = 0.5, omega = 7.0;
  SystemSpec spec;
  spec.parameters = {{"m", m}, {"R", R}, {"g", kG}, {"omega", omega}};
  spec.coordinates = {{"theta", 0.4, 0.0}, {"phi", 0.0, omega}};
  spec.lagrangian = "m*R^2/2*(theta_dot^2 + sin(theta)^2*phi_dot^2) + m*g*R*cos(theta)";
  spec.constraints = {{"motor", "phi - omega*t"}};
  const System sys(spec);
  const Trajectory tr = sys.simulate({.t_end = 3.0, .tolerance = 1e-12, .output_dt = 0.5});

  SystemSpec reduced;
  reduced.parameters = spec.parameters;
  reduced.coordinates = {{"theta", 0.4, 0.0}};
  reduced.lagrangian = "m*R^2/2*(theta_dot^2 + sin(theta)^2*omega^2) + m*g*R*cos(theta)";
  const Trajectory ref = System(reduced).simulate({.t_end = 3.0, .tolerance = 1e-12,
                                                   .output_dt = 0.5});
  ASSERT_EQ(tr.t.size(), ref.t.size());
  for (Eigen::Index k = 0; k < tr.t.size(); ++k) {
    // two integrations at 1e-12 of the same motion on a 3 s, mildly unstable orbit
    EXPECT_NEAR(tr.q(k, 0), ref.q(k, 0), 1e-8);
    const double th = tr.q(k, 0), thd = tr.q_dot(k, 0);
    EXPECT_NEAR(tr.lambda(k, 0), 2 * m * R * R * omega * std::sin(th) * std::cos(th) * thd, 1e-8);
  }
  EXPECT_LT(tr.residual.maxCoeff(), 1e-10);
}

// ---------------------------------------------------------------------------------------------
// Kepler problem L = ½ m (ṙ² + r² φ̇²) + k m / r: φ is cyclic, p_φ = m r² φ̇ is conserved;
// the period is 2π √(a³/k) with a = −k m/(2E)  [Goldstein2002, §3.7]
TEST(Kepler, AngularMomentumIsTheCyclicMomentumAndThePeriodIsKeplers) {
  const double m = 2.0, k = 1.0, r0 = 1.0, v0 = 1.2;
  SystemSpec spec;
  spec.parameters = {{"m", m}, {"k", k}};
  spec.coordinates = {{"r", r0, 0.0}, {"phi", 0.0, v0 / r0}};
  spec.lagrangian = "m/2*(r_dot^2 + r^2*phi_dot^2) + k*m/r";
  const System sys(spec);
  ASSERT_EQ(sys.cyclic_coordinates(), std::vector<std::string>{"phi"});
  const double E = 0.5 * m * v0 * v0 - k * m / r0;
  const double a = -k * m / (2 * E);
  const double T = 2 * M_PI * std::sqrt(a * a * a / k);
  const Trajectory tr = sys.simulate({.t_end = T, .tolerance = 1e-13, .output_dt = T / 8});
  ASSERT_EQ(tr.cyclic_momenta.cols(), 1);
  const double L0 = m * r0 * v0;
  for (Eigen::Index i = 0; i < tr.t.size(); ++i) {
    EXPECT_NEAR(tr.cyclic_momenta(i, 0), m * tr.q(i, 0) * tr.q(i, 0) * tr.q_dot(i, 1),
                test::ulps(16, L0));
    EXPECT_NEAR(tr.cyclic_momenta(i, 0), L0, 1e-10 * L0);  // integrator tolerance
    EXPECT_NEAR(tr.energy(i), E, 1e-10 * std::abs(E));
  }
  const Eigen::Index last = tr.t.size() - 1;
  // after one period the orbit closes: r back to r0, φ advanced by 2π
  EXPECT_NEAR(tr.q(last, 0), r0, 1e-9);
  EXPECT_NEAR(tr.q(last, 1), 2 * M_PI, 1e-9);
}

// ---------------------------------------------------------------------------------------------
// a mass hanging from a world point on a spring (k, rest length L) in a pendulum-free vertical
// line: equilibrium y = −(L + m g/k), period 2π √(m/k), independent of gravity
TEST(Spring, VerticalOscillatorPeriodAndEquilibrium) {
  const double m = 0.5, k = 80.0, L = 0.3;
  const double y_eq = -(L + m * kG / k), amplitude = 0.02;
  SystemSpec spec;
  spec.parameters = {{"k", k}};
  spec.coordinates = {{"y", y_eq + amplitude, 0.0}};
  spec.bodies.push_back(Body{"bob", point_mass(m), {"0", "y", "0"}, {}});
  spec.springs.push_back(Spring{.body_a = "bob", .stiffness = "k", .rest_length = "0.3"});
  spec.gravity_W = Eigen::Vector3d(0, -kG, 0);
  const System sys(spec);
  const double T = 2 * M_PI * std::sqrt(m / k);
  const Trajectory tr = sys.simulate({.t_end = T, .tolerance = 1e-13, .output_dt = T / 2});
  // linear oscillation about y_eq (the spring stays stretched, |p_a − p_b| = −y)
  EXPECT_NEAR(tr.q(1, 0), y_eq - amplitude, 1e-9);
  EXPECT_NEAR(tr.q(2, 0), y_eq + amplitude, 1e-9);
  // T + V with V = ½ k (|y| − L)² + m g y is conserved
  EXPECT_NEAR(tr.energy(2), tr.energy(0), 1e-10);
  const double y0 = y_eq + amplitude;
  EXPECT_NEAR(tr.energy(0), 0.5 * k * (-y0 - L) * (-y0 - L) + m * kG * y0, test::ulps(64, 10.0));
}

TEST(Spring, UnknownBodyIsNamed) {
  SystemSpec spec;
  spec.coordinates = {{"y"}};
  spec.bodies.push_back(Body{"bob", point_mass(1.0), {"0", "y", "0"}, {}});
  spec.springs.push_back(Spring{.body_a = "bob", .body_b = "bobb", .stiffness = "1"});
  try {
    System sys(spec);
    ADD_FAILURE() << "expected an error";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("spring 0: body_b names the unknown body 'bobb'; "
                                         "bodies: bob"), std::string::npos) << e.what();
  }
}

// ---------------------------------------------------------------------------------------------
// measured convergence orders on a pendulum with constant M (so Störmer–Verlet applies):
// error at t = 2 against a dopri5 reference at 1e-13, dt vs dt/2, ratio 2^p within ±10%
TEST(Convergence, OrdersOfEachIntegratorOnAPendulum) {
  SystemSpec spec;
  spec.parameters = {{"m", 1.0}, {"l", 0.7}, {"g", kG}};
  spec.coordinates = {{"theta", 1.0, 0.0}};
  spec.lagrangian = "m*l^2/2*theta_dot^2 + m*g*l*cos(theta)";
  const System sys(spec);
  const Trajectory ref = sys.simulate({.t_end = 2.0, .tolerance = 1e-14});
  const double q_ref = ref.q(ref.t.size() - 1, 0);
  auto error = [&](Method method, double dt) {
    const Trajectory tr = sys.simulate({.t_end = 2.0, .method = method, .dt = dt});
    return std::abs(tr.q(tr.t.size() - 1, 0) - q_ref);
  };
  struct Case { Method method; double dt; double order; };
  for (const Case c : {Case{Method::kRk4, 0.02, 4}, Case{Method::kImplicitMidpoint, 0.01, 2},
                       Case{Method::kStormerVerlet, 0.01, 2}}) {
    const double ratio = error(c.method, c.dt) / error(c.method, c.dt / 2);
    EXPECT_NEAR(ratio, std::pow(2, c.order), 0.1 * std::pow(2, c.order))
        << integrate::to_string(c.method);
  }
}

}  // namespace
}  // namespace rigid::lagrange
