// The regressor of a robot model as code (regressor_export.hpp).
//
// The exported regressor is robot::regressor's recursion (regressor.cpp) with the model's
// placements, joint axes, anchors and references written in as constants: a forward pass that
// places each link and carries its spatial velocity and acceleration through its joints, then
// per link with an inertial its wrench basis Ψ in the world frame, projected on the axis of
// every joint between the link and the root. The operations live in a few small helpers of the
// file (3 × 3 products, the hinge's Rodrigues rotation, Ψ), called once per link and joint, so
// the file reads as the model does: one block per link.
#include "rigid/robot/regressor_export.hpp"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstddef>
#include <string_view>

#include <fmt/format.h>
#include <fmt/ranges.h>

#include "rigid/common/error.hpp"
#include "joint_motion.hpp"

namespace rigid::robot {
namespace {

constexpr std::size_t kLinkParameters = 10;
constexpr std::size_t kJointParameters = 3;  // Ia, fv, k

// A double as a literal of either language: the shortest decimal that reads back to it, with a
// '.0' where it would read as an integer.
std::string literal(double v) {
  RIGID_REQUIRE_AS("regressor export", std::isfinite(v), "a constant of the model is {}", v);
  std::string s = fmt::format("{}", v);
  if (s.find_first_of(".e") == std::string::npos) s += ".0";
  return s;
}

std::string literals(const double* v, std::size_t n) {
  std::vector<std::string> out;
  for (std::size_t k = 0; k < n; ++k) out.push_back(literal(v[k]));
  return fmt::format("{}", fmt::join(out, ", "));
}

std::string row_major(const Eigen::Matrix3d& m) {
  const double v[9] = {m(0, 0), m(0, 1), m(0, 2), m(1, 0), m(1, 1),
                       m(1, 2), m(2, 0), m(2, 1), m(2, 2)};
  return literals(v, 9);
}

std::string vector3(const Eigen::Vector3d& v) { return literals(v.data(), 3); }

// "x - ref" with the reference folded into one literal: "q[2]", "q[2] - 0.5", "q[2] + 0.5"
std::string offset(const std::string& x, double ref) {
  if (ref == 0) return x;
  return ref > 0 ? fmt::format("{} - {}", x, literal(ref))
                 : fmt::format("{} + {}", x, literal(-ref));
}

std::string quoted(std::string_view s) {
  std::string out = "\"";
  for (const char c : s) {
    if (c == '"' || c == '\\') {
      out += '\\';
      out += c;
    } else if (static_cast<unsigned char>(c) < 0x20 || c == 0x7f) {
      // three octal digits: the same in C++ and Python, and (unlike \x) never longer
      out += fmt::format("\\{:03o}", static_cast<unsigned char>(c));
    } else {
      out += c;
    }
  }
  return out + "\"";
}

// A name of the model in a comment: one line, no control characters.
std::string comment_text(std::string_view s) {
  std::string out;
  for (const char c : s) {
    out += static_cast<unsigned char>(c) < 0x20 || c == 0x7f ? '?' : c;
  }
  return out;
}

bool has_inertial(const io::RobotLink& link) {
  return link.mass > 0 || !link.inertia_com.isZero(0);
}

// The layout of π and of the coordinates (as regressor.cpp's): per link its first column (none:
// npos), its joints' first column and its first coordinate.
struct Layout {
  std::vector<std::size_t> link_column, joint_column, first_q, first_dof;
  std::size_t parameters = 0, nq = 0, dof = 0;  // dof: nv
  bool rotations = false;                      // a ball or free joint (nq ≠ nv)
};

Layout layout_of(const io::RobotModel& model) {
  Layout l;
  for (const io::RobotLink& link : model.links) {
    l.link_column.push_back(has_inertial(link) ? l.parameters : std::string::npos);
    if (has_inertial(link)) l.parameters += kLinkParameters;
    l.joint_column.push_back(l.parameters);
    l.parameters += kJointParameters * link.joints.size();
    l.first_q.push_back(l.nq);
    l.first_dof.push_back(l.dof);
    for (const io::RobotJoint& joint : link.joints) {
      l.nq += static_cast<std::size_t>(io::position_count(joint.type));
      l.dof += static_cast<std::size_t>(io::velocity_count(joint.type));
    }
  }
  l.rotations = l.nq != l.dof;
  return l;
}

// The file's opening comment, in either language's comment marker.
std::string header_comment(const io::RobotModel& model, const Layout& layout,
                           const BaseParameters& base, const RegressorExportOptions& options,
                           std::string_view mark) {
  const StandardParameters& s = base.standard;
  std::string out = fmt::format(
      "{0} The inverse-dynamics regressor of {1}: tau = Y(q, q_dot, q_ddot) pi = "
      "Y_b(q, q_dot, q_ddot) beta,\n"
      "{0} exported by rigid (rigid eom MODEL --regressor --emit). Gravity ({2}) m/s^2 and the "
      "joints'\n"
      "{0} passive forces are in Y: tau is the whole joint force of the inverse dynamics.\n"
      "{0}\n"
      "{0} pi, the {3} standard parameters: per link with an inertial, in its frame about its "
      "origin,\n"
      "{0}   m, mx, my, mz (m c), Ixx, Ixy, Ixz, Iyy, Iyz, Izz (J = I_C + m (|c|^2 1 - c c^T), "
      "J_xy = -int x y dm);\n"
      "{0}   per joint: Ia (armature), fv (viscous damping), k (stiffness; its column "
      "q - springref{7}).\n"
      "{0} beta, the {4} base parameters (the identifiable combinations; rank of Y stacked at "
      "{5} random\n"
      "{0} states, seed {6}), beta = C pi:\n",
      mark, options.source.empty() ? "a robot model" : comment_text(options.source),
      vector3(model.gravity), s.values.size(), base.rank, base.samples,
      // the seed is the default of BaseParameterOptions, as rigid eom uses it
      BaseParameterOptions{}.seed,
      layout.rotations
          ? fmt::format(";\n{}   a ball's the rotation vector r of its quaternion, a free joint's "
                        "(p - p0, r of q0^-1 q)",
                        mark)
          : std::string());
  for (std::size_t i = 0; i < base.rank; ++i) {
    out += fmt::format("{}   {} = {}\n", mark, base.name(i), comment_text(base.expression(i)));
  }
  if (!base.unidentifiable.empty()) {
    std::vector<std::string> names;
    for (const std::size_t u : base.unidentifiable) names.push_back(comment_text(s.names[u]));
    out += fmt::format("{} unidentifiable (their columns of Y are 0): {}\n", mark,
                       fmt::join(names, ", "));
  }
  return out;
}

// ---- C++ ----

// The helpers of ball and free joints, written only into the files of models that have them.
constexpr const char* kCppRotationHelpers = R"(namespace detail {

// The rotation of a quaternion q = (w, x, y, z), 3 x 3 row-major: q/|q|'s for any q != 0.
inline void quaternion_rotation(const double* q, double* R) {
  const double w = q[0], x = q[1], y = q[2], z = q[3];
  const double s = 2 / (w * w + x * x + y * y + z * z);
  R[0] = 1 - s * (y * y + z * z);
  R[1] = s * (x * y - w * z);
  R[2] = s * (x * z + w * y);
  R[3] = s * (x * y + w * z);
  R[4] = 1 - s * (x * x + z * z);
  R[5] = s * (y * z - w * x);
  R[6] = s * (x * z - w * y);
  R[7] = s * (y * z + w * x);
  R[8] = 1 - s * (x * x + y * y);
}

// The link's three axes through x (world), s_k = (R e_k, x x R e_k) into S (18 values): fixed in
// the link, so all three are carried by the velocity the link had before them (V0).
inline void link_axes(const double* x, const double* rate, const double* accel, const double* R,
                      double* V, double* A, double* S) {
  double V0[6], vxs[6], t[3];
  for (int k = 0; k < 6; ++k) V0[k] = V[k];
  for (int j = 0; j < 3; ++j) {
    double* s = S + 6 * j;
    for (int k = 0; k < 3; ++k) s[k] = R[3 * k + j];
    cross(x, s, s + 3);
    cross(V0, s, vxs);
    cross(V0, s + 3, vxs + 3);
    cross(V0 + 3, s, t);
    for (int k = 0; k < 3; ++k) vxs[3 + k] += t[k];
    for (int k = 0; k < 6; ++k) {
      A[k] += vxs[k] * rate[j] + s[k] * accel[j];
      V[k] += s[k] * rate[j];
    }
  }
}

// A ball about `anchor` (link frame) turned by the quaternion q (parent side <- link): the link
// turns about the anchor; its three axes through it (link_axes) into S.
inline void ball_joint(const double* anchor, const double* q, const double* rate,
                       const double* accel, double* R, double* p, double* V, double* A, double* S) {
  double x[3], t[3], Q[9], Rn[9];
  mul3(R, anchor, t);
  for (int k = 0; k < 3; ++k) x[k] = p[k] + t[k];
  quaternion_rotation(q, Q);
  mul33(R, Q, Rn);
  for (int k = 0; k < 9; ++k) R[k] = Rn[k];
  mul3(R, anchor, t);
  for (int k = 0; k < 3; ++k) p[k] = x[k] - t[k];
  link_axes(x, rate, accel, R, V, A, S);
}

// A free joint: the link's origin at `position` (world), turned by the quaternion q (world <-
// link); three world-fixed translations, then the link's axes through its origin, into S (36).
inline void free_joint(const double* position, const double* q, const double* rate,
                       const double* accel, double* R, double* p, double* V, double* A, double* S) {
  for (int j = 0; j < 3; ++j) {
    double* s = S + 6 * j;
    for (int k = 0; k < 6; ++k) s[k] = k == 3 + j ? 1 : 0;
    A[3 + j] += accel[j];  // a world-fixed translation: V x s has no part
    V[3 + j] += rate[j];
  }
  quaternion_rotation(q, R);
  for (int k = 0; k < 3; ++k) p[k] = position[k];
  link_axes(p, rate + 3, accel + 3, R, V, A, S + 18);
}

// The rotation vector r of a quaternion (angle in [-pi, pi] about its axis; MuJoCo's
// mju_quat2Vel), the column of a ball joint's stiffness.
inline void rotation_vector(const double* q, double* r) {
  const double s = std::sqrt(q[1] * q[1] + q[2] * q[2] + q[3] * q[3]);
  if (!(s > 0)) {
    r[0] = r[1] = r[2] = 0;
    return;
  }
  double angle = 2 * std::atan2(s, q[0]);
  if (angle > 3.14159265358979323846) angle -= 2 * 3.14159265358979323846;
  for (int k = 0; k < 3; ++k) r[k] = angle / s * q[1 + k];
}

// r of q0^-1 q: a free joint's turn from its reference orientation q0.
inline void relative_rotation_vector(const double* q0, const double* q, double* r) {
  const double d[4] = {q0[0] * q[0] + q0[1] * q[1] + q0[2] * q[2] + q0[3] * q[3],
                       q0[0] * q[1] - q0[1] * q[0] - q0[2] * q[3] + q0[3] * q[2],
                       q0[0] * q[2] + q0[1] * q[3] - q0[2] * q[0] - q0[3] * q[1],
                       q0[0] * q[3] - q0[1] * q[2] + q0[2] * q[1] - q0[3] * q[0]};
  rotation_vector(d, r);
}

}  // namespace detail
)";

