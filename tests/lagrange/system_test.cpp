#include "rigid/lagrange/system.hpp"

#include <cmath>

#include <fmt/format.h>
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "support/expect_error.hpp"
#include "support/tolerance.hpp"

namespace rigid::lagrange {
namespace {

using integrate::Method;
using ::testing::HasSubstr;

SystemSpec pendulum_spec() {
  SystemSpec spec;
  spec.parameters = {{"m", 2.0}, {"l", 0.5}, {"g", 9.81}};
  spec.coordinates = {{"theta", 0.3, 0.0}};
  spec.lagrangian = "m*l^2/2*theta_dot^2 + m*g*l*cos(theta)";
  return spec;
}

TEST(System, PendulumMassMatrixAndForce) {
  const System sys(pendulum_spec());
  Eigen::MatrixXd M;
  Eigen::VectorXd f;
  sys.mass_matrix_and_forces(0.0, Eigen::VectorXd::Constant(1, 0.7), Eigen::VectorXd::Zero(1), M,
                             f);
  // M = m l², f = −m g l sin θ
  EXPECT_NEAR(M(0, 0), 2.0 * 0.25, test::ulps(4, 0.5));
  EXPECT_NEAR(f[0], -2.0 * 9.81 * 0.5 * std::sin(0.7), test::ulps(8, 10.0));
  EXPECT_TRUE(sys.cyclic_coordinates().empty());
}

TEST(System, SetParameterChangesTheNumbersWithoutRederiving) {
  System sys(pendulum_spec());
  sys.set_parameter("m", 3.0);
  Eigen::MatrixXd M;
  Eigen::VectorXd f;
  sys.mass_matrix_and_forces(0.0, Eigen::VectorXd::Zero(1), Eigen::VectorXd::Zero(1), M, f);
  EXPECT_NEAR(M(0, 0), 3.0 * 0.25, test::ulps(4, 1.0));
  EXPECT_RIGID_ERROR(sys.set_parameter("mass", 1.0), "unknown parameter 'mass'");
}

// What the parser accepts can still fail in GiNaC or CLN while the equations are derived:
// d/dq 0^q = 0^q log 0 is a pole (GiNaC::pole_error), and expanding 80^(10^15 + a) computes an
// exact power whose exponent is beyond CLN's 32-bit integers (cln::runtime_exception). Both were
// found by the expression fuzz target escaping System's constructor; both are rigid::Errors in
// rigid's words now, without the libraries' texts.
TEST(System, LibraryFailuresWhileDerivingAreWorded) {
  const auto message = [](const std::string& lagrangian) {
    SystemSpec spec;
    spec.parameters = {{"a", 1.5}};
    spec.coordinates = {{"q", 0.3, 0.2}};
    spec.lagrangian = lagrangian;
    try {
      const System sys(spec);
    } catch (const Error& e) {
      return std::string(e.what());
    }
    return std::string("no error");
  };
  const std::string pole = message("q_dot^2/2 - a*0^q");
  EXPECT_THAT(pole, HasSubstr("a term of the Lagrangian, its energies or their derivatives has a "
                              "pole here"));
  EXPECT_THAT(pole, ::testing::Not(HasSubstr("log_eval")));
  const std::string huge = message("q_dot^2/2 - 80^(1473776214705732 + 9705732980^a) * q");
  EXPECT_THAT(huge, HasSubstr("holds a number too large for exact arithmetic"));
  EXPECT_THAT(huge, ::testing::Not(HasSubstr("32-bit")));
}

// (a + pi)^(8^6) was built in an instant and expanded for minutes (the expression fuzz
// target's timeouts): the terms a parsed expression multiplies out to are estimated first.
TEST(System, ExpressionsThatMultiplyOutBeyondTheLimitAreRefusedBeforeExpanding) {
  const auto spec_with = [](const std::string& potential) {
    SystemSpec spec;
    spec.parameters = {{"a", 1.5}};
    spec.coordinates = {{"q", 0.3, 0.2}};
    spec.lagrangian = "q_dot^2/2";
    spec.potentials = {{"V", Expression(potential)}};
    return spec;
  };
  // (q + a)^n has n + 1 terms: 1,000 is the limit
  EXPECT_RIGID_ERROR(System(spec_with("(q + a)^(8^6)")), "multiplies out to about 10^5.42 terms");
  EXPECT_RIGID_ERROR(System(spec_with("(q + a)^1000")), "at most 1000 are allowed");
  EXPECT_RIGID_ERROR(System(spec_with("(q + a)^(3^8)")), "multiplies out to about 10^3.82 terms");
  // an exponent far beyond a double's integers: 2^708 + 1 terms (a difference of lgamma
  // values cancelled to 0 here, and the expansion overflowed the stack)
  EXPECT_RIGID_ERROR(System(spec_with("(q + a)^(2^708)")), "multiplies out to about 10^213 terms");
  // nested: the inner power's 51 terms plus 1, to the 50th, is about 10^40 terms
  EXPECT_RIGID_ERROR(System(spec_with("((q + a)^50 + 1)^50")), "multiplies out to about 10^");
  // a product of the same sum is a power too (GiNaC gathers the factors)
  std::string product = "1";
  for (int i = 0; i < 10000; ++i) product += "*(q + pi)";
  EXPECT_RIGID_ERROR(System(spec_with(product)), "multiplies out to about 10^4");
  // a single term to a power beyond 32 bits is no expansion; its tape takes pow, not a
  // repeated product (q^(6^63) wrapped the exponent): V' = 6^63 q^(6^63 − 1) = 0 at q = 0.3
  {
    const System big(spec_with("q^(6^63)"));
    Eigen::VectorXd q_ddot, lambda;
    big.accelerations(0.0, big.initial_q(), big.initial_q_dot(), q_ddot, lambda);
    EXPECT_EQ(q_ddot(0), 0.0);
  }
  // a product of two sums multiplies out (30 × 40 = 1,200 terms); a long sum as written does
  // not (2,000 terms of the text's own)
  std::string first = "0", second = "0", sum = "0";
  for (int i = 1; i <= 30; ++i) first += fmt::format(" + {}*q^{}", i, i);
  for (int i = 1; i <= 40; ++i) second += fmt::format(" + a^{}", i);
  for (int i = 1; i <= 2000; ++i) sum += fmt::format(" + q*a^{}", i);
  EXPECT_RIGID_ERROR(System(spec_with("(" + first + ")*(" + second + ")")), "about 10^3.08 terms");
  EXPECT_NO_THROW(System(spec_with(sum)));
  EXPECT_NO_THROW(System(spec_with("2*(" + first + ")")));
  // few terms, each long (from the fuzz target, where it took minutes; a second such input is
  // fuzz/regressions/expression/nested_powers_of_sums_long_terms.txt): the 627 terms of
  // (a + X·pi)^626 each hold X = (a + pi)^E with E's 627 terms, about 10^5.9 symbols and
  // operations at first, 10^6.2 counting the 627 copies of the base that (a + pi)^E multiplies
  // out to (a power of a sum of exponents is a product of powers)
  EXPECT_RIGID_ERROR(System(spec_with("(a + (a + pi)^((a + pi)^626)*pi)^626")),
                     "multiplies out to about 10^6.2 symbols and operations");
  // accepted, but its derivative multiplies out far beyond (the fuzz target's
  // fuzz/regressions/expression/tower_over_a_sum_to_the_626th.txt, which took minutes and
  // gigabytes to print): by the chain rule each of the 626 terms of d/dq (q + pi)^626 holds the
  // 627 powers that (a + pi)^((q + pi)^626) multiplies out to. The derived equation is
  // estimated before it is expanded: 400 × 401 factors are refused, 101 × 102 derived
  EXPECT_RIGID_ERROR(System(spec_with("626^8^(a + pi)^(q + pi)^626")),
                     "the equation of motion of 'q' multiplies out to about 10^6.");
  EXPECT_RIGID_ERROR(System(spec_with("(a + pi)^((q + pi)^400)")),
                     "the equation of motion of 'q' multiplies out to about 10^6.05 symbols and "
                     "operations (products of long sums in the derivatives of the Lagrangian); at "
                     "most 1000000 are allowed");
  {
    // a constraint's rate and acceleration term likewise (ġ = ∂g/∂q q̇)
    SystemSpec constrained = spec_with("q^2");
    constrained.coordinates.push_back({"x", 0.0, 0.0});
    constrained.lagrangian = "q_dot^2/2 + x_dot^2/2";
    constrained.constraints = {{"tower", "x - (a + pi)^((q + pi)^400)"}};
    EXPECT_RIGID_ERROR((void)System(constrained),
                       "the rate ġ of constraint 'tower' multiplies out to about 10^6.");
  }
  {
    const System within(spec_with("(a + pi)^((q + 7/10)^100)"));
    // f = −V' = −V log(a + pi) 100 (q + 7/10)^99 = −100 (a + pi) log(a + pi) at q = 0.3: the
    // expanded tape (101 positive terms of the exponent, 101 × 102 factors of f) against the
    // closed form, to the rounding of a few hundred operations on values of order 1
    Eigen::VectorXd q_ddot, lambda;
    within.accelerations(0.0, within.initial_q(), within.initial_q_dot(), q_ddot, lambda);
    const double b = 1.5 + M_PI;
    EXPECT_NEAR(q_ddot(0), -100 * b * std::log(b), 1e-12 * 100 * b * std::log(b));
    EXPECT_FALSE(within.equations().text.front().empty());
  }
  // a high power of a sine stays a power: sin² + cos² = 1 rewrites only up to the 64th, since
  // (1 − cos²)^(n/2) multiplies out to n/2 + 1 terms (this one asked for gigabytes; the fuzz
  // target's fuzz/regressions/expression/sine_to_the_730452665th_out_of_memory.txt)
  {
    const System high(spec_with("sin(a + pi)^730452665*807 + q^2/2"));
    Eigen::VectorXd q_ddot, lambda;
    high.accelerations(0.0, high.initial_q(), high.initial_q_dot(), q_ddot, lambda);
    EXPECT_EQ(q_ddot(0), -0.3);  // V' = q; the constant term has no derivative
    // an exponent beyond a long is compared as a number, never converted: the equation of
    // motion keeps it, q̈ = −10³⁰ cos q sin^(10³⁰ − 1) q
    const System beyond(spec_with("sin(q)^(10^30)"));
    std::string text;
    for (const std::string& line : beyond.equations().text) text += line + "\n";
    EXPECT_NE(text.find("sin(q)^999999999999999999999999999999"), std::string::npos) << text;
  }
  // a long sum as written is not counted (4,000 terms of about three symbols each)
  std::string long_sum = "0";
  for (int i = 1; i <= 4000; ++i) long_sum += fmt::format(" + q*a^{}", i);
  EXPECT_NO_THROW(System(spec_with(long_sum)));
  // within the limit: (q + a)^9 = Σ C(9, k) q^k a^(9-k), V' = 9 (q + a)^8 at q = 0.3
  const System sys(spec_with("(q + a)^9"));
  Eigen::VectorXd q_ddot, lambda;
  sys.accelerations(0.0, sys.initial_q(), sys.initial_q_dot(), q_ddot, lambda);
  const double expected = -9.0 * std::pow(1.8, 8);
  EXPECT_NEAR(q_ddot(0), expected, test::ulps(64, std::abs(expected)));
}

TEST(System, EquationsPrintAsTextAndLatex) {
  const Equations eq = System(pendulum_spec()).equations();
  ASSERT_EQ(eq.text.size(), 1u);
  // m l² θ̈ = −m g l sin θ, in GiNaC's canonical term order
  EXPECT_THAT(eq.text[0], HasSubstr("theta_ddot"));
  EXPECT_THAT(eq.text[0], HasSubstr("sin(theta)"));
  EXPECT_THAT(eq.text[0], HasSubstr("l^2"));
  EXPECT_THAT(eq.latex[0], HasSubstr("\\ddot{\\theta}"));
  EXPECT_THAT(eq.latex[0], HasSubstr("\\sin(\\theta)"));
  EXPECT_THAT(eq.energy_text, HasSubstr("theta_dot^2"));
}

TEST(System, ConstraintEquationsCarryMultipliers) {
  SystemSpec spec;
  spec.coordinates = {{"x", 1.0}, {"y"}};
  spec.lagrangian = "(x_dot^2 + y_dot^2)/2";
  spec.constraints = {{"line", "x + y - 1"}};
  const Equations eq = System(spec).equations();
  EXPECT_THAT(eq.text[0], HasSubstr("lambda_line"));
  EXPECT_THAT(eq.latex[1], HasSubstr("\\lambda_{\\mathrm{line}}"));
  ASSERT_EQ(eq.constraints_text.size(), 1u);
  EXPECT_THAT(eq.constraints_text[0], HasSubstr("= 0"));
}

TEST(System, TrigonometricIdentitiesCancelInBodyKineticEnergy) {
  // a point mass on a circle of radius l: |ċ|² = l² θ̇² (cos² + sin²) must print as l² θ̇²
  SystemSpec spec;
  spec.parameters = {{"l", 0.5}};
  spec.coordinates = {{"theta"}};
  spec.bodies.push_back(Body{"bob", MassProperties(2.0, Eigen::Vector3d::Zero(),
                                                   Eigen::Matrix3d::Zero()),
                             {"l*sin(theta)", "-l*cos(theta)", "0"}, {}});
  const Equations eq = System(spec).equations();
  EXPECT_THAT(eq.text[0], ::testing::Not(HasSubstr("cos")));
  EXPECT_THAT(eq.text[0], ::testing::Not(HasSubstr("sin")));
}

TEST(System, CyclicCoordinatesAreDetected) {
  SystemSpec spec;
  spec.coordinates = {{"x"}, {"y"}, {"z"}};
  spec.lagrangian = "(x_dot^2 + y_dot^2 + z_dot^2)/2 - 9.81*z";
  spec.forces = {{"y", "-0.1*y_dot"}};  // damping makes y not cyclic
  const System sys(spec);
  EXPECT_EQ(sys.cyclic_coordinates(), std::vector<std::string>{"x"});
}

TEST(System, GeneralizedForceDampsTheMotion) {
  // ẍ = −c ẋ: ẋ(t) = v0 e^{−c t}
  SystemSpec spec;
  spec.parameters = {{"c", 0.5}};
  spec.coordinates = {{"x", 0.0, 2.0}};
  spec.lagrangian = "x_dot^2/2";
  spec.forces = {{"x", "-c*x_dot"}};
  const Trajectory tr = System(spec).simulate({.t_end = 2.0, .tolerance = 1e-12});
  EXPECT_NEAR(tr.q_dot(tr.t.size() - 1, 0), 2.0 * std::exp(-1.0), 1e-10);
  EXPECT_NEAR(tr.q(tr.t.size() - 1, 0), 4.0 * (1 - std::exp(-1.0)), 1e-10);
}

TEST(System, TapeSharesCommonSubexpressions) {
  // a 4-link chain repeats sin/cos of each angle across every entry of M and f
  SystemSpec spec;
  std::string x = "0", y = "0";
  for (int i = 1; i <= 4; ++i) {
    const std::string th = fmt::format("th{}", i);
    spec.coordinates.push_back({th, 0.1 * i, 0.0});
    x = fmt::format("{}+sin({})", x, th);
    y = fmt::format("{}-cos({})", y, th);
    spec.bodies.push_back(Body{fmt::format("b{}", i),
                               MassProperties(1.0, Eigen::Vector3d::Zero(), Eigen::Matrix3d::Zero()),
                               {x, y, "0"}, {}});
  }
  spec.gravity_W = Eigen::Vector3d(0, -9.81, 0);
  const System sys(spec);
  // without sharing M alone would need > 10 entries × several trig calls each; the whole
  // tape (M, f) of the 4-link chain stays a few hundred instructions
  EXPECT_LT(sys.tape_size(), 600u);
  EXPECT_GT(sys.tape_size(), 20u);
}

TEST(System, SameModelTwiceGivesBitwiseEqualTrajectories) {
  // GiNaC orders terms by hash and symbol serial numbers, which differ between two builds in
  // one process; the tape is emitted in a structural order, so results must not differ
  SystemSpec spec;
  spec.parameters = {{"l1", 1.0}, {"l2", 0.8}};
  spec.coordinates = {{"a", 1.0}, {"b", -0.5, 0.3}};
  spec.bodies.push_back(Body{"p", MassProperties(1.0, Eigen::Vector3d::Zero(), Eigen::Matrix3d::Zero()),
                             {"l1*sin(a)", "-l1*cos(a)", "0"}, {}});
  spec.bodies.push_back(Body{"q", MassProperties(0.7, Eigen::Vector3d::Zero(), Eigen::Matrix3d::Zero()),
                             {"l1*sin(a) + l2*sin(b)", "-l1*cos(a) - l2*cos(b)", "0"}, {}});
  spec.gravity_W = Eigen::Vector3d(0, -9.81, 0);
  const System first(spec);
  const System unrelated(pendulum_spec());
  const System second(spec);
  EXPECT_EQ(first.tape_size(), second.tape_size());
  const SimulationOptions o{.t_end = 3.0, .output_dt = 0.5};
  const Trajectory x = first.simulate(o), y = second.simulate(o);
  ASSERT_EQ(x.q.rows(), y.q.rows());
  EXPECT_TRUE((x.q.array() == y.q.array()).all());
  EXPECT_TRUE((x.q_dot.array() == y.q_dot.array()).all());
  EXPECT_TRUE((x.energy.array() == y.energy.array()).all());
}

// ---------------------------------------------------------------------------------------------
// bad input

TEST(SystemErrors, ParseErrorsSayWhere) {
  SystemSpec spec = pendulum_spec();
  spec.lagrangian = "m*l^2/2*theta_dot^2 + * cos(theta)";
  EXPECT_RIGID_ERROR(System{spec}, "Lagrangian: unexpected '*'; expected a number, a name or "
                                   "'(' at column 23");
  spec.lagrangian = "m*(theta_dot^2";
  EXPECT_RIGID_ERROR(System{spec}, "missing ')'");
  spec.lagrangian = "m*theta_dot^2 + cosh(theta) + foo(theta)";
  EXPECT_RIGID_ERROR(System{spec}, "unknown function 'foo'");
  spec.lagrangian = "m*theta_dot^2 2";
  EXPECT_RIGID_ERROR(System{spec}, "unexpected '2'; expected an operator or the end at column 15");
  spec.lagrangian = "m*theta_dot^2/0";
  EXPECT_RIGID_ERROR(System{spec}, "division by zero");
}

TEST(SystemErrors, UndefinedSymbolNamesTheKnownOnes) {
  SystemSpec spec = pendulum_spec();
  spec.lagrangian = "m*l^2/2*theta_dot^2 + m*g*l*cos(thta)";
  EXPECT_RIGID_ERROR(System{spec}, "Lagrangian: undefined symbol 'thta'; known names: g, l, m, "
                                   "t, theta, theta_dot, pi at column 33");
}

TEST(SystemErrors, SourceLocationsPointIntoTheFile) {
  SystemSpec spec = pendulum_spec();
  spec.potentials = {{"spring", Expression("k*theta^2", SourceLocation{"scene.toml", 12, 9})}};
  EXPECT_RIGID_ERROR(System{spec}, "scene.toml:12:9: potential 'spring': undefined symbol 'k'");
}

TEST(SystemErrors, VelocitiesAreRefusedWherePositionsAreExpected) {
  SystemSpec spec = pendulum_spec();
  spec.constraints = {{"c", "theta_dot - 1"}};
  EXPECT_RIGID_ERROR(System{spec}, "constraint 'c': depends on the velocity 'theta_dot'");
  spec = pendulum_spec();
  spec.potentials = {{"V", "theta*theta_dot"}};
  EXPECT_RIGID_ERROR(System{spec}, "potential 'V': depends on the velocity 'theta_dot'");
}

TEST(SystemErrors, BadNames) {
  SystemSpec spec = pendulum_spec();
  spec.parameters.push_back({"theta", 1.0});
  spec.coordinates = {{"theta"}};
  EXPECT_RIGID_ERROR(System{spec}, "coordinate name 'theta' is already used by a parameter");
  spec = pendulum_spec();
  spec.coordinates.push_back({"t"});
  EXPECT_RIGID_ERROR(System{spec}, "coordinate name 't' is reserved");
  spec = pendulum_spec();
  spec.coordinates.push_back({"2x"});
  EXPECT_RIGID_ERROR(System{spec}, "coordinate name '2x' is not a valid name");
  spec = pendulum_spec();
  spec.forces = {{"phi", "1"}};
  EXPECT_RIGID_ERROR(System{spec}, "force on 'phi': no coordinate of that name; coordinates: theta");
  EXPECT_RIGID_ERROR(System{SystemSpec{}}, "a system needs at least one coordinate");
}

TEST(SystemErrors, LagrangianWithoutAVelocityTermIsSingular) {
  SystemSpec spec = pendulum_spec();
  spec.coordinates.push_back({"x"});
  EXPECT_RIGID_ERROR(System{spec}, "the Lagrangian is not quadratic in the velocity 'x_dot'");
}

TEST(SystemErrors, NegativeKineticEnergyIsNotPositiveDefinite) {
  SystemSpec spec;
  spec.coordinates = {{"x", 0.5}};
  spec.lagrangian = "-x_dot^2/2";
  EXPECT_RIGID_ERROR((void)System(spec).simulate({.t_end = 1.0}),
                     "mass matrix M = ∂²L/∂q̇∂q̇ is singular or not positive definite at "
                     "t = 0 s, q = (x = 0.5)");
}

TEST(SystemErrors, MassMatrixBecomingSingularStopsTheRun) {
  // M = x², reaching x = 0 at t = 1 (ẋ = −1 while M ẍ = f = −x ẋ² keeps x ẋ constant)
  SystemSpec spec;
  spec.coordinates = {{"x", 1.0, -1.0}};
  spec.lagrangian = "x^2*x_dot^2/2";
  try {
    (void)System(spec).simulate({.t_end = 2.0, .method = Method::kRk4, .dt = 0.01});
    ADD_FAILURE() << "expected an error";
  } catch (const Error& e) {
    const std::string what = e.what();
    EXPECT_TRUE(what.find("singular or not positive definite at t = ") != std::string::npos ||
                what.find("non-finite state") != std::string::npos) << what;
    EXPECT_THAT(what, HasSubstr("x = "));
  }
}

TEST(SystemErrors, RedundantAndInconsistentConstraints) {
  SystemSpec spec;
  spec.coordinates = {{"x", 1.0}, {"y"}};
  spec.lagrangian = "(x_dot^2 + y_dot^2)/2";
  spec.constraints = {{"a", "x - 1"}, {"b", "2*x - 2"}};
  EXPECT_RIGID_ERROR((void)System(spec).simulate({.t_end = 1.0}),
                     "constraints 'a', 'b' are redundant");
  spec.constraints = {{"a", "x - 1"}, {"b", "x - 2"}};
  EXPECT_RIGID_ERROR((void)System(spec).simulate({.t_end = 1.0}),
                     "constraints 'a', 'b' are inconsistent");
  spec.constraints = {{"a", "t - 1"}};
  EXPECT_RIGID_ERROR(System{spec}, "constraint 'a' = t - 1 does not depend on any coordinate");
  spec.constraints = {{"a", "x - 1"}, {"a", "y"}};
  EXPECT_RIGID_ERROR(System{spec}, "constraint name 'a' is used twice");
}

TEST(SystemErrors, StormerVerletNeedsConstantMassMatrix) {
  SystemSpec spec;
  spec.coordinates = {{"r", 1.0}, {"phi", 0.0, 1.0}};
  spec.lagrangian = "(r_dot^2 + r^2*phi_dot^2)/2 + 1/r";
  EXPECT_RIGID_ERROR(
      (void)System(spec).simulate({.t_end = 1.0, .method = Method::kStormerVerlet}),
      "stormer_verlet needs T = ½ q̇ᵀ M q̇ with a constant M");
}

}  // namespace
}  // namespace rigid::lagrange
