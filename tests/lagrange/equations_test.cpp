// System::equations() and format_equations(): the printed, simplified, structured equations.
#include <sstream>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "rigid/lagrange/system.hpp"
#include "support/expect_error.hpp"

namespace rigid::lagrange {
namespace {

using ::testing::HasSubstr;
using ::testing::Not;

// The planar double pendulum of examples/double_pendulum.toml: two point masses on rods.
SystemSpec double_pendulum() {
  SystemSpec spec;
  spec.parameters = {{"g", 9.81}, {"m1", 1.0}, {"m2", 1.0}, {"l1", 1.0}, {"l2", 1.0}};
  spec.coordinates = {{"theta1", 1.0}, {"theta2", 0.5}};
  BodyMass m1, m2;
  m1.mass = "m1";
  m2.mass = "m2";
  spec.bodies.push_back(Body{"bob1", m1, {"l1*sin(theta1)", "0", "-l1*cos(theta1)"}, {}});
  spec.bodies.push_back(Body{"bob2", m2, {"l1*sin(theta1) + l2*sin(theta2)", "0",
                                          "-l1*cos(theta1) - l2*cos(theta2)"}, {}});
  spec.gravity_W = Vector3Expression(std::array<Expression, 3>{"0", "0", "-g"});
  return spec;
}

// A line that starts (after blanks) with a lone name and then '=' or '&=': a label such as
// "L =". `words`: a name is a word ([A-Za-z_][A-Za-z0-9_]*), else one letter. (By hand:
// <regex> makes GCC 12 warn wrongly under the sanitizers.)
bool starts_with_label(const std::string& line, bool words) {
  auto letter = [](char c) { return (c >= 'A' && c <= 'Z') || (c >= 'a' && c <= 'z'); };
  auto digit = [](char c) { return c >= '0' && c <= '9'; };
  std::size_t i = line.find_first_not_of(" \t");
  if (i == std::string::npos || !(letter(line[i]) || (words && line[i] == '_'))) return false;
  ++i;
  while (words && i < line.size() && (letter(line[i]) || digit(line[i]) || line[i] == '_')) ++i;
  while (i < line.size() && (line[i] == ' ' || line[i] == '\t')) ++i;
  if (!words && i < line.size() && line[i] == '&') ++i;
  return i < line.size() && line[i] == '=';
}

TEST(EquationLabels, TheLabelCheckFindsLabels) {
  EXPECT_TRUE(starts_with_label("  L = 1/2*m*x_dot^2", true));
  EXPECT_TRUE(starts_with_label("h_1= 3", true));
  EXPECT_FALSE(starts_with_label("  m*x_ddot = -k*x", true));
  EXPECT_FALSE(starts_with_label("Lagrangian:", true));
  EXPECT_TRUE(starts_with_label("L &= T - V", false));
  EXPECT_FALSE(starts_with_label("\\mathcal{L} &= T - V", false));
}

TEST(Equations, DoublePendulumAsATextbookWritesIt) {
  const Equations eq = System(double_pendulum()).equations();
  // M = [[(m1 + m2) l1², m2 l1 l2 cos(θ1 − θ2)], [m2 l1 l2 cos(θ1 − θ2), m2 l2²]]
  // [Goldstein2002, §1.6 ex. / Taylor2005 §11.4]
  ASSERT_EQ(eq.mass_matrix.size(), 2u);
  EXPECT_EQ(eq.mass_matrix[0][0].text, "(m1 + m2)*l1^2");
  EXPECT_EQ(eq.mass_matrix[0][1].text, "m2*l1*l2*cos(theta1 - theta2)");
  EXPECT_EQ(eq.mass_matrix[1][0].text, "m2*l1*l2*cos(theta1 - theta2)");
  EXPECT_EQ(eq.mass_matrix[1][1].text, "m2*l2^2");
  EXPECT_EQ(eq.mass_matrix[0][1].latex, "m_{2} l_{1} l_{2} \\cos(\\theta_{1} - \\theta_{2})");
  EXPECT_EQ(eq.text[0],
            "(m1 + m2)*l1^2*theta1_ddot + m2*l1*l2*cos(theta1 - theta2)*theta2_ddot = "
            "-(m1 + m2)*g*l1*sin(theta1) - m2*l1*l2*sin(theta1 - theta2)*theta2_dot^2");
  EXPECT_EQ(eq.text[1],
            "m2*l1*l2*cos(theta1 - theta2)*theta1_ddot + m2*l2^2*theta2_ddot = "
            "m2*l1*l2*sin(theta1 - theta2)*theta1_dot^2 - g*m2*l2*sin(theta2)");
  // f = inertial + potential; no generalized forces, so h is conserved
  EXPECT_EQ(eq.forcing_potential[1].text, "-g*m2*l2*sin(theta2)");
  EXPECT_EQ(eq.forcing_inertial[1].text, "m2*l1*l2*sin(theta1 - theta2)*theta1_dot^2");
  EXPECT_EQ(eq.forcing_generalized[1].text, "0");
  EXPECT_TRUE(eq.jacobi_conserved);
}

TEST(Equations, SameBytesFromTwoDerivations) {
  const std::string a = format_equations(System(double_pendulum()).equations(), EquationFormat::kJson);
  const std::string b = format_equations(System(double_pendulum()).equations(), EquationFormat::kJson);
  EXPECT_EQ(a, b);
}

TEST(Equations, GeneralizedForcesAndTimeAreReported) {
  SystemSpec spec;
  spec.parameters = {{"m", 2.0}, {"l", 0.5}, {"g", 9.81}, {"c", 0.1}};
  spec.coordinates = {{"theta", 0.3, 0.0}};
  spec.lagrangian = "m*l^2/2*theta_dot^2 + m*g*l*cos(theta)";
  spec.forces = {{"theta", "-c*theta_dot"}};
  const Equations eq = System(spec).equations();
  EXPECT_EQ(eq.forcing_generalized[0].text, "-c*theta_dot");
  EXPECT_EQ(eq.forcing_potential[0].text, "-m*l*g*sin(theta)");
  EXPECT_EQ(eq.forcing_inertial[0].text, "0");
  EXPECT_EQ(eq.text[0], "m*l^2*theta_ddot = -m*l*g*sin(theta) - c*theta_dot");
  EXPECT_FALSE(eq.jacobi_conserved);
}

TEST(Equations, LabelsNeverCollideWithParameterNames) {
  // parameters named like the labels a printout might use: L, T, V, h, M, f, G, p
  SystemSpec spec;
  spec.parameters = {{"L", 1.0}, {"T", 2.0}, {"V", 3.0}, {"h", 0.5}, {"M", 1.5}, {"f", 0.2},
                     {"G", 9.81}, {"p", 0.3}};
  spec.coordinates = {{"x", 0.1}, {"phi", 0.0}};
  spec.lagrangian = "M*x_dot^2/2 + L*T*phi_dot^2/2 - G*h*x - V*f*p*x^2";
  const Equations eq = System(spec).equations();
  const std::string text = format_equations(eq, EquationFormat::kText);
  const std::string latex = format_equations(eq, EquationFormat::kLatex);
  // no line of the text starts with a lone name and '=' (a label); the equations are
  // "lhs = rhs" lines with the accelerations on the left
  std::istringstream lines(text);
  for (std::string line; std::getline(lines, line);) {
    EXPECT_FALSE(starts_with_label(line, true)) << line << "\n" << text;
  }
  for (const char* label : {"\\mathcal{L} &=", "\\mathcal{T} &=", "\\mathcal{V} &=", "\\mathcal{H} &=",
                            "\\mathbf{M} &=", "\\mathbf{f} &=", "\\frac{\\partial \\mathcal{L}}{\\partial \\dot{\\phi}} &="}) {
    EXPECT_THAT(latex, HasSubstr(label));
  }
  std::istringstream tex(latex);
  for (std::string line; std::getline(tex, line);) {
    EXPECT_FALSE(starts_with_label(line, false)) << line;
  }
  EXPECT_THAT(latex, HasSubstr("\\begin{align*}"));
  EXPECT_THAT(latex, HasSubstr("\\end{align*}"));
  // φ is cyclic: its momentum is listed with the conserved quantities
  EXPECT_EQ(eq.cyclic, std::vector<std::string>{"phi"});
  ASSERT_EQ(eq.cyclic_momenta.size(), 1u);
  EXPECT_EQ(eq.cyclic_momenta[0].text, "L*T*phi_dot");
}

TEST(Equations, ConstraintsAndTheirJacobian) {
  SystemSpec spec;
  spec.parameters = {{"R", 0.1}};
  spec.coordinates = {{"y"}, {"phi"}};
  spec.lagrangian = "(y_dot^2 + phi_dot^2)/2";
  spec.constraints = {{"rope", "y - R*phi"}};
  const Equations eq = System(spec).equations();
  ASSERT_EQ(eq.constraint_jacobian.size(), 1u);
  EXPECT_EQ(eq.constraint_jacobian[0][0].text, "1");
  EXPECT_EQ(eq.constraint_jacobian[0][1].text, "-R");
  EXPECT_EQ(eq.constraints[0].text, "y - R*phi");
  EXPECT_EQ(eq.text[1], "phi_ddot = -R*lambda_rope");
  EXPECT_THAT(format_equations(eq, EquationFormat::kLatex), HasSubstr("\\text{(rope)}"));
}

TEST(Equations, FormatNamesAreChecked) {
  EXPECT_EQ(parse_equation_format("json"), EquationFormat::kJson);
  EXPECT_RIGID_ERROR((void)parse_equation_format("html"), "unknown equation format 'html'; expected text, latex or json");
}

}  // namespace
}  // namespace rigid::lagrange
