#include "rigid/robot/tree_dynamics.hpp"

#include <cmath>
#include <numbers>
#include <utility>

#include <Eigen/Cholesky>
#include <Eigen/Geometry>
#include <fmt/format.h>

#include "rigid/common/error.hpp"
#include "rigid/common/format.hpp"
#include "joint_motion.hpp"

namespace rigid::robot {

namespace {

using Vector6d = Eigen::Matrix<double, 6, 1>;
using Matrix6d = Eigen::Matrix<double, 6, 6>;

Eigen::Matrix3d hat(const Eigen::Vector3d& v) {
  Eigen::Matrix3d m;
  m << 0, -v.z(), v.y(), v.z(), 0, -v.x(), -v.y(), v.x(), 0;
  return m;
}

// V ×m X: the rate of a motion vector X carried by a frame moving with V (both (ω; v))
Vector6d cross_motion(const Vector6d& V, const Vector6d& X) {
  const Eigen::Vector3d w = V.head<3>(), v = V.tail<3>();
  Vector6d r;
  r << w.cross(X.head<3>()), w.cross(X.tail<3>()) + v.cross(X.head<3>());
  return r;
}

// V ×* F: the same for a force vector F = (moment; force)
Vector6d cross_force(const Vector6d& V, const Vector6d& F) {
  const Eigen::Vector3d w = V.head<3>(), v = V.tail<3>();
  Vector6d r;
  r << w.cross(F.head<3>()) + v.cross(F.tail<3>()), w.cross(F.tail<3>());
  return r;
}

// The spatial inertia about the world origin of a mass m with COM c and inertia I_c about the
// COM, all in the world frame: [[I_c + m ĉ ĉᵀ, m ĉ], [m ĉᵀ, m 1]].
Matrix6d spatial_inertia(double m, const Eigen::Vector3d& c, const Eigen::Matrix3d& I_c) {
  const Eigen::Matrix3d C = hat(c);
  Matrix6d I;
  I.topLeftCorner<3, 3>() = I_c + m * C * C.transpose();
  I.topRightCorner<3, 3>() = m * C;
  I.bottomLeftCorner<3, 3>() = m * C.transpose();
  I.bottomRightCorner<3, 3>() = m * Eigen::Matrix3d::Identity();
  return I;
}

bool is_rotation_joint(io::RobotJointType t) {
  return t == io::RobotJointType::kBall || t == io::RobotJointType::kFree;
}

}  // namespace

struct TreeDynamics::Kinematics {
  std::vector<LinkPose> poses;
  Eigen::Matrix<double, 6, Eigen::Dynamic> S;  // joint motion axes, world frame at the origin
  std::vector<Matrix6d> inertia;               // link spatial inertias, same frame
};

TreeDynamics::TreeDynamics(io::RobotModel model) : model_(std::move(model)) {
  std::vector<double> armature, damping;
  for (const io::RobotLink& link : model_.links) {
    first_q_.push_back(nq_);
    first_v_.push_back(nv_);
    std::size_t link_nv = 0;
    for (const io::RobotJoint& joint : link.joints) {
      const SourceLocation where{link.file.empty() ? model_.source : link.file, joint.line, 0};
      if (is_rotation_joint(joint.type) && link.joints.size() > 1) {
        rigid::detail::throw_error_at(
            where, fmt::format("joint '{}' (type {}) shares link '{}' with other joints; a ball or "
                               "free joint must be its link's only joint",
                               joint.name, io::to_string(joint.type), link.name));
      }
      if (joint.type == io::RobotJointType::kFree && link.parent >= 0) {
        rigid::detail::throw_error_at(
            where, fmt::format("joint '{}' (type free): link '{}' has a parent link; a free "
                               "joint's link must be a root (its state is its world pose)",
                               joint.name, link.name));
      }
      nq_ += static_cast<std::size_t>(io::position_count(joint.type));
      const int nv = io::velocity_count(joint.type);
      link_nv += static_cast<std::size_t>(nv);
      for (int k = 0; k < nv; ++k) {
        armature.push_back(joint.armature);
        damping.push_back(joint.damping);
      }
    }
    link_nv_.push_back(link_nv);
    nv_ += link_nv;
  }
  RIGID_REQUIRE_AS("TreeDynamics", nv_ > 0,
                   "{}: the model has no joint, so it has no equations of motion", model_.source);
  armature_ = Eigen::Map<const Eigen::VectorXd>(armature.data(), static_cast<Eigen::Index>(nv_));
  damping_ = Eigen::Map<const Eigen::VectorXd>(damping.data(), static_cast<Eigen::Index>(nv_));
  q0_.resize(static_cast<Eigen::Index>(nq_));
  for (std::size_t i = 0; i < model_.links.size(); ++i) {
    const io::RobotLink& link = model_.links[i];
    auto k = static_cast<Eigen::Index>(first_q_[i]);
    for (const io::RobotJoint& joint : link.joints) {
      switch (joint.type) {
        case io::RobotJointType::kHinge:
        case io::RobotJointType::kSlide:
          q0_(k++) = joint.ref;
          break;
        case io::RobotJointType::kBall:
          q0_.segment<4>(k) << 1, 0, 0, 0;
          k += 4;
          break;
        case io::RobotJointType::kFree: {
          const Eigen::Quaterniond r = detail::reference_orientation(link);
          q0_.segment<3>(k) = link.position;
          q0_.segment<4>(k + 3) << r.w(), r.x(), r.y(), r.z();
          k += 7;
          break;
        }
      }
    }
  }
  const Eigen::MatrixXd M = mass_matrix(q0_);
  const double scale = M.diagonal().cwiseAbs().maxCoeff();
  for (std::size_t i = 0; i < model_.links.size(); ++i) {
    const io::RobotLink& link = model_.links[i];
    auto c = static_cast<Eigen::Index>(first_v_[i]);
    for (const io::RobotJoint& joint : link.joints) {
      for (int e = 0; e < io::velocity_count(joint.type); ++e, ++c) {
        if (M(c, c) > 1e-14 * scale) continue;
        const bool turns = joint.type != io::RobotJointType::kSlide &&
                           !(joint.type == io::RobotJointType::kFree && e < 3);
        rigid::detail::throw_error_at(
            SourceLocation{link.file.empty() ? model_.source : link.file, joint.line, 0},
            fmt::format("joint '{}' moves nothing: the links it carries have no {} about its axis, "
                        "so the mass matrix is singular; give them an inertial or an armature",
                        joint.name, turns ? "inertia" : "mass"));
      }
    }
  }
  RIGID_REQUIRE_AS("TreeDynamics", M.llt().info() == Eigen::Success,
                   "{}: the mass matrix at the reference configuration is not positive definite "
                   "(two joints move the same links the same way)",
                   model_.source);
}

Eigen::VectorXd TreeDynamics::reference_configuration() const { return q0_; }

void TreeDynamics::check_sizes(const char* what, const Eigen::VectorXd& v, std::size_t n) const {
  RIGID_REQUIRE_AS("TreeDynamics", static_cast<std::size_t>(v.size()) == n,
                   "{} has {} entries; the model has {} ({})", what, v.size(), n,
                   n == nq_ && nq_ != nv_ ? "entries of qpos" : "coordinates");
  RIGID_REQUIRE_AS("TreeDynamics", v.allFinite(), "{} is not finite", what);
}

void TreeDynamics::kinematics(const Eigen::VectorXd& q, Kinematics& k) const {
  check_sizes("q", q, nq_);
  const std::size_t links = model_.links.size();
  k.poses.assign(links, LinkPose{});
  k.S.resize(6, static_cast<Eigen::Index>(nv_));
  k.inertia.resize(links);
  for (std::size_t i = 0; i < links; ++i) {
    const io::RobotLink& link = model_.links[i];
    LinkPose parent;
    if (link.parent >= 0) parent = k.poses[static_cast<std::size_t>(link.parent)];
    Eigen::Matrix3d R = parent.rotation * link.rotation;
    Eigen::Vector3d p = parent.position + parent.rotation * link.position;
    auto column = static_cast<Eigen::Index>(first_v_[i]);
    auto entry = static_cast<Eigen::Index>(first_q_[i]);
    for (const io::RobotJoint& joint : link.joints) {
      detail::move_joint(joint, q, entry, R, p, "TreeDynamics",
                         [&](const Vector6d& S, bool) { k.S.col(column++) = S; });
      entry += io::position_count(joint.type);
    }
    k.poses[i] = {p, R};
    k.inertia[i] =
        spatial_inertia(link.mass, p + R * link.com, R * link.inertia_com * R.transpose());
  }
}

Eigen::VectorXd TreeDynamics::rnea(const Kinematics& k, const Eigen::VectorXd& q_dot,
                                   const Eigen::VectorXd& q_ddot) const {
  const std::size_t links = model_.links.size();
  std::vector<Vector6d> V(links), A(links), F(links);
  // gravity as an upward acceleration of the world [Featherstone2008, §5.3]
  Vector6d A_world = Vector6d::Zero();
  A_world.tail<3>() = -model_.gravity;
  for (std::size_t i = 0; i < links; ++i) {
    const io::RobotLink& link = model_.links[i];
    Vector6d v = link.parent >= 0 ? V[static_cast<std::size_t>(link.parent)] : Vector6d::Zero();
    Vector6d a = link.parent >= 0 ? A[static_cast<std::size_t>(link.parent)] : A_world;
    auto c = static_cast<Eigen::Index>(first_v_[i]);
    for (const io::RobotJoint& joint : link.joints) {
      // the acceleration Ṡ v + S v̇ of each group of axes, Ṡ = V × S with V the velocity that
      // carries them: the parent's for axes fixed in it (a hinge's, a slide's, a free joint's
      // world translations); the link's own for axes that turn with the link (a ball's, a free
      // joint's rotations: V_link × S ω, MuJoCo's cdof_dot), which equals V_parent × S ω
      // because S ω × S ω = 0
      const int count = io::velocity_count(joint.type);
      const int fixed = joint.type == io::RobotJointType::kFree   ? 3
                        : joint.type == io::RobotJointType::kBall ? 0
                                                                  : 1;
      if (fixed > 0) {
        const Vector6d Sv = k.S.middleCols(c, fixed) * q_dot.segment(c, fixed);
        a += cross_motion(v, Sv) + k.S.middleCols(c, fixed) * q_ddot.segment(c, fixed);
        v += Sv;
      }
      if (count > fixed) {
        const Eigen::Index r = c + fixed;
        const Vector6d Sw = k.S.middleCols(r, 3) * q_dot.segment(r, 3);
        v += Sw;
        a += cross_motion(v, Sw) + k.S.middleCols(r, 3) * q_ddot.segment(r, 3);
      }
      c += count;
    }
    V[i] = v;
    A[i] = a;
    F[i] = k.inertia[i] * a + cross_force(v, k.inertia[i] * v);
  }
  Eigen::VectorXd tau(static_cast<Eigen::Index>(nv_));
  for (std::size_t i = links; i-- > 0;) {
    const io::RobotLink& link = model_.links[i];
    for (std::size_t j = 0; j < link_nv_[i]; ++j) {
      const auto c = static_cast<Eigen::Index>(first_v_[i] + j);
      tau(c) = k.S.col(c).dot(F[i]);
    }
    if (link.parent >= 0) F[static_cast<std::size_t>(link.parent)] += F[i];
  }
  return tau;
}

std::vector<LinkPose> TreeDynamics::link_poses(const Eigen::VectorXd& q) const {
  Kinematics k;
  kinematics(q, k);
  return std::move(k.poses);
}

Eigen::MatrixXd TreeDynamics::mass_matrix(const Eigen::VectorXd& q) const {
  Kinematics k;
  kinematics(q, k);
  return crba(k);
}

Eigen::MatrixXd TreeDynamics::crba(const Kinematics& k) const {
  const std::size_t links = model_.links.size();
  // composite inertias: each link's subtree [Featherstone2008, §6.2]
  std::vector<Matrix6d> Ic = k.inertia;
  for (std::size_t i = links; i-- > 0;) {
    if (model_.links[i].parent >= 0) Ic[static_cast<std::size_t>(model_.links[i].parent)] += Ic[i];
  }
  const auto n = static_cast<Eigen::Index>(nv_);
  Eigen::MatrixXd M = Eigen::MatrixXd::Zero(n, n);
  for (std::size_t i = 0; i < links; ++i) {
    for (std::size_t j = 0; j < link_nv_[i]; ++j) {
      const auto col = static_cast<Eigen::Index>(first_v_[i] + j);
      const Vector6d F = Ic[i] * k.S.col(col);
      // the axes of this link and of every ancestor feel it
      for (int a = static_cast<int>(i); a >= 0;
           a = model_.links[static_cast<std::size_t>(a)].parent) {
        const auto ua = static_cast<std::size_t>(a);
        for (std::size_t jj = 0; jj < link_nv_[ua]; ++jj) {
          const auto row = static_cast<Eigen::Index>(first_v_[ua] + jj);
          M(row, col) = M(col, row) = k.S.col(row).dot(F);
        }
      }
    }
  }
  M.diagonal() += armature_;
  return M;
}

Eigen::VectorXd TreeDynamics::bias_forces(const Eigen::VectorXd& q,
                                          const Eigen::VectorXd& q_dot) const {
  check_sizes("q_dot", q_dot, nv_);
  Kinematics k;
  kinematics(q, k);
  return rnea(k, q_dot, Eigen::VectorXd::Zero(static_cast<Eigen::Index>(nv_)));
}

Eigen::VectorXd TreeDynamics::passive_forces(const Eigen::VectorXd& q,
                                             const Eigen::VectorXd& q_dot) const {
  check_sizes("q", q, nq_);
  check_sizes("q_dot", q_dot, nv_);
  Eigen::VectorXd p = -damping_.cwiseProduct(q_dot);
  for (std::size_t i = 0; i < model_.links.size(); ++i) {
    auto e = static_cast<Eigen::Index>(first_q_[i]);
    auto c = static_cast<Eigen::Index>(first_v_[i]);
    for (const io::RobotJoint& joint : model_.links[i].joints) {
      const int n = io::velocity_count(joint.type);
      p.segment(c, n) -= joint.stiffness * detail::spring_displacement(joint, model_.links[i], q, e).head(n);
      e += io::position_count(joint.type);
      c += n;
    }
  }
  return p;
}

Eigen::VectorXd TreeDynamics::inverse_dynamics(const Eigen::VectorXd& q,
                                               const Eigen::VectorXd& q_dot,
                                               const Eigen::VectorXd& q_ddot) const {
  check_sizes("q_dot", q_dot, nv_);
  check_sizes("q_ddot", q_ddot, nv_);
  Kinematics k;
  kinematics(q, k);
  return rnea(k, q_dot, q_ddot) - passive_forces(q, q_dot) + armature_.cwiseProduct(q_ddot);
}

Eigen::VectorXd TreeDynamics::forward_dynamics(const Eigen::VectorXd& q,
                                               const Eigen::VectorXd& q_dot,
                                               const Eigen::VectorXd& tau) const {
  check_sizes("q_dot", q_dot, nv_);
  check_sizes("tau", tau, nv_);
  // one pass of kinematics for M and b
  Kinematics k;
  kinematics(q, k);
  const Eigen::LLT<Eigen::MatrixXd> llt(crba(k));
  RIGID_REQUIRE_AS("TreeDynamics", llt.info() == Eigen::Success,
                   "the mass matrix is not positive definite at q = {}",
                   rigid::to_string(q.transpose()));
  const Eigen::VectorXd b =
      rnea(k, q_dot, Eigen::VectorXd::Zero(static_cast<Eigen::Index>(nv_)));
  return llt.solve(tau - b + passive_forces(q, q_dot));
}

double TreeDynamics::kinetic_energy(const Eigen::VectorXd& q, const Eigen::VectorXd& q_dot) const {
  check_sizes("q_dot", q_dot, nv_);
  return 0.5 * q_dot.dot(mass_matrix(q) * q_dot);
}

double TreeDynamics::potential_energy(const Eigen::VectorXd& q) const {
  Kinematics k;
  kinematics(q, k);
  double V = 0;
  for (std::size_t i = 0; i < model_.links.size(); ++i) {
    const io::RobotLink& link = model_.links[i];
    const Eigen::Vector3d c = k.poses[i].position + k.poses[i].rotation * link.com;
    V -= link.mass * model_.gravity.dot(c);
  }
  for (std::size_t i = 0; i < model_.links.size(); ++i) {
    auto e = static_cast<Eigen::Index>(first_q_[i]);
    for (const io::RobotJoint& joint : model_.links[i].joints) {
      V += 0.5 * joint.stiffness * detail::spring_displacement(joint, model_.links[i], q, e).squaredNorm();
      e += io::position_count(joint.type);
    }
  }
  return V;
}

}  // namespace rigid::robot