constexpr const char* kCppHelpers = R"(namespace detail {

// C = A B, 3 x 3 row-major
inline void mul33(const double* A, const double* B, double* C) {
  for (int i = 0; i < 3; ++i) {
    for (int j = 0; j < 3; ++j) {
      C[3 * i + j] = A[3 * i] * B[j] + A[3 * i + 1] * B[3 + j] + A[3 * i + 2] * B[6 + j];
    }
  }
}

// y = A x
inline void mul3(const double* A, const double* x, double* y) {
  for (int i = 0; i < 3; ++i) y[i] = A[3 * i] * x[0] + A[3 * i + 1] * x[1] + A[3 * i + 2] * x[2];
}

// y = A^T x
inline void mul3t(const double* A, const double* x, double* y) {
  for (int i = 0; i < 3; ++i) y[i] = A[i] * x[0] + A[3 + i] * x[1] + A[6 + i] * x[2];
}

inline void cross(const double* a, const double* b, double* c) {
  c[0] = a[1] * b[2] - a[2] * b[1];
  c[1] = a[2] * b[0] - a[0] * b[2];
  c[2] = a[0] * b[1] - a[1] * b[0];
}

// A root link at its placement (Rc, pc) in the world: at rest, its acceleration less gravity
// is -g (the world accelerates upwards). V, A: spatial (angular; linear at the world origin).
inline void place_root(const double* Rc, const double* pc, const double* g, double* R, double* p,
                       double* V, double* A) {
  for (int k = 0; k < 9; ++k) R[k] = Rc[k];
  for (int k = 0; k < 3; ++k) {
    p[k] = pc[k];
    V[k] = V[3 + k] = A[k] = 0;
    A[3 + k] = -g[k];
  }
}

