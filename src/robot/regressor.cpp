#include "rigid/robot/regressor.hpp"

#include <algorithm>
#include <cmath>
#include <iterator>
#include <numbers>
#include <optional>
#include <random>

#include <Eigen/Geometry>
#include <Eigen/QR>
#include <fmt/format.h>

#include "rigid/common/error.hpp"
#include "joint_motion.hpp"

namespace rigid::robot {

namespace {

using Vector6d = Eigen::Matrix<double, 6, 1>;
using Matrix6x10d = Eigen::Matrix<double, 6, 10>;

constexpr Eigen::Index kLinkParameters = 10;
constexpr Eigen::Index kJointParameters = 3;  // Ia, fv, k

Eigen::Matrix3d hat(const Eigen::Vector3d& v) {
  Eigen::Matrix3d m;
  m << 0, -v.z(), v.y(), v.z(), 0, -v.x(), -v.y(), v.x(), 0;
  return m;
}

bool has_inertial(const io::RobotLink& link) {
  return link.mass > 0 || !link.inertia_com.isZero(0);
}

// Layout of π: the first column of each link's 10 (−1: none) and of each link's joint terms;
// the first entry of q and of the velocities of each link's joints.
struct Layout {
  std::vector<Eigen::Index> link_column;
  std::vector<Eigen::Index> joint_column;  // per link: its first joint's Ia column
  std::vector<Eigen::Index> first_q;       // per link: its first joint's entry of q
  std::vector<Eigen::Index> first_dof;     // per link: its first joint's velocity
  Eigen::Index parameters = 0;
  Eigen::Index nq = 0;
  Eigen::Index dof = 0;  // nv
};

Layout layout_of(const io::RobotModel& model) {
  Layout l;
  for (const io::RobotLink& link : model.links) {
    l.link_column.push_back(has_inertial(link) ? l.parameters : -1);
    if (has_inertial(link)) l.parameters += kLinkParameters;
    l.joint_column.push_back(l.parameters);
    l.parameters += kJointParameters * static_cast<Eigen::Index>(link.joints.size());
    l.first_q.push_back(l.nq);
    l.first_dof.push_back(l.dof);
    for (const io::RobotJoint& joint : link.joints) {
      l.nq += io::position_count(joint.type);
      l.dof += io::velocity_count(joint.type);
    }
  }
  return l;
}

void check_vector(const char* what, const Eigen::VectorXd& v, Eigen::Index n, const char* entries) {
  RIGID_REQUIRE_AS("regressor", v.size() == n, "{} has {} entries; the model has {} {}", what,
                   v.size(), n, entries);
  RIGID_REQUIRE_AS("regressor", v.allFinite(), "{} is not finite", what);
}

// Ψ: the wrench (n; f) of a link about its origin, in its frame, per unit of each of its 10
// parameters (m, mc, J), from its angular velocity w, angular acceleration al and the
// acceleration a of its origin less gravity, all in the link frame [Atkeson, An & Hollerbach 1986]:
//   f = m a + al × mc + w × (w × mc),   n = J al + w × (J w) + mc × a,
// with J w = L(w) (J_xx, J_xy, J_xz, J_yy, J_yz, J_zz).
Matrix6x10d link_wrench_basis(const Eigen::Vector3d& w, const Eigen::Vector3d& al,
                              const Eigen::Vector3d& a) {
  const auto L = [](const Eigen::Vector3d& v) {
    Eigen::Matrix<double, 3, 6> m;
    m << v.x(), v.y(), v.z(), 0, 0, 0,  //
        0, v.x(), 0, v.y(), v.z(), 0,   //
        0, 0, v.x(), 0, v.y(), v.z();
    return m;
  };
  const Eigen::Matrix3d W = hat(w);
  Matrix6x10d psi = Matrix6x10d::Zero();
  // moment: (m c) × a = −â (m c); J al + ŵ L(w) J
  psi.block<3, 3>(0, 1) = -hat(a);
  psi.block<3, 6>(0, 4) = L(al) + W * L(w);
  // force: m a; (âl + ŵ ŵ) (m c)
  psi.block<3, 1>(3, 0) = a;
  psi.block<3, 3>(3, 1) = hat(al) + W * W;
  return psi;
}

}  // namespace

StandardParameters standard_parameters(const io::RobotModel& model) {
  const Layout layout = layout_of(model);
  StandardParameters s;
  s.values.resize(layout.parameters);
  Eigen::Index k = 0;
  const auto add = [&](std::string name, const char* unit, double value) {
    s.names.push_back(std::move(name));
    s.units.emplace_back(unit);
    s.values(k++) = value;
  };
  for (const io::RobotLink& link : model.links) {
    if (has_inertial(link)) {
      const double m = link.mass;
      const Eigen::Vector3d& c = link.com;
      // the inertia about the link origin: parallel axes, J = I_C + m (|c|² 1 − c cᵀ)
      const Eigen::Matrix3d J =
          link.inertia_com +
          m * (c.squaredNorm() * Eigen::Matrix3d::Identity() - c * c.transpose());
      const std::string& n = link.name;
      add("m_" + n, "kg", m);
      add("mx_" + n, "kg·m", m * c.x());
      add("my_" + n, "kg·m", m * c.y());
      add("mz_" + n, "kg·m", m * c.z());
      add("Ixx_" + n, "kg·m²", J(0, 0));
      add("Ixy_" + n, "kg·m²", J(0, 1));
      add("Ixz_" + n, "kg·m²", J(0, 2));
      add("Iyy_" + n, "kg·m²", J(1, 1));
      add("Iyz_" + n, "kg·m²", J(1, 2));
      add("Izz_" + n, "kg·m²", J(2, 2));
    }
    for (const io::RobotJoint& joint : link.joints) {
      // a free joint's one number acts on its translations and its rotations alike (MuJoCo's):
      // its unit is the translations' and the rotations', "kg|kg·m²"
      const bool slide = joint.type == io::RobotJointType::kSlide;
      const bool free = joint.type == io::RobotJointType::kFree;
      add("Ia_" + joint.name, slide ? "kg" : free ? "kg|kg·m²" : "kg·m²",
          joint.armature);
      add("fv_" + joint.name,
          slide ? "N·s/m" : free ? "N·s/m|N·m·s/rad" : "N·m·s/rad",
          joint.damping);
      add("k_" + joint.name, slide ? "N/m" : free ? "N/m|N·m/rad" : "N·m/rad",
          joint.stiffness);
    }
  }
  return s;
}

Eigen::MatrixXd regressor(const io::RobotModel& model, const Eigen::VectorXd& q,
                          const Eigen::VectorXd& q_dot, const Eigen::VectorXd& q_ddot) {
  const Layout layout = layout_of(model);
  check_vector("q", q, layout.nq, "coordinates (nq)");
  check_vector("q_dot", q_dot, layout.dof, "velocities (nv)");
  check_vector("q_ddot", q_ddot, layout.dof, "velocities (nv)");
  const std::size_t links = model.links.size();

  // forward pass: poses, joint axes S and spatial velocity V and acceleration A (ω; v) of
  // each link, in the world frame at the world origin [Featherstone2008, §5.3]; gravity as an
  // upward acceleration of the world, so A is the acceleration less gravity
  std::vector<Eigen::Vector3d> p(links);
  std::vector<Eigen::Matrix3d> R(links);
  std::vector<Vector6d> V(links), A(links);
  Eigen::Matrix<double, 6, Eigen::Dynamic> S(6, layout.dof);
  Vector6d A_world = Vector6d::Zero();
  A_world.tail<3>() = -model.gravity;
  // the rate of s carried by a frame moving with v: v ×m s
  const auto carried = [](const Vector6d& v, const Vector6d& s) {
    Vector6d vxs;
    vxs << v.head<3>().cross(s.head<3>()),
        v.head<3>().cross(s.tail<3>()) + v.tail<3>().cross(s.head<3>());
    return vxs;
  };
  for (std::size_t i = 0; i < links; ++i) {
    const io::RobotLink& link = model.links[i];
    const bool rooted = link.parent < 0;
    const auto parent = static_cast<std::size_t>(std::max(link.parent, 0));
    Eigen::Matrix3d R_WL = rooted ? link.rotation : Eigen::Matrix3d(R[parent] * link.rotation);
    Eigen::Vector3d p_WL =
        rooted ? link.position : Eigen::Vector3d(p[parent] + R[parent] * link.position);
    Vector6d v = rooted ? Vector6d::Zero() : V[parent];
    Vector6d a = rooted ? A_world : A[parent];
    Eigen::Index e = layout.first_q[i];
    Eigen::Index c = layout.first_dof[i];
    // one column s of velocity c, turning in a frame that moves with v_in
    const auto column = [&](const Vector6d& s, const Vector6d& v_in) {
      a += carried(v_in, s) * q_dot(c) + s * q_ddot(c);
      v += s * q_dot(c);
      S.col(c++) = s;
    };
    for (const io::RobotJoint& joint : link.joints) {
      // a ball's columns, fixed in the link, all turn in the frame before them
      // (Σ_k Ṡ_k ω_k = V⁻ × S ω); the others in the frame as each finds it
      std::optional<Vector6d> v_before;  // at the first column fixed in the link
      detail::move_joint(joint, q, e, R_WL, p_WL, "regressor", [&](const Vector6d& s, bool fixed) {
        if (fixed && !v_before) v_before = v;
        column(s, fixed ? *v_before : v);
      });
      e += io::position_count(joint.type);
    }
    R[i] = R_WL;
    p[i] = p_WL;
    V[i] = v;
    A[i] = a;
  }

  Eigen::MatrixXd Y = Eigen::MatrixXd::Zero(layout.dof, layout.parameters);
  for (std::size_t b = 0; b < links; ++b) {
    const Eigen::Index column = layout.link_column[b];
    if (column < 0) continue;
    // the link's motion in its own frame at its origin p: ω, α and the classical acceleration
    // of the origin, a = A_lin + α × p + ω × v_p with v_p = V_lin + ω × p (a spatial
    // acceleration's linear part is the rate of the velocity of the point at the world origin)
    const Eigen::Vector3d w = V[b].head<3>(), al = A[b].head<3>();
    const Eigen::Vector3d v_p = V[b].tail<3>() + w.cross(p[b]);
    const Eigen::Vector3d a_p = A[b].tail<3>() + al.cross(p[b]) + w.cross(v_p);
    const Eigen::Matrix3d Rt = R[b].transpose();
    const Matrix6x10d psi_L = link_wrench_basis(Rt * w, Rt * al, Rt * a_p);
    // the wrench in the world frame about the world origin: n_O = R n + p × R f, f_O = R f
    Matrix6x10d psi;
    psi.bottomRows<3>() = R[b] * psi_L.bottomRows<3>();
    psi.topRows<3>() = R[b] * psi_L.topRows<3>() + hat(p[b]) * psi.bottomRows<3>();
    // every joint from the link to the root carries it: τ_j = S_jᵀ F
    for (int a = static_cast<int>(b); a >= 0; a = model.links[static_cast<std::size_t>(a)].parent) {
      const auto ua = static_cast<std::size_t>(a);
      const Eigen::Index first = layout.first_dof[ua];
      const Eigen::Index last = ua + 1 < links ? layout.first_dof[ua + 1] : layout.dof;
      for (Eigen::Index j = first; j < last; ++j) {
        Y.block<1, kLinkParameters>(j, column) = S.col(j).transpose() * psi;
      }
    }
  }
  // the joint terms: armature q̈, damping q̇ per velocity entry; stiffness (τ = … − p) times
  // q − springref, a ball's rotation vector r of q, a free joint's p − p₀ and r of q₀⁻¹ ⊗ q
  // (MuJoCo's qfrc_passive, as TreeDynamics::passive_forces)
  for (std::size_t i = 0; i < links; ++i) {
    Eigen::Index e = layout.first_q[i];
    Eigen::Index c = layout.first_dof[i];
    Eigen::Index column = layout.joint_column[i];
    for (const io::RobotJoint& joint : model.links[i].joints) {
      const int n = io::velocity_count(joint.type);
      Y.block(c, column, n, 1) = q_ddot.segment(c, n);
      Y.block(c, column + 1, n, 1) = q_dot.segment(c, n);
      Y.block(c, column + 2, n, 1) = detail::spring_displacement(joint, model.links[i], q, e).head(n);
      e += io::position_count(joint.type);
      c += n;
      column += kJointParameters;
    }
  }
  return Y;
}

std::string BaseParameters::name(std::size_t i) const { return fmt::format("beta_{}", i + 1); }

std::string BaseParameters::expression(std::size_t i) const {
  const auto row = static_cast<Eigen::Index>(i);
  fmt::memory_buffer out;
  // the independent parameter first (coefficient 1), then the dependent ones in π's order
  fmt::format_to(std::back_inserter(out), "{}", standard.names[independent[i]]);
  for (Eigen::Index j = 0; j < combination.cols(); ++j) {
    const double c = combination(row, j);
    if (c == 0 || static_cast<std::size_t>(j) == independent[i]) continue;
    const std::string coefficient = fmt::format("{:.12g}", std::abs(c));
    fmt::format_to(std::back_inserter(out), " {} {}{}", c < 0 ? '-' : '+',
                   coefficient == "1" ? "" : coefficient + "*",
                   standard.names[static_cast<std::size_t>(j)]);
  }
  return fmt::to_string(out);
}

Eigen::MatrixXd BaseParameters::reduce(const Eigen::MatrixXd& Y) const {
  RIGID_REQUIRE_AS("BaseParameters::reduce", Y.cols() == standard.values.size(),
                   "Y has {} columns; the model has {} standard parameters", Y.cols(),
                   standard.values.size());
  Eigen::MatrixXd Yb(Y.rows(), static_cast<Eigen::Index>(rank));
  for (std::size_t k = 0; k < rank; ++k) {
    Yb.col(static_cast<Eigen::Index>(k)) = Y.col(static_cast<Eigen::Index>(independent[k]));
  }
  return Yb;
}

BaseParameters base_parameters(const io::RobotModel& model, const BaseParameterOptions& options) {
  RIGID_REQUIRE(options.rank_tolerance > 0 && options.rank_tolerance < 1,
                "rank_tolerance {} is not in (0, 1); it is relative to the largest column norm",
                options.rank_tolerance);
  BaseParameters out;
  out.standard = standard_parameters(model);
  const Layout layout = layout_of(model);
  const Eigen::Index n = layout.dof, np = layout.parameters;
  RIGID_REQUIRE(n > 0, "{}: the model has no joint, so no inverse dynamics to identify",
                model.source);
  const auto samples = static_cast<Eigen::Index>(
      options.samples > 0 ? options.samples : static_cast<std::size_t>((3 * np + n - 1) / n + 8));
  out.samples = static_cast<std::size_t>(samples);
  out.rank_tolerance = options.rank_tolerance;

  // 1. the stack of Y at random states; uniform numbers from the raw 64-bit draws, so the
  // states are the same on every standard library
  std::mt19937_64 rng(options.seed);
  const auto uniform = [&rng] {  // in [−1, 1)
    return static_cast<double>(rng() >> 11) * 0x1.0p-52 - 1.0;
  };
  // a uniformly distributed rotation: a point of the 4-ball (by rejection) made a unit quaternion
  const auto rotation = [&uniform] {
    Eigen::Vector4d x;
    do {
      for (int k = 0; k < 4; ++k) x(k) = uniform();
    } while (!(x.squaredNorm() <= 1 && x.squaredNorm() > 1e-6));
    return Eigen::Vector4d(x.normalized());
  };
  Eigen::MatrixXd W(n * samples, np);
  Eigen::VectorXd q(layout.nq), q_dot(n), q_ddot(n);
  for (Eigen::Index s = 0; s < samples; ++s) {
    Eigen::Index e = 0, c = 0;
    for (const io::RobotLink& link : model.links) {
      for (const io::RobotJoint& joint : link.joints) {
        switch (joint.type) {
          case io::RobotJointType::kHinge:
          case io::RobotJointType::kSlide: {
            const double range = joint.type == io::RobotJointType::kHinge ? std::numbers::pi : 1.0;
            q(e) = joint.ref + range * uniform();
            break;
          }
          case io::RobotJointType::kBall:
            q.segment<4>(e) = rotation();
            break;
          case io::RobotJointType::kFree:
            for (int k = 0; k < 3; ++k) q(e + k) = link.position(k) + uniform();
            q.segment<4>(e + 3) = rotation();
            break;
        }
        e += io::position_count(joint.type);
        for (int k = 0; k < io::velocity_count(joint.type); ++k, ++c) {
          q_dot(c) = uniform();
          q_ddot(c) = uniform();
        }
      }
    }
    W.middleRows(s * n, n) = regressor(model, q, q_dot, q_ddot);
  }

  // 2. Householder QR whose pivot is the next column, in π's order, that is not in the span of
  // those chosen before it (|R_kk| > tol); the reflectors are applied to the later columns only
  const Eigen::VectorXd norms = W.colwise().norm().transpose();
  double scale = 0;  // a loop, not maxCoeff: GCC 12 warns of a null dereference in the latter
  for (Eigen::Index j = 0; j < np; ++j) scale = std::max(scale, norms(j));
  RIGID_REQUIRE(scale > 0, "{}: no parameter moves any joint (Y is zero at every state)",
                model.source);
  const double tol = options.rank_tolerance * scale;
  // the pivot preference, Khalil's per-link order: the inertia J, then m c, then m, then the
  // joint terms; so a point mass is grouped into the inertias and first moments of its own
  // and its parent's link (Izz_1 + m_2 l_1²) rather than the other way round
  std::vector<Eigen::Index> order;
  for (std::size_t i = 0; i < model.links.size(); ++i) {
    const Eigen::Index c = layout.link_column[i];
    if (c >= 0) {
      for (Eigen::Index t : {4, 5, 6, 7, 8, 9, 1, 2, 3, 0}) order.push_back(c + t);
    }
    const auto joints = static_cast<Eigen::Index>(model.links[i].joints.size());
    for (Eigen::Index t = 0; t < kJointParameters * joints; ++t) {
      order.push_back(layout.joint_column[i] + t);
    }
  }
  Eigen::MatrixXd A(W.rows(), np);
  for (Eigen::Index t = 0; t < np; ++t) A.col(t) = W.col(order[static_cast<std::size_t>(t)]);
  const Eigen::Index rows = A.rows();
  Eigen::Index k = 0;
  out.smallest_independent = 1;
  out.largest_dependent = 0;
  for (Eigen::Index t = 0; t < np; ++t) {
    const Eigen::Index j = order[static_cast<std::size_t>(t)];
    const auto index = static_cast<std::size_t>(j);
    if (norms(j) <= tol) {
      out.unidentifiable.push_back(index);
      continue;
    }
    const double r_kk = k < rows ? A.col(t).tail(rows - k).norm() : 0.0;
    if (r_kk <= tol) {
      out.dependent.push_back(index);
      out.largest_dependent = std::max(out.largest_dependent, r_kk / scale);
      continue;
    }
    out.independent.push_back(index);
    out.smallest_independent = std::min(out.smallest_independent, r_kk / scale);
    Eigen::VectorXd essential(rows - k - 1);
    double tau = 0, beta = 0;
    A.col(t).tail(rows - k).makeHouseholder(essential, tau, beta);
    if (t + 1 < np) {
      Eigen::VectorXd workspace(np - t - 1);
      A.bottomRightCorner(rows - k, np - t - 1)
          .applyHouseholderOnTheLeft(essential, tau, workspace.data());
    }
    ++k;
  }
  std::sort(out.independent.begin(), out.independent.end());
  std::sort(out.dependent.begin(), out.dependent.end());
  std::sort(out.unidentifiable.begin(), out.unidentifiable.end());
  out.rank = out.independent.size();
  const auto r = static_cast<Eigen::Index>(out.rank);

  // 3. K = R_II⁻¹ R_ID: the least-squares solution of W_I K = W_D, exact up to round-off
  Eigen::MatrixXd W_I(W.rows(), r), W_D(W.rows(), static_cast<Eigen::Index>(out.dependent.size()));
  for (Eigen::Index i = 0; i < r; ++i)
    W_I.col(i) = W.col(static_cast<Eigen::Index>(out.independent[static_cast<std::size_t>(i)]));
  for (Eigen::Index i = 0; i < W_D.cols(); ++i) {
    W_D.col(i) = W.col(static_cast<Eigen::Index>(out.dependent[static_cast<std::size_t>(i)]));
  }
  out.K = Eigen::HouseholderQR<Eigen::MatrixXd>(W_I).solve(W_D);
  // an entry whose share of its dependent column is below 1e-10 is round-off of a structural
  // zero: drop it
  for (Eigen::Index d = 0; d < out.K.cols(); ++d) {
    const double column =
        norms(static_cast<Eigen::Index>(out.dependent[static_cast<std::size_t>(d)]));
    for (Eigen::Index i = 0; i < r; ++i) {
      const double share =
          std::abs(out.K(i, d)) *
          norms(static_cast<Eigen::Index>(out.independent[static_cast<std::size_t>(i)]));
      if (share < 1e-10 * column) out.K(i, d) = 0;
    }
  }
  out.combination = Eigen::MatrixXd::Zero(r, np);
  for (Eigen::Index i = 0; i < r; ++i) {
    out.combination(i, static_cast<Eigen::Index>(out.independent[static_cast<std::size_t>(i)])) = 1;
    for (Eigen::Index d = 0; d < out.K.cols(); ++d) {
      out.combination(i, static_cast<Eigen::Index>(out.dependent[static_cast<std::size_t>(d)])) =
          out.K(i, d);
    }
  }
  out.values = out.combination * out.standard.values;
  return out;
}

}  // namespace rigid::robot
