// Symbolic mass properties, immutable systems with per-run workspaces, and simulation from
// several threads at once (also run under ThreadSanitizer by the tsan preset).
#include <cmath>
#include <thread>
#include <vector>

#include <ginac/ginac.h>
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "rigid/lagrange/system.hpp"
#include "rigid/mass/primitives.hpp"
#include "support/expect_error.hpp"
#include "support/tolerance.hpp"

namespace rigid::lagrange {
namespace {

using ::testing::HasSubstr;
using ::testing::Not;

// A physical pendulum: a thin rod of mass m and length L hanging from one end, with its mass
// properties written as expressions of the parameters (I_xx = I_yy = m L²/12 about the COM).
SystemSpec symbolic_pendulum() {
  SystemSpec spec;
  spec.parameters = {{"m", 0.5}, {"L", 1.0}, {"g", 9.81}};
  spec.coordinates = {{"theta", 1.0, 0.0}};
  BodyMass rod;
  rod.mass = "m";
  rod.inertia = {"m*L^2/12", "m*L^2/12", "0", "0", "0", "0"};
  spec.bodies.push_back(Body{"rod", rod, {"-(L/2)*sin(theta)", "0", "-(L/2)*cos(theta)"},
                             {AxisRotation{Eigen::Vector3d::UnitY(), "theta"}}});  // body z along the rod, to the pivot
  spec.gravity_W = Vector3Expression(std::array<Expression, 3>{"0", "0", "-g"});
  return spec;
}

TEST(SymbolicMass, EquationsKeepTheParameterNames) {
  const Equations eq = System(symbolic_pendulum()).equations();
  ASSERT_EQ(eq.text.size(), 1u);
  // m L²/3 θ̈ = −m g L/2 sin θ: every factor is a parameter, no number other than 1/3, 1/2
  EXPECT_THAT(eq.text[0], HasSubstr("m"));
  EXPECT_THAT(eq.text[0], HasSubstr("L^2"));
  EXPECT_THAT(eq.text[0], HasSubstr("g"));
  EXPECT_THAT(eq.text[0], HasSubstr("1/3"));
  EXPECT_THAT(eq.text[0], Not(HasSubstr("981")));
  EXPECT_THAT(eq.lagrangian_text, HasSubstr("theta_dot^2"));
}

TEST(SymbolicMass, SameNumbersAsTheNumericMassProperties) {
  // the same rod from the numeric primitive: M and f agree to round-off
  SystemSpec numeric = symbolic_pendulum();
  numeric.bodies[0].mass = mass::thin_rod_with_mass(0.5, 1.0);
  const System a(symbolic_pendulum()), b(numeric);
  const Eigen::VectorXd q = Eigen::VectorXd::Constant(1, 0.4), qd = Eigen::VectorXd::Constant(1, -0.3);
  Eigen::MatrixXd Ma, Mb;
  Eigen::VectorXd fa, fb;
  a.mass_matrix_and_forces(0.0, q, qd, Ma, fa);
  b.mass_matrix_and_forces(0.0, q, qd, Mb, fb);
  // M = m L²/3 = 1/6 kg·m²: the thin rod's numeric inertia m L²/12 = 0.041666… is rounded once
  EXPECT_NEAR(Ma(0, 0), 0.5 / 3.0, test::ulps(4, 0.2));
  EXPECT_NEAR(Mb(0, 0), Ma(0, 0), test::ulps(4, 0.2));
  EXPECT_NEAR(fb[0], fa[0], test::ulps(8, 3.0));
}

TEST(SymbolicMass, RefusesUnphysicalValuesNamingTheBody) {
  System sys(symbolic_pendulum());
  EXPECT_RIGID_ERROR(sys.set_parameter("m", -2.0), "body 'rod' with m = -2: mass must be positive");
  // the refused value did not stick
  EXPECT_EQ(sys.parameters()[0].value, 0.5);
  SystemSpec spec = symbolic_pendulum();
  spec.parameters[0].value = 0.0;
  EXPECT_RIGID_ERROR(System{spec}, "body 'rod' for the parameters' values: mass must be positive");
  spec = symbolic_pendulum();
  spec.bodies[0].mass.inertia[0] = "m*theta";
  EXPECT_RIGID_ERROR(System{spec}, "depends on the coordinate 'theta'");
  spec = symbolic_pendulum();
  spec.gravity_W[2] = "-g*t";
  EXPECT_RIGID_ERROR(System{spec}, "gravity[2]: depends on the time 't'");
}

TEST(Workspace, ParametersPerRunLeaveTheSystemAlone) {
  const System sys(symbolic_pendulum());
  Workspace w = sys.make_workspace();
  w.set_parameter("m", 2.0);
  Eigen::MatrixXd M;
  Eigen::VectorXd f;
  const Eigen::VectorXd z = Eigen::VectorXd::Zero(1);
  sys.mass_matrix_and_forces(w, 0.0, z, z, M, f);
  EXPECT_NEAR(M(0, 0), 2.0 / 3.0, test::ulps(4, 1.0));
  sys.mass_matrix_and_forces(0.0, z, z, M, f);  // a fresh workspace: the System's own m = 0.5
  EXPECT_NEAR(M(0, 0), 0.5 / 3.0, test::ulps(4, 1.0));
  EXPECT_RIGID_ERROR(w.set_parameter("mm", 1.0), "unknown parameter 'mm'; did you mean 'm'?");

  // simulate with an override: the small-angle period 2π√(2L/(3g)) does not depend on m, but
  // the energy does, in proportion
  SimulationOptions o{.t_end = 0.5, .method = integrate::Method::kRk4, .dt = 1e-3, .output_dt = 0.5};
  const Trajectory light = sys.simulate(o);
  o.parameters = {{"m", 2.0}};
  const Trajectory heavy = sys.simulate(o);
  EXPECT_NEAR(heavy.q(1, 0), light.q(1, 0), test::ulps(64));
  EXPECT_NEAR(heavy.energy(1), 4.0 * light.energy(1), test::ulps(64, 10.0));
  o.parameters = {{"n", 1.0}};
  EXPECT_RIGID_ERROR((void)sys.simulate(o), "unknown parameter 'n'");
}

TEST(Workspace, BelongsToItsSystem) {
  const System a(symbolic_pendulum()), b(symbolic_pendulum());
  Workspace w = a.make_workspace();
  Eigen::MatrixXd M;
  Eigen::VectorXd f;
  const Eigen::VectorXd z = Eigen::VectorXd::Zero(1);
  EXPECT_RIGID_ERROR(b.mass_matrix_and_forces(w, 0.0, z, z, M, f), "the workspace belongs to another System");
}

TEST(Workspace, OneSystemSimulatesOnSeveralThreadsAtOnce) {
  // The double pendulum with its parameters varied per thread: every thread's run must equal,
  // bit for bit, the same run done alone (the tape and the solver write only into the run's
  // workspace). Under ThreadSanitizer (the tsan preset) a shared scratch would be reported.
  SystemSpec spec;
  spec.parameters = {{"l1", 1.0}, {"l2", 0.7}, {"g", 9.81}};
  spec.coordinates = {{"theta1", 1.2, 0.0}, {"theta2", -0.4, 0.3}};
  spec.bodies.push_back(Body{"bob1", MassProperties(1.0, Eigen::Vector3d::Zero(), Eigen::Matrix3d::Zero()),
                             {"l1*sin(theta1)", "-l1*cos(theta1)", "0"}, {}});
  spec.bodies.push_back(Body{"bob2", MassProperties(0.5, Eigen::Vector3d::Zero(), Eigen::Matrix3d::Zero()),
                             {"l1*sin(theta1) + l2*sin(theta2)", "-l1*cos(theta1) - l2*cos(theta2)", "0"}, {}});
  spec.gravity_W = Eigen::Vector3d(0, -9.81, 0);
  const System sys(spec);
  constexpr int kThreads = 4;
  auto run = [&](int k) {
    SimulationOptions o{.t_end = 2.0, .method = k % 2 ? integrate::Method::kRk4 : integrate::Method::kDopri5,
                        .dt = 1e-3, .output_dt = 0.1};
    o.parameters = {{"l2", 0.5 + 0.1 * k}};
    return sys.simulate(o);
  };
  std::vector<Trajectory> alone;
  for (int k = 0; k < kThreads; ++k) alone.push_back(run(k));
  std::vector<Trajectory> together(kThreads);
  std::vector<std::thread> threads;
  for (int k = 0; k < kThreads; ++k) threads.emplace_back([&, k] { together[static_cast<std::size_t>(k)] = run(k); });
  for (auto& t : threads) t.join();
  for (int k = 0; k < kThreads; ++k) {
    const auto i = static_cast<std::size_t>(k);
    ASSERT_EQ(together[i].q.rows(), alone[i].q.rows());
    EXPECT_EQ(together[i].q, alone[i].q) << "thread " << k;
    EXPECT_EQ(together[i].energy, alone[i].energy) << "thread " << k;
  }
  // and the runs did differ (a shared parameter would make them equal)
  EXPECT_NE(alone[0].q(alone[0].q.rows() - 1, 1), alone[2].q(alone[2].q.rows() - 1, 1));
}

TEST(Simulate, DivergenceIsRefusedNamingTheCoordinate) {
  // ẍ = x³ from x = 10: blows up at t = √2/100 ≈ 0.014 s
  SystemSpec spec;
  spec.coordinates = {{"x", 10.0, 0.0}};
  spec.lagrangian = "x_dot^2/2 + x^4/4";
  EXPECT_RIGID_ERROR((void)System(spec).simulate({.t_end = 1.0, .method = integrate::Method::kRk4, .dt = 1e-3}),
                     "non-finite state");
  EXPECT_RIGID_ERROR((void)System(spec).simulate({.t_end = 1.0, .method = integrate::Method::kRk4, .dt = 1e-3}),
                     "x");
}

// The equation lines "  lhs = rhs" of free_body_equations, each as lhs − rhs parsed back by
// GiNaC's own parser (term order of the printout does not matter).
std::vector<GiNaC::ex> equation_residuals(const std::vector<std::string>& lines, GiNaC::parser& reader) {
  std::vector<GiNaC::ex> out;
  for (const std::string& line : lines) {
    const bool euler = line.find(" = ") != std::string::npos &&
                       (line.find("w1_dot") != std::string::npos || line.find("w2_dot") != std::string::npos ||
                        line.find("w3_dot") != std::string::npos);
    if (!euler) continue;
    const auto eq = line.find(" = ");
    out.push_back((reader(line.substr(0, eq)) - reader(line.substr(eq + 3))).expand());
  }
  return out;
}

TEST(FreeBodyEquations, PrintTheInertiaAsWritten) {
  FreeBodyEquationsSpec body;
  body.name = "racket";
  body.mass.mass = "m";
  body.mass.inertia = {"I1", "I2", "I3", "0", "0", "0"};
  const std::vector<Parameter> params = {{"m", 0.35}, {"I1", 1}, {"I2", 2}, {"I3", 3}};
  GiNaC::parser reader;
  const std::vector<GiNaC::ex> r = equation_residuals(free_body_equations(params, body, false), reader);
  ASSERT_EQ(r.size(), 3u);
  const GiNaC::ex I1 = reader("I1"), I2 = reader("I2"), I3 = reader("I3");
  const GiNaC::ex w1 = reader("w1"), w2 = reader("w2"), w3 = reader("w3");
  const GiNaC::ex wd1 = reader("w1_dot"), wd2 = reader("w2_dot"), wd3 = reader("w3_dot");
  // Euler's equations [Landau1976, §36]: I1 ω̇1 − (I2 − I3) ω2 ω3 = 0, and cyclic
  EXPECT_TRUE((r[0] - (I1 * wd1 - (I2 - I3) * w2 * w3)).expand().is_zero()) << r[0];
  EXPECT_TRUE((r[1] - (I2 * wd2 - (I3 - I1) * w3 * w1)).expand().is_zero()) << r[1];
  EXPECT_TRUE((r[2] - (I3 * wd3 - (I1 - I2) * w1 * w2)).expand().is_zero()) << r[2];

  // a heavy top with its COM at d on the z axis: about the pivot the transverse moments gain
  // m d² (parallel-axis theorem) and each line gains the torque component
  body.has_pivot = true;
  body.mass.com = Vector3Expression(std::array<Expression, 3>{"0", "0", "d"});
  const std::vector<Parameter> top_params = {{"m", 1}, {"I1", 1}, {"I2", 1}, {"I3", 0.5}, {"d", 0.1}};
  const std::vector<GiNaC::ex> t = equation_residuals(free_body_equations(top_params, body, false), reader);
  ASSERT_EQ(t.size(), 3u);
  const GiNaC::ex m = reader("m"), d = reader("d"), tau1 = reader("tau1");
  const GiNaC::ex J1 = I1 + m * d * d, J2 = I2 + m * d * d;
  EXPECT_TRUE((t[0] - (J1 * wd1 - (J2 - I3) * w2 * w3 - tau1)).expand().is_zero()) << t[0];
}

}  // namespace
}  // namespace rigid::lagrange