// A link at its placement (Rc, pc) on its parent (Rp, pp), moving with it.
inline void place(const double* Rp, const double* pp, const double* Vp, const double* Ap,
                  const double* Rc, const double* pc, double* R, double* p, double* V, double* A) {
  mul33(Rp, Rc, R);
  mul3(Rp, pc, p);
  for (int k = 0; k < 3; ++k) p[k] += pp[k];
  for (int k = 0; k < 6; ++k) {
    V[k] = Vp[k];
    A[k] = Ap[k];
  }
}

// A joint's axis s moves the link: A += (V x s) rate + s accel, V += s rate.
inline void carry(const double* s, double rate, double accel, double* V, double* A) {
  double vxs[6], t[3];
  cross(V, s, vxs);
  cross(V, s + 3, vxs + 3);
  cross(V + 3, s, t);
  for (int k = 0; k < 3; ++k) vxs[3 + k] += t[k];
  for (int k = 0; k < 6; ++k) {
    A[k] += vxs[k] * rate + s[k] * accel;
    V[k] += s[k] * rate;
  }
}

// A hinge about the unit `axis` through `anchor` (link frame) turned by `angle`: s = (u, x x u)
// with u and x the axis and anchor in the world; the link turns about the anchor (Rodrigues).
inline void hinge(const double* axis, const double* anchor, double angle, double rate,
                  double accel, double* R, double* p, double* V, double* A, double* s) {
  double x[3], t[3];
  mul3(R, axis, s);
  mul3(R, anchor, t);
  for (int k = 0; k < 3; ++k) x[k] = p[k] + t[k];
  cross(x, s, s + 3);
  const double c = std::cos(angle), sn = std::sin(angle), v = 1 - c;
  const double a0 = axis[0], a1 = axis[1], a2 = axis[2];
  const double Q[9] = {c + v * a0 * a0,      v * a0 * a1 - sn * a2, v * a0 * a2 + sn * a1,
                       v * a0 * a1 + sn * a2, c + v * a1 * a1,      v * a1 * a2 - sn * a0,
                       v * a0 * a2 - sn * a1, v * a1 * a2 + sn * a0, c + v * a2 * a2};
  double Rn[9];
  mul33(R, Q, Rn);
  for (int k = 0; k < 9; ++k) R[k] = Rn[k];
  mul3(R, anchor, t);
  for (int k = 0; k < 3; ++k) p[k] = x[k] - t[k];
  carry(s, rate, accel, V, A);
}

// A slide along the unit `axis` (link frame) by `amount`: s = (0, u).
inline void slide(const double* axis, double amount, double rate, double accel, double* R,
                  double* p, double* V, double* A, double* s) {
  s[0] = s[1] = s[2] = 0;
  mul3(R, axis, s + 3);
  for (int k = 0; k < 3; ++k) p[k] += s[3 + k] * amount;
  carry(s, rate, accel, V, A);
}

// Psi (6 x 10 row-major): the wrench (moment about the world origin; force) of a link in the
// world frame per unit of each of its 10 parameters, from its motion (Atkeson, An & Hollerbach
// 1986): in its frame, f = m a + al x mc + w x (w x mc), n = J al + w x (J w) + mc x a.
inline void link_wrench(const double* R, const double* p, const double* V, const double* A,
                        double* psi) {
  double t[3], vp[3], ap[3], w[3], al[3], a[3];
  cross(V, p, t);
  for (int k = 0; k < 3; ++k) vp[k] = V[3 + k] + t[k];
  cross(A, p, t);
  for (int k = 0; k < 3; ++k) ap[k] = A[3 + k] + t[k];
  cross(V, vp, t);
  for (int k = 0; k < 3; ++k) ap[k] += t[k];
  mul3t(R, V, w);
  mul3t(R, A, al);
  mul3t(R, ap, a);
  const double W[9] = {0, -w[2], w[1], w[2], 0, -w[0], -w[1], w[0], 0};
  const double Lw[18] = {w[0], w[1], w[2], 0, 0, 0, 0, w[0], 0, w[1], w[2], 0, 0, 0, w[0], 0, w[1], w[2]};
  const double La[18] = {al[0], al[1], al[2], 0, 0, 0, 0, al[0], 0, al[1], al[2], 0, 0, 0, al[0], 0, al[1], al[2]};
  const double Hal[9] = {0, -al[2], al[1], al[2], 0, -al[0], -al[1], al[0], 0};
  double L[60] = {};  // in the link frame: moment rows 0-2, force rows 3-5
  L[2] = a[2];
  L[3] = -a[1];
  L[11] = -a[2];
  L[13] = a[0];
  L[21] = a[1];
  L[22] = -a[0];
  for (int i = 0; i < 3; ++i) {
    for (int j = 0; j < 6; ++j) {
      L[10 * i + 4 + j] = La[6 * i + j] + W[3 * i] * Lw[j] + W[3 * i + 1] * Lw[6 + j] + W[3 * i + 2] * Lw[12 + j];
    }
    L[10 * (3 + i)] = a[i];
    for (int j = 0; j < 3; ++j) {
      L[10 * (3 + i) + 1 + j] = Hal[3 * i + j] + W[3 * i] * W[j] + W[3 * i + 1] * W[3 + j] + W[3 * i + 2] * W[6 + j];
    }
  }
  // in the world: f = R f_L, n = R n_L + p x f
  for (int j = 0; j < 10; ++j) {
    const double nL[3] = {L[j], L[10 + j], L[20 + j]}, fL[3] = {L[30 + j], L[40 + j], L[50 + j]};
    double f[3], n[3];
    mul3(R, fL, f);
    mul3(R, nL, n);
    cross(p, f, t);
    for (int k = 0; k < 3; ++k) {
      psi[10 * k + j] = n[k] + t[k];
      psi[10 * (3 + k) + j] = f[k];
    }
  }
}

// y[j] = s . psi[:, j]: a joint's share of a link's wrench, per parameter
inline void project(const double* s, const double* psi, double* y) {
  for (int j = 0; j < 10; ++j) {
    double sum = 0;
    for (int r = 0; r < 6; ++r) sum += s[r] * psi[10 * r + j];
    y[j] = sum;
  }
}

}  // namespace detail
)";

// The body of the regressor in either language, from the model (one block per link).
struct Printer {
  const io::RobotModel& model;
  const Layout& layout;
  bool python;

  std::string link_comment(std::size_t i) const {
    const io::RobotLink& link = model.links[i];
    const std::string parent =
        link.parent < 0
            ? std::string("the world")
            : fmt::format("'{}'", comment_text(model.links[static_cast<std::size_t>(link.parent)].name));
    return fmt::format("{} link '{}' on {}", python ? "#" : "//", comment_text(link.name), parent);
  }

