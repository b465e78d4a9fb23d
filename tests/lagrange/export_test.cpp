#include "rigid/lagrange/export.hpp"

#include <cmath>
#include <utility>

#include <fmt/format.h>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "support/expect_error.hpp"
#include "support/tolerance.hpp"

namespace rigid::lagrange {
namespace {

using ::testing::HasSubstr;
using ::testing::Not;

// A mass on a rod of length l swinging about a pivot that slides along x (coordinates x, θ),
// held on the line x = a·θ by a constraint: M, f, G and γ all non-trivial.
SystemSpec slider_spec() {
  SystemSpec spec;
  spec.parameters = {{"m", 2.0}, {"l", 0.5}, {"g", 9.81}, {"a", 0.3}};
  spec.coordinates = {{"x", 0.0, 0.0}, {"theta", 0.0, 0.0}};
  spec.lagrangian = "m/2*((x_dot + l*cos(theta)*theta_dot)^2 + (l*sin(theta)*theta_dot)^2) "
                    "+ m*g*l*cos(theta)";
  spec.constraints = {{"track", "x - a*sin(theta)"}};
  return spec;
}

TEST(Export, ParsesTheLanguagesAndRefusesOthersWithACloseMatch) {
  EXPECT_EQ(parse_language("c++"), Language::kCpp);
  EXPECT_EQ(parse_language("cpp"), Language::kCpp);
  EXPECT_EQ(parse_language("python"), Language::kPython);
  EXPECT_EQ(parse_language("py"), Language::kPython);
  EXPECT_RIGID_ERROR((void)parse_language("pyhton"), "did you mean 'python'?");
  EXPECT_RIGID_ERROR((void)parse_language("rust"), "unknown export language 'rust'; expected c++ or python");
}

TEST(Export, SameSystemGivesTheSameBytes) {
  // two Systems of one spec in one process (GiNaC's term order differs between them)
  const System a(slider_spec()), b(slider_spec());
  EXPECT_EQ(emit_cpp(a), emit_cpp(b));
  EXPECT_EQ(emit_python(a), emit_python(b));
}

TEST(Export, CppIsSelfContainedWithParametersAsNamedDefaults) {
  const System sys(slider_spec());
  ExportOptions o;
  o.name = "slider-1";  // not an identifier: made one
  const std::string code = emit_cpp(sys, o);
  EXPECT_THAT(code, HasSubstr("namespace slider_1 {"));
  EXPECT_THAT(code, HasSubstr("#include <cmath>"));
  EXPECT_THAT(code, Not(HasSubstr("Eigen")));
  EXPECT_THAT(code, HasSubstr("double m = 2.0;"));
  EXPECT_THAT(code, HasSubstr("double g = 9.81;"));
  EXPECT_THAT(code, HasSubstr("inline constexpr int kNumConstraints = 1;"));
  EXPECT_THAT(code, HasSubstr("inline void constraint_gamma("));
  // only <cmath>: no other include
  EXPECT_EQ(code.find("#include"), code.rfind("#include"));
}

TEST(Export, TheSourceStaysOnItsCommentLine) {
  const System sys(slider_spec());
  ExportOptions o;
  o.source = "dir\nint x = 1;/scene.toml";
  const std::string cpp = emit_cpp(sys, o), py = emit_python(sys, o);
  EXPECT_THAT(cpp, HasSubstr("// Equations of motion of dir?int x = 1;/scene.toml, generated"));
  EXPECT_THAT(py, HasSubstr("# Equations of motion of dir?int x = 1;/scene.toml, generated"));
}

TEST(Export, ReservedParameterNamesAreMarked) {
  SystemSpec spec;
  spec.parameters = {{"lambda", 1.0}, {"class", 2.0}, {"q", 3.0}, {"_k", 4.0}, {"M_PI", 5.0}};
  spec.coordinates = {{"x", 0.0, 0.0}};
  spec.lagrangian = "lambda*x_dot^2/2 - class*q*_k*M_PI*x^2/2";
  const System sys(spec);
  const std::string cpp = emit_cpp(sys), py = emit_python(sys);
  // C++: keywords and <cmath> macros; lambda and q are fine there
  EXPECT_THAT(cpp, HasSubstr("double class_ = 2.0;"));
  EXPECT_THAT(cpp, HasSubstr("double M_PI_ = 5.0;"));
  EXPECT_THAT(cpp, HasSubstr("double lambda = 1.0;"));
  EXPECT_THAT(cpp, HasSubstr("double q = 3.0;"));
  EXPECT_THAT(cpp, HasSubstr("double p_k = 4.0;"));  // '_' first: the implementation's
  // Python: keywords, argument names, and names starting with '_'
  EXPECT_THAT(py, HasSubstr("lambda_=1.0"));
  EXPECT_THAT(py, HasSubstr("q_=3.0"));
  EXPECT_THAT(py, HasSubstr("p_k=4.0"));
  EXPECT_THAT(py, HasSubstr("class_=2.0"));
  EXPECT_THAT(py, HasSubstr("\"lambda\": \"lambda_\""));
}

TEST(Export, OneRuleRenamesForBothLanguagesAndTheHeaderListsIt) {
  SystemSpec spec;
  spec.parameters = {{"float", 1.0}, {"float_", 2.0}, {"linux", 3.0}, {"_Complex", 4.0},
                     {"Parameters", 5.0}, {"M", 6.0}, {"range", 7.0}, {"typeof", 8.0}};
  spec.coordinates = {{"x", 0.0, 0.0}};
  spec.lagrangian = "float*float_*linux*_Complex*Parameters*M*range*typeof*x_dot^2/2";
  const System sys(spec);
  ExportOptions o;
  o.name = "main";
  const std::string cpp = emit_cpp(sys, o), py = emit_python(sys, o);
  // C++: keywords and macros take '_' until unused (float_ is taken: float__), a name starting
  // with '_' a 'p', a member may not name its struct; M and range are members p.M, p.range
  EXPECT_THAT(cpp, HasSubstr("  double float__ = 1.0;  // float\n  double float_ = 2.0;\n"));
  EXPECT_THAT(cpp, HasSubstr("  double linux_ = 3.0;  // linux\n"));
  EXPECT_THAT(cpp, HasSubstr("  double p_Complex = 4.0;  // _Complex\n"));
  EXPECT_THAT(cpp, HasSubstr("  double Parameters_ = 5.0;  // Parameters\n"));
  EXPECT_THAT(cpp, HasSubstr("  double M = 6.0;\n  double range = 7.0;\n  double typeof_ = 8.0;"));
  EXPECT_THAT(cpp, HasSubstr("namespace main_ {"));
  EXPECT_THAT(cpp, HasSubstr("}  // namespace main_\n"));
  // the header comment (before the code) lists each rename
  const std::string cpp_header = cpp.substr(0, cpp.find("#pragma once"));
  for (const char* item : {"float → float__,", "linux → linux_,", "_Complex → p_Complex,",
                           "Parameters → Parameters_,", "typeof → typeof_,",
                           "namespace main → main_."}) {
    EXPECT_THAT(cpp_header, HasSubstr(item));
  }
  EXPECT_THAT(cpp_header, Not(HasSubstr("float_ →")));
  // Python: the same rule with Python's words; linux, Parameters and typeof are names there
  EXPECT_THAT(py, HasSubstr("def forces(q, q_dot, t=0.0, *, float__=1.0, float_=2.0, linux=3.0, "
                            "p_Complex=4.0, Parameters=5.0, M=6.0, range_=7.0, typeof=8.0):"));
  const std::string py_header = py.substr(0, py.find("import math"));
  for (const char* item : {"float → float__,", "_Complex → p_Complex,", "range → range_."}) {
    EXPECT_THAT(py_header, HasSubstr(item));
  }
  EXPECT_THAT(py_header, Not(HasSubstr("linux →")));
  // the header's lines stay within 100 columns (UTF-8 continuation bytes take none)
  for (const std::string& header : {cpp_header, py_header}) {
    std::size_t columns = 0;
    for (char c : header) {
      if (c == '\n') {
        columns = 0;
      } else if ((static_cast<unsigned char>(c) & 0xC0) != 0x80) {
        EXPECT_LE(++columns, 100u) << header;
      }
    }
  }
}

TEST(Export, TheNamespaceIsNeverANameBesideIt) {
  // at global scope beside main(), std and what <cmath> declares or defines there
  const System sys(slider_spec());
  const std::pair<const char*, const char*> cases[] = {
      {"main", "main_"},        {"std", "std_"},           {"sin", "sin_"},
      {"expf128", "expf128_"},  {"lgammaf_r", "lgammaf_r_"}, {"f32addf64", "f32addf64_"},
      {"daddl", "daddl_"},      {"strtod_l", "strtod_l_"}, {"random", "random_"},
      {"strfromf128", "strfromf128_"}, {"strtoull", "strtoull_"}, {"strtol_", "strtol_"},
      {"size_t", "size_t_"},    {"linux", "linux_"},       {"M_PIl", "M_PIl_"},
      {"NULL", "NULL_"},        {"float", "float_"},       {"and", "and_"},
      {"_Model", "p_Model"},    {"__x", "p__x"},           {"2d", "model_2d"},
      {"my-model", "my_model"}, {"", "model_"},            {"sine", "sine"},
      {"pendulum", "pendulum"}};
  for (const auto& [name, expected] : cases) {
    ExportOptions o;
    o.name = name;
    EXPECT_THAT(emit_cpp(sys, o), HasSubstr(fmt::format("\nnamespace {} {{\n", expected))) << name;
  }
}

TEST(Export, DynamicsFunctionsOnlyWithoutConstraints) {
  // without constraints: inverse and forward dynamics on mass_matrix_and_forces
  SystemSpec free_slider = slider_spec();
  free_slider.constraints.clear();
  const System free_sys(free_slider);
  const std::string cpp = emit_cpp(free_sys), py = emit_python(free_sys);
  EXPECT_THAT(cpp, HasSubstr("inline void inverse_dynamics(const double q[2], const double q_dot[2], "
                             "const double q_ddot[2], double t, double tau[2], const Parameters& p = {}) {"));
  EXPECT_THAT(cpp, HasSubstr("[[nodiscard]] inline bool forward_dynamics(const double q[2], const double "
                             "q_dot[2], const double tau[2], double t, double q_ddot[2], const Parameters& p = {}) {"));
  EXPECT_THAT(cpp, HasSubstr("  mass_matrix_and_forces(q, q_dot, t, M, f, p);\n"));
  EXPECT_THAT(py, HasSubstr("def inverse_dynamics(q, q_dot, q_ddot, t=0.0, *, m=2.0, l=0.5, g=9.81, a=0.3):"));
  EXPECT_THAT(py, HasSubstr("def forward_dynamics(q, q_dot, tau, t=0.0, *, m=2.0, l=0.5, g=9.81, a=0.3):"));
  EXPECT_THAT(py, HasSubstr("_mass_matrix_and_forces(q, q_dot, t, m=m, l=l, g=g, a=a)"));
  // still only <cmath> and `math`: no linear-algebra library
  EXPECT_EQ(cpp.find("#include"), cpp.rfind("#include"));
  EXPECT_THAT(py, Not(HasSubstr("numpy")));
  EXPECT_EQ(py.find("\nimport "), py.rfind("\nimport "));  // `import math` only
  // the functions before them are those of the system's file without them: the new ones are
  // added at the end
  const std::size_t end_cpp = cpp.find("/// τ = M q̈ − f");
  ASSERT_NE(end_cpp, std::string::npos);
  EXPECT_EQ(cpp.find("inline void constraint_gamma("), cpp.rfind("inline void constraint_gamma("));
  EXPECT_LT(cpp.find("inline void constraint_gamma("), end_cpp);

  // with a constraint: neither, and a comment saying why
  const System sys(slider_spec());
  const std::string ccpp = emit_cpp(sys), cpy = emit_python(sys);
  for (const std::string& code : {ccpp, cpy}) {
    EXPECT_THAT(code, Not(HasSubstr("inverse_dynamics(")));
    EXPECT_THAT(code, Not(HasSubstr("forward_dynamics(")));
    EXPECT_THAT(code, HasSubstr("inverse_dynamics and forward_dynamics are not exported: the system has "
                                "constraints (m = 1),"));
  }
}

TEST(Export, PythonMarksParametersNamedLikeTheDynamicsArguments) {
  SystemSpec spec;
  spec.parameters = {{"tau", 2.0}, {"q_ddot", 3.0}};
  spec.coordinates = {{"x", 0.0, 0.0}};
  spec.lagrangian = "tau*x_dot^2/2 - q_ddot*x^2/2";
  const std::string py = emit_python(System(spec));
  EXPECT_THAT(py, HasSubstr("def forward_dynamics(q, q_dot, tau, t=0.0, *, tau_=2.0, q_ddot_=3.0):"));
  EXPECT_THAT(py, HasSubstr("\"tau\": \"tau_\""));
  // C++ reads them as p.tau, p.q_ddot: no mark
  EXPECT_THAT(emit_cpp(System(spec)), HasSubstr("double tau = 2.0;"));
}

TEST(Export, ConstraintTermsSatisfyTheEquationsOfMotion) {
  // q̈ and λ from the engine satisfy M q̈ = f + Gᵀλ and G q̈ = γ with the G and γ returned
  const System sys(slider_spec());
  Workspace w = sys.make_workspace();
  const Eigen::VectorXd q = Eigen::Vector2d(0.2, 0.4), qd = Eigen::Vector2d(-0.3, 1.1);
  Eigen::MatrixXd M, G;
  Eigen::VectorXd f, gamma, qdd, lambda;
  sys.mass_matrix_and_forces(w, 0.0, q, qd, M, f);
  constraint_terms(sys, w, 0.0, q, qd, G, gamma);
  sys.accelerations(w, 0.0, q, qd, qdd, lambda);
  ASSERT_EQ(G.rows(), 1);
  ASSERT_EQ(G.cols(), 2);
  // g = x − a sin θ: G = (1, −a cos θ), γ = −a sin θ θ̇² (from g̈ = ẍ − a cos θ θ̈ + a sin θ θ̇²)
  EXPECT_NEAR(G(0, 0), 1.0, test::ulps(2));
  EXPECT_NEAR(G(0, 1), -0.3 * std::cos(0.4), test::ulps(4));
  EXPECT_NEAR(gamma[0], -0.3 * std::sin(0.4) * 1.1 * 1.1, test::ulps(8));
  // residuals of a solve with M ≈ 1 and |f| ≈ 10: 1e-12 covers its round-off
  EXPECT_NEAR((G * qdd)[0], gamma[0], 1e-12);
  EXPECT_LT((M * qdd - f - G.transpose() * lambda).norm(), 1e-12);
}

TEST(Export, ConstraintTermsRefuseAnotherSystemsWorkspace) {
  const System a(slider_spec()), b(slider_spec());
  Workspace w = b.make_workspace();
  Eigen::MatrixXd G;
  Eigen::VectorXd gamma;
  EXPECT_RIGID_ERROR(constraint_terms(a, w, 0.0, Eigen::Vector2d::Zero(), Eigen::Vector2d::Zero(), G, gamma),
                     "belongs to another System");
  Workspace wa = a.make_workspace();
  EXPECT_RIGID_ERROR(constraint_terms(a, wa, 0.0, Eigen::Vector3d::Zero(), Eigen::Vector2d::Zero(), G, gamma),
                     "expected q and q_dot of size 2");
}

}  // namespace
}  // namespace rigid::lagrange