  std::string forward_pass() const {
    const char* in = python ? "    " : "  ";
    std::string out;
    for (std::size_t i = 0; i < model.links.size(); ++i) {
      const io::RobotLink& link = model.links[i];
      out += fmt::format("{}{}\n", in, link_comment(i));
      if (python) {
        if (link.parent < 0) {
          out += fmt::format("{0}R{1}, p{1}, V{1}, A{1} = _place_root(({2}), ({3}), _G)\n", in, i,
                             row_major(link.rotation), vector3(link.position));
        } else {
          out += fmt::format(
              "{0}R{1}, p{1}, V{1}, A{1} = _place(R{4}, p{4}, V{4}, A{4}, ({2}), ({3}))\n", in, i,
              row_major(link.rotation), vector3(link.position), link.parent);
        }
      } else {
        out += fmt::format("{0}static constexpr double Rc{1}[9] = {{{2}}}, pc{1}[3] = {{{3}}};\n",
                           in, i, row_major(link.rotation), vector3(link.position));
        out += fmt::format("{0}double R{1}[9], p{1}[3], V{1}[6], A{1}[6];\n", in, i);
        if (link.parent < 0) {
          out += fmt::format("{0}detail::place_root(Rc{1}, pc{1}, g, R{1}, p{1}, V{1}, A{1});\n",
                             in, i);
        } else {
          out += fmt::format(
              "{0}detail::place(R{2}, p{2}, V{2}, A{2}, Rc{1}, pc{1}, R{1}, p{1}, V{1}, A{1});\n",
              in, i, link.parent);
        }
      }
      std::size_t c = layout.first_dof[i];
      std::size_t e = layout.first_q[i];
      for (const io::RobotJoint& joint : link.joints) {
        if (joint.type == io::RobotJointType::kBall || joint.type == io::RobotJointType::kFree) {
          out += rotation_joint(joint, i, e, c);
          e += static_cast<std::size_t>(io::position_count(joint.type));
          c += static_cast<std::size_t>(io::velocity_count(joint.type));
          continue;
        }
        const bool hinge = joint.type == io::RobotJointType::kHinge;
        const std::string amount = offset(fmt::format("q[{}]", e), joint.ref);
        out += fmt::format("{}{} joint '{}' ({}, coordinate {})\n", in, python ? "#" : "//",
                           comment_text(joint.name), hinge ? "hinge" : "slide",
                           layout.rotations ? fmt::format("q[{}], velocity {}", e, c)
                                            : fmt::format("{}", c));
        if (python) {
          out += fmt::format(
              fmt::runtime(hinge ? "{0}S[{1}] = _hinge(({2}), ({3}), {4}, q_dot[{1}], q_ddot[{1}], R{5}, p{5}, "
                      "V{5}, A{5})\n"
                    : "{0}S[{1}] = _slide(({2}), {4}, q_dot[{1}], q_ddot[{1}], R{5}, p{5}, V{5}, "
                      "A{5})\n"),
              in, c, vector3(joint.axis), vector3(joint.anchor), amount, i);
        } else if (hinge) {
          out += fmt::format(
              "{0}static constexpr double axis{1}[3] = {{{2}}}, anchor{1}[3] = {{{3}}};\n"
              "{0}detail::hinge(axis{1}, anchor{1}, {4}, q_dot[{1}], q_ddot[{1}], R{5}, p{5}, "
              "V{5}, A{5}, S + {6});\n",
              in, c, vector3(joint.axis), vector3(joint.anchor), amount, i, 6 * c);
        } else {
          out += fmt::format(
              "{0}static constexpr double axis{1}[3] = {{{2}}};\n"
              "{0}detail::slide(axis{1}, {3}, q_dot[{1}], q_ddot[{1}], R{4}, p{4}, V{4}, A{4}, "
              "S + {5});\n",
              in, c, vector3(joint.axis), amount, i, 6 * c);
        }
        ++c;
        ++e;
      }
    }
    return out;
  }

  // A ball or free joint of link i, its quaternion (free: position) at q[e], velocities from c.
  std::string rotation_joint(const io::RobotJoint& joint, std::size_t i, std::size_t e,
                             std::size_t c) const {
    const char* in = python ? "    " : "  ";
    const bool free = joint.type == io::RobotJointType::kFree;
    const auto n = static_cast<std::size_t>(io::velocity_count(joint.type));
    std::string out = fmt::format(
        "{}{} joint '{}' ({}, q[{}..{}], velocities {}..{}{})\n", in, python ? "#" : "//",
        comment_text(joint.name), free ? "free" : "ball", e, e + (free ? 6 : 3), c, c + n - 1,
        free ? "" : ", quaternion parent side <- link");
    if (python) {
      if (free) {
        out += fmt::format(
            "{0}S[{1}:{2}] = _free_joint(q[{3}:{4}], q[{4}:{5}], q_dot[{1}:{2}], q_ddot[{1}:{2}], "
            "R{6}, p{6}, V{6}, A{6})\n",
            in, c, c + n, e, e + 3, e + 7, i);
      } else {
        out += fmt::format(
            "{0}S[{1}:{2}] = _ball_joint(({3}), q[{4}:{5}], q_dot[{1}:{2}], q_ddot[{1}:{2}], "
            "R{6}, p{6}, V{6}, A{6})\n",
            in, c, c + n, vector3(joint.anchor), e, e + 4, i);
      }
    } else if (free) {
      out += fmt::format(
          "{0}detail::free_joint(q + {1}, q + {2}, q_dot + {3}, q_ddot + {3}, R{4}, p{4}, V{4}, "
          "A{4}, S + {5});\n",
          in, e, e + 3, c, i, 6 * c);
    } else {
      out += fmt::format(
          "{0}static constexpr double anchor{1}[3] = {{{2}}};\n"
          "{0}detail::ball_joint(anchor{1}, q + {3}, q_dot + {1}, q_ddot + {1}, R{4}, p{4}, V{4}, "
          "A{4}, S + {5});\n",
          in, c, vector3(joint.anchor), e, i, 6 * c);
    }
    return out;
  }

  // Ψ of each link with an inertial onto every joint from it to the root; then the joint terms
  std::string projections() const {
    const char* in = python ? "    " : "  ";
    std::string out;
    for (std::size_t b = 0; b < model.links.size(); ++b) {
      const std::size_t column = layout.link_column[b];
      if (column == std::string::npos) continue;
      out += fmt::format("{}{} link '{}': columns {} to {}\n", in, python ? "#" : "//",
                         comment_text(model.links[b].name), column, column + kLinkParameters - 1);
      out += fmt::format(fmt::runtime(python ? "{0}psi = _link_wrench(R{1}, p{1}, V{1}, A{1})\n"
                                             : "{0}detail::link_wrench(R{1}, p{1}, V{1}, A{1}, psi);\n"),
                         in, b);
      for (int a = static_cast<int>(b); a >= 0; a = model.links[static_cast<std::size_t>(a)].parent) {
        const auto ua = static_cast<std::size_t>(a);
        const std::size_t last = ua + 1 < model.links.size() ? layout.first_dof[ua + 1] : layout.dof;
        for (std::size_t j = 0; layout.first_dof[ua] + j < last; ++j) {
          const std::size_t row = layout.first_dof[ua] + j;
          out += fmt::format(fmt::runtime(python ? "{0}_project(S[{1}], psi, Y[{1}], {2})\n"
                                                 : "{0}detail::project(S + {3}, psi, Y + {4});\n"),
                             in, row, column, 6 * row, row * layout.parameters + column);
        }
      }
    }
    out += fmt::format("{}{} the joints: armature q_ddot, damping q_dot, stiffness q - springref\n",
                       in, python ? "#" : "//");
    for (std::size_t i = 0; i < model.links.size(); ++i) {
      std::size_t c = layout.first_dof[i];
      std::size_t e = layout.first_q[i];
      std::size_t column = layout.joint_column[i];
      for (const io::RobotJoint& joint : model.links[i].joints) {
        if (joint.type == io::RobotJointType::kBall || joint.type == io::RobotJointType::kFree) {
          out += rotation_joint_terms(joint, model.links[i], e, c, column);
          e += static_cast<std::size_t>(io::position_count(joint.type));
          c += static_cast<std::size_t>(io::velocity_count(joint.type));
          column += kJointParameters;
          continue;
        }
        const std::string spring = offset(fmt::format("q[{}]", e), joint.springref);
        if (python) {
          out += fmt::format("{0}Y[{1}][{2}:{3}] = [q_ddot[{1}], q_dot[{1}], {4}]\n", in, c,
                             column, column + kJointParameters, spring);
        } else {
          const std::size_t k = c * layout.parameters + column;
          out += fmt::format("{0}Y[{1}] = q_ddot[{2}];\n{0}Y[{3}] = q_dot[{2}];\n{0}Y[{4}] = {5};\n",
                             in, k, c, k + 1, k + 2, spring);
        }
        ++c;
        ++e;
        column += kJointParameters;
      }
    }
    return out;
  }

  // A ball's or free joint's armature, damping and stiffness columns over its velocity rows: the
  // stiffness's a ball's rotation vector r, a free joint's p - p0 and r of q0^-1 q
  std::string rotation_joint_terms(const io::RobotJoint& joint, const io::RobotLink& link,
                                   std::size_t e, std::size_t c, std::size_t column) const {
    const char* in = python ? "    " : "  ";
    const bool free = joint.type == io::RobotJointType::kFree;
    const auto n = static_cast<std::size_t>(io::velocity_count(joint.type));
    const std::size_t turn = free ? e + 3 : e;  // the quaternion
    const std::size_t rows = free ? c + 3 : c;  // the rotation rows
    // a free joint's reference placement p0, q0 (its link's), as literals
    const Eigen::Quaterniond r0 = detail::reference_orientation(link);
    const std::string p0 = vector3(link.position);
    const std::string q0 = literals(Eigen::Vector4d(r0.w(), r0.x(), r0.y(), r0.z()).data(), 4);
    std::string out;
    if (python) {
      out += fmt::format("{0}for k in range({1}, {2}):\n{0}    Y[k][{3}:{4}] = [q_ddot[k], q_dot[k]]\n",
                         in, c, c + n, column, column + 2);
      if (free) {
        out += fmt::format("{0}for k in range(3):\n{0}    Y[{1} + k][{2}] = q[{3} + k] - ({4})[k]\n",
                           in, c, column + 2, e, p0);
        out += fmt::format("{0}r = _relative_rotation_vector(({1}), q[{2}:{3}])\n", in, q0, turn,
                           turn + 4);
      } else {
        out += fmt::format("{0}r = _rotation_vector(q[{1}:{2}])\n", in, turn, turn + 4);
      }
      out += fmt::format("{0}for k in range(3):\n{0}    Y[{1} + k][{2}] = r[k]\n", in, rows,
                         column + 2);
      return out;
    }
    const std::size_t np = layout.parameters;
    out += fmt::format("{0}for (int k = {1}; k < {2}; ++k) {{\n{0}  Y[k * {3} + {4}] = q_ddot[k];\n"
                       "{0}  Y[k * {3} + {5}] = q_dot[k];\n{0}}}\n",
                       in, c, c + n, np, column, column + 1);
    out += fmt::format("{0}{{\n", in);
    if (free) {
      out += fmt::format("{0}  static constexpr double p0[3] = {{{1}}}, q0[4] = {{{2}}};\n", in, p0, q0);
      out += fmt::format("{0}  for (int k = 0; k < 3; ++k) Y[({1} + k) * {2} + {3}] = q[{4} + k] - p0[k];\n",
                         in, c, np, column + 2, e);
      out += fmt::format("{0}  double r[3];\n{0}  detail::relative_rotation_vector(q0, q + {1}, r);\n",
                         in, turn);
    } else {
      out += fmt::format("{0}  double r[3];\n{0}  detail::rotation_vector(q + {1}, r);\n", in, turn);
    }
    out += fmt::format("{0}  for (int k = 0; k < 3; ++k) Y[({1} + k) * {2} + {3}] = r[k];\n{0}}}\n",
                       in, rows, np, column + 2);
    return out;
  }
};

// β_i = Σ_j C_ij π_j as one expression of pi[j]
std::string combination(const BaseParameters& base, std::size_t i) {
  const auto row = static_cast<Eigen::Index>(i);
  std::string out = fmt::format("pi[{}]", base.independent[i]);
  for (Eigen::Index j = 0; j < base.combination.cols(); ++j) {
    const double c = base.combination(row, j);
    if (c == 0 || static_cast<std::size_t>(j) == base.independent[i]) continue;
    out += fmt::format(" {} {}pi[{}]", c < 0 ? '-' : '+',
                       std::abs(c) == 1 ? std::string() : literal(std::abs(c)) + " * ", j);
  }
  return out;
}

template <typename F>
std::string joined(std::size_t n, F&& item) {
  std::vector<std::string> out;
  for (std::size_t k = 0; k < n; ++k) out.push_back(item(k));
  return fmt::format("{}", fmt::join(out, ", "));
}

// The checks that the exported file describes this model (a BaseParameters of another model
// would export a file whose Y and beta disagree).
void check_base(const Layout& layout, const BaseParameters& base) {
  RIGID_REQUIRE_AS("regressor export",
                   base.standard.values.size() == static_cast<Eigen::Index>(layout.parameters) &&
                       base.combination.cols() == static_cast<Eigen::Index>(layout.parameters),
                   "the base parameters have {} standard parameters; the model has {} (they "
                   "belong to another model)",
                   base.standard.values.size(), layout.parameters);
}

}  // namespace

std::string emit_regressor_cpp(const io::RobotModel& model, const BaseParameters& base,
                               const RegressorExportOptions& options) {
  const Layout layout = layout_of(model);
  check_base(layout, base);
  const StandardParameters& s = base.standard;
  const std::string& ns = options.name;
  const bool identifier =
      !ns.empty() && std::isdigit(static_cast<unsigned char>(ns[0])) == 0 &&
      std::all_of(ns.begin(), ns.end(), [](char c) {
        return std::isalnum(static_cast<unsigned char>(c)) != 0 || c == '_';
      });
  RIGID_REQUIRE_AS("regressor export", identifier,
                   "the namespace '{}' is not a C++ identifier (letters, digits and '_', not "
                   "starting with a digit)",
                   ns);
  std::string out = header_comment(model, layout, base, options, "//");
  out += "//\n// Arrays are row-major: Y[i*np + j], Y_b[i*nb + k].\n";
  out += "#pragma once\n\n#include <cmath>\n\n";
  out += fmt::format("namespace {} {{\n\n", ns);
  out += fmt::format("inline constexpr int nq = {}, nv = {};\n", layout.nq, layout.dof);
  out += fmt::format("inline constexpr int np = {};  // standard parameters pi\n", layout.parameters);
  out += fmt::format("inline constexpr int nb = {};  // base parameters beta\n", base.rank);
  const std::vector<std::string> coordinates = model.coordinate_names();
  out += fmt::format("inline constexpr const char* coordinate_names[nq] = {{{}}};\n",
                     joined(coordinates.size(), [&](std::size_t k) { return quoted(coordinates[k]); }));
  if (layout.rotations) {
    const std::vector<std::string> velocities = model.velocity_names();
    out += fmt::format("inline constexpr const char* velocity_names[nv] = {{{}}};\n",
                       joined(velocities.size(), [&](std::size_t k) { return quoted(velocities[k]); }));
  }
  out += fmt::format("inline constexpr const char* parameter_names[np] = {{{}}};\n",
                     joined(s.names.size(), [&](std::size_t k) { return quoted(s.names[k]); }));
  out += fmt::format("inline constexpr const char* parameter_units[np] = {{{}}};\n",
                     joined(s.units.size(), [&](std::size_t k) { return quoted(s.units[k]); }));
  out += "/// pi of the model\n";
  out += fmt::format("inline constexpr double standard_parameters[np] = {{{}}};\n",
                     literals(s.values.data(), layout.parameters));
  out += "/// the columns of Y that make Y_b, in the order of beta\n";
  out += fmt::format("inline constexpr int base_columns[nb] = {{{}}};\n",
                     joined(base.rank, [&](std::size_t k) { return fmt::format("{}", base.independent[k]); }));
  out += fmt::format("inline constexpr const char* base_parameter_names[nb] = {{{}}};\n",
                     joined(base.rank, [&](std::size_t k) { return quoted(base.name(k)); }));
  out += "/// beta = C pi of the model\n";
  out += fmt::format("inline constexpr double base_parameter_values[nb] = {{{}}};\n\n",
                     literals(base.values.data(), base.rank));
  out += kCppHelpers;
  if (layout.rotations) out += std::string("\n") + kCppRotationHelpers;
  const Printer printer{model, layout, false};
  out += layout.rotations
             ? "\n/// Y (nv x np): tau = Y pi. q (nq) in rad, m and a ball's or free joint's quaternion\n"
               "/// (w, x, y, z), q_dot and q_ddot (nv) the velocities (a ball's angular velocity in its\n"
               "/// link's frame, MuJoCo's qvel) and their rates.\n"
             : "\n/// Y (nv x np): tau = Y pi. q in rad or m, q_dot and q_ddot their rates.\n";
  out += "inline void regressor(const double* q, const double* q_dot, const double* q_ddot, "
         "double* Y) {\n";
  out += fmt::format("  static constexpr double g[3] = {{{}}};\n", vector3(model.gravity));
  out += "  double S[6 * nv];  // the joints' axes in the world (angular; linear at the origin)\n";
  out += printer.forward_pass();
  out += "  for (int k = 0; k < nv * np; ++k) Y[k] = 0;\n";
  if (std::any_of(layout.link_column.begin(), layout.link_column.end(),
                  [](std::size_t c) { return c != std::string::npos; })) {
    out += "  double psi[60];\n";
  }
  out += printer.projections();
  out += "}\n\n";
  out += "/// Y_b (nv x nb): tau = Y_b beta, the columns base_columns of Y.\n";
  out += "inline void base_regressor(const double* q, const double* q_dot, const double* q_ddot, "
         "double* Y_b) {\n"
         "  double Y[nv * np];  // on the stack: nv * np doubles\n"
         "  regressor(q, q_dot, q_ddot, Y);\n"
         "  for (int i = 0; i < nv; ++i) {\n"
         "    for (int k = 0; k < nb; ++k) Y_b[i * nb + k] = Y[i * np + base_columns[k]];\n"
         "  }\n"
         "}\n\n";
  out += "/// beta = C pi: the base parameters of the standard parameters pi (np values).\n";
  out += "inline void base_parameters(const double* pi, double* beta) {\n";
  for (std::size_t i = 0; i < base.rank; ++i) {
    out += fmt::format("  beta[{}] = {};\n", i, combination(base, i));
  }
  out += "}\n";
  out += fmt::format("\n}}  // namespace {}\n", ns);
  return out;
}

// The Python helpers of ball and free joints, written only into the modules of models that have
// them (the same operations as kCppRotationHelpers).
constexpr const char* kPythonRotationHelpers = R"(

def _coordinates(values):
    values = [float(v) for v in values]
    if len(values) != _NQ:
        raise ValueError(f"q needs {_NQ} values (one per coordinate, four per quaternion), "
                         f"got {len(values)}")
    return values


def _quaternion_rotation(q):
    """The rotation of a quaternion (w, x, y, z), row-major: q/|q|'s for any q != 0."""
    w, x, y, z = q
    s = 2 / (w * w + x * x + y * y + z * z)
    return [1 - s * (y * y + z * z), s * (x * y - w * z), s * (x * z + w * y),
            s * (x * y + w * z), 1 - s * (x * x + z * z), s * (y * z - w * x),
            s * (x * z - w * y), s * (y * z + w * x), 1 - s * (x * x + y * y)]


def _link_axes(x, rate, accel, R, V, A):
    """The link's three axes through x (world), fixed in the link: all three are carried by the
    velocity it had before them; V and A move; returns the three s."""
    V0 = list(V)
    S = []
    for j in range(3):
        u = [R[j], R[3 + j], R[6 + j]]
        s = u + _cross(x, u)
        vxs = _cross(V0[:3], s[:3]) + _cross(V0[:3], s[3:])
        t = _cross(V0[3:], s[:3])
        for k in range(3):
            vxs[3 + k] += t[k]
        for k in range(6):
            A[k] += vxs[k] * rate[j] + s[k] * accel[j]
            V[k] += s[k] * rate[j]
        S.append(s)
    return S


def _ball_joint(anchor, q, rate, accel, R, p, V, A):
    """A ball about anchor (link frame) turned by the quaternion q (parent side <- link); R, p,
    V, A move; returns its three s."""
    t = _mul3(R, anchor)
    x = [p[k] + t[k] for k in range(3)]
    R[:] = _mul33(R, _quaternion_rotation(q))
    t = _mul3(R, anchor)
    p[:] = [x[k] - t[k] for k in range(3)]
    return _link_axes(x, rate, accel, R, V, A)


def _free_joint(position, q, rate, accel, R, p, V, A):
    """A free joint: the link's origin at position (world), turned by q (world <- link); three
    world-fixed translations, then the link's axes; returns its six s."""
    S = []
    for j in range(3):
        s = [0.0] * 6
        s[3 + j] = 1.0
        A[3 + j] += accel[j]
        V[3 + j] += rate[j]
        S.append(s)
    R[:] = _quaternion_rotation(q)
    p[:] = list(position)
    return S + _link_axes(p, rate[3:], accel[3:], R, V, A)


def _rotation_vector(q):
    """The rotation vector of a quaternion (angle in [-pi, pi] about its axis; MuJoCo's
    mju_quat2Vel): the column of a ball joint's stiffness."""
    s = math.sqrt(q[1] * q[1] + q[2] * q[2] + q[3] * q[3])
    if not s > 0:
        return [0.0, 0.0, 0.0]
    angle = 2 * math.atan2(s, q[0])
    if angle > math.pi:
        angle -= 2 * math.pi
    return [angle / s * q[1 + k] for k in range(3)]


def _relative_rotation_vector(q0, q):
    """The rotation vector of q0^-1 q: a free joint's turn from its reference orientation."""
    return _rotation_vector([
        q0[0] * q[0] + q0[1] * q[1] + q0[2] * q[2] + q0[3] * q[3],
        q0[0] * q[1] - q0[1] * q[0] - q0[2] * q[3] + q0[3] * q[2],
        q0[0] * q[2] + q0[1] * q[3] - q0[2] * q[0] - q0[3] * q[1],
        q0[0] * q[3] - q0[1] * q[2] + q0[2] * q[1] - q0[3] * q[0]])
)";

std::string emit_regressor_python(const io::RobotModel& model, const BaseParameters& base,
                                  const RegressorExportOptions& options) {
  const Layout layout = layout_of(model);
  check_base(layout, base);
  const StandardParameters& s = base.standard;
  std::string out = header_comment(model, layout, base, options, "#");
  out += "#\n# Matrices are lists of rows.\n\n";
  const std::vector<std::string> coordinates = model.coordinate_names();
  out += fmt::format("COORDINATES = ({}{})\n",
                     joined(coordinates.size(), [&](std::size_t k) { return quoted(coordinates[k]); }),
                     coordinates.size() == 1 ? "," : "");
  out += "# pi of the model, name -> value\n";
  out += fmt::format("PARAMETERS = {{{}}}\n", joined(s.names.size(), [&](std::size_t k) {
                       return fmt::format("{}: {}", quoted(s.names[k]), literal(s.values(static_cast<Eigen::Index>(k))));
                     }));
  out += fmt::format("PARAMETER_UNITS = {{{}}}\n", joined(s.names.size(), [&](std::size_t k) {
                       return fmt::format("{}: {}", quoted(s.names[k]), quoted(s.units[k]));
                     }));
  out += "# the columns of Y that make Y_b, in the order of beta\n";
  out += fmt::format("BASE_COLUMNS = ({}{})\n",
                     joined(base.rank, [&](std::size_t k) { return fmt::format("{}", base.independent[k]); }),
                     base.rank == 1 ? "," : "");
  out += "# beta = C pi of the model, name -> value\n";
  out += fmt::format("BASE_PARAMETERS = {{{}}}\n", joined(base.rank, [&](std::size_t k) {
                       return fmt::format("{}: {}", quoted(base.name(k)), literal(base.values(static_cast<Eigen::Index>(k))));
                     }));
  out += fmt::format("_G = ({})\n", vector3(model.gravity));
  out += fmt::format("_NV = {}\n_NP = {}\n", layout.dof, layout.parameters);
  if (layout.rotations) {
    const std::vector<std::string> velocities = model.velocity_names();
    out = out.insert(out.find("# pi of the model"),
                     fmt::format("VELOCITIES = ({})\n", joined(velocities.size(), [&](std::size_t k) {
                                   return quoted(velocities[k]);
                                 })));
    out += fmt::format("_NQ = {}\n", layout.nq);
  }
  out += R"(

def _vector(values, name):
    values = [float(v) for v in values]
    if len(values) != _NV:
        raise ValueError(f"{name} needs {_NV} values (one per coordinate), got {len(values)}")
    return values


def _mul33(A, B):
    return [A[3 * i] * B[j] + A[3 * i + 1] * B[3 + j] + A[3 * i + 2] * B[6 + j]
            for i in range(3) for j in range(3)]


def _mul3(A, x):
    return [A[3 * i] * x[0] + A[3 * i + 1] * x[1] + A[3 * i + 2] * x[2] for i in range(3)]


def _mul3t(A, x):
    return [A[i] * x[0] + A[3 + i] * x[1] + A[6 + i] * x[2] for i in range(3)]


def _cross(a, b):
    return [a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]]


def _place_root(Rc, pc, g):
    """A root link at its placement: at rest, its acceleration less gravity is -g."""
    return list(Rc), list(pc), [0.0] * 6, [0.0, 0.0, 0.0, -g[0], -g[1], -g[2]]


def _place(Rp, pp, Vp, Ap, Rc, pc):
    """A link at its placement (Rc, pc) on its parent, moving with it."""
    t = _mul3(Rp, pc)
    return _mul33(Rp, Rc), [pp[k] + t[k] for k in range(3)], list(Vp), list(Ap)


def _carry(s, rate, accel, V, A):
    """A joint's axis s moves the link: A += (V x s) rate + s accel, V += s rate."""
    vxs = _cross(V[:3], s[:3]) + _cross(V[:3], s[3:])
    t = _cross(V[3:], s[:3])
    for k in range(3):
        vxs[3 + k] += t[k]
    for k in range(6):
        A[k] += vxs[k] * rate + s[k] * accel
        V[k] += s[k] * rate


def _hinge(axis, anchor, angle, rate, accel, R, p, V, A):
    """A hinge about the unit axis through anchor (link frame); R, p, V, A move; returns s."""
    u = _mul3(R, axis)
    t = _mul3(R, anchor)
    x = [p[k] + t[k] for k in range(3)]
    s = u + _cross(x, u)
    c, sn = math.cos(angle), math.sin(angle)
    v = 1 - c
    a0, a1, a2 = axis
    Q = [c + v * a0 * a0, v * a0 * a1 - sn * a2, v * a0 * a2 + sn * a1,
         v * a0 * a1 + sn * a2, c + v * a1 * a1, v * a1 * a2 - sn * a0,
         v * a0 * a2 - sn * a1, v * a1 * a2 + sn * a0, c + v * a2 * a2]
    R[:] = _mul33(R, Q)
    t = _mul3(R, anchor)
    p[:] = [x[k] - t[k] for k in range(3)]
    _carry(s, rate, accel, V, A)
    return s


def _slide(axis, amount, rate, accel, R, p, V, A):
    """A slide along the unit axis (link frame); R, p, V, A move; returns s."""
    s = [0.0, 0.0, 0.0] + _mul3(R, axis)
    p[:] = [p[k] + s[3 + k] * amount for k in range(3)]
    _carry(s, rate, accel, V, A)
    return s


def _link_wrench(R, p, V, A):
    """Psi (6 rows of 10): the wrench (moment about the world origin; force) of a link per unit
    of each of its parameters (Atkeson, An & Hollerbach 1986)."""
    t = _cross(V[:3], p)
    vp = [V[3 + k] + t[k] for k in range(3)]
    t = _cross(A[:3], p)
    ap = [A[3 + k] + t[k] for k in range(3)]
    t = _cross(V[:3], vp)
    ap = [ap[k] + t[k] for k in range(3)]
    w, al, a = _mul3t(R, V[:3]), _mul3t(R, A[:3]), _mul3t(R, ap)
    W = [0.0, -w[2], w[1], w[2], 0.0, -w[0], -w[1], w[0], 0.0]
    Lw = [w[0], w[1], w[2], 0, 0, 0, 0, w[0], 0, w[1], w[2], 0, 0, 0, w[0], 0, w[1], w[2]]
    La = [al[0], al[1], al[2], 0, 0, 0, 0, al[0], 0, al[1], al[2], 0, 0, 0, al[0], 0, al[1], al[2]]
    Hal = [0.0, -al[2], al[1], al[2], 0.0, -al[0], -al[1], al[0], 0.0]
    L = [[0.0] * 10 for _ in range(6)]
    L[0][2], L[0][3], L[1][1], L[1][3], L[2][1], L[2][2] = a[2], -a[1], -a[2], a[0], a[1], -a[0]
    for i in range(3):
        for j in range(6):
            L[i][4 + j] = (La[6 * i + j] + W[3 * i] * Lw[j] + W[3 * i + 1] * Lw[6 + j]
                           + W[3 * i + 2] * Lw[12 + j])
        L[3 + i][0] = a[i]
        for j in range(3):
            L[3 + i][1 + j] = (Hal[3 * i + j] + W[3 * i] * W[j] + W[3 * i + 1] * W[3 + j]
                               + W[3 * i + 2] * W[6 + j])
    psi = [[0.0] * 10 for _ in range(6)]
    for j in range(10):
        f = _mul3(R, [L[3][j], L[4][j], L[5][j]])
        n = _mul3(R, [L[0][j], L[1][j], L[2][j]])
        t = _cross(p, f)
        for k in range(3):
            psi[k][j] = n[k] + t[k]
            psi[3 + k][j] = f[k]
    return psi


def _project(s, psi, row, column):
    """A joint's share of a link's wrench, per parameter, into row[column:column + 10]."""
    for j in range(10):
        row[column + j] = sum(s[r] * psi[r][j] for r in range(6))
)";
  if (layout.rotations) out += kPythonRotationHelpers;
  out += layout.rotations
             ? R"(

def regressor(q, q_dot, q_ddot):
    """Y (nv lists of np floats): tau = Y pi. q (nq) in rad, m and a ball's or free joint's
    quaternion (w, x, y, z), q_dot and q_ddot (nv) the velocities (a ball's angular velocity in
    its link's frame, MuJoCo's qvel) and their rates."""
    q, q_dot, q_ddot = _coordinates(q), _vector(q_dot, "q_dot"), _vector(q_ddot, "q_ddot")
    S = [None] * _NV
)"
             : R"(

def regressor(q, q_dot, q_ddot):
    """Y (nv lists of np floats): tau = Y pi. q in rad or m, q_dot and q_ddot their rates."""
    q, q_dot, q_ddot = _vector(q, "q"), _vector(q_dot, "q_dot"), _vector(q_ddot, "q_ddot")
    S = [None] * _NV
)";
  const Printer printer{model, layout, true};
  out += printer.forward_pass();
  out += "    Y = [[0.0] * _NP for _ in range(_NV)]\n";
  out += printer.projections();
  out += "    return Y\n";
  out += R"(

def base_regressor(q, q_dot, q_ddot):
    """Y_b (nv lists of nb floats): tau = Y_b beta, the columns BASE_COLUMNS of Y."""
    return [[row[c] for c in BASE_COLUMNS] for row in regressor(q, q_dot, q_ddot)]


def base_parameters(pi=None):
    """beta = C pi for the standard parameters pi (np values; None: the model's)."""
    pi = list(PARAMETERS.values()) if pi is None else [float(v) for v in pi]
    if len(pi) != _NP:
        raise ValueError(f"pi needs {_NP} values (one per standard parameter), got {len(pi)}")
    return [
)";
  for (std::size_t i = 0; i < base.rank; ++i) out += fmt::format("        {},\n", combination(base, i));
  out += "    ]\n";
  // the module's only import, at the top where a reader looks for it
  const std::size_t first_code = out.find("\nCOORDINATES");
  out.insert(first_code + 1, "import math\n\n");
  return out;
}

}  // namespace rigid::robot
