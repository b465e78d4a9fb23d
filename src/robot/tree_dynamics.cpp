#include "rigid/robot/tree_dynamics.hpp"

#include <cmath>
#include <utility>

#include <Eigen/Cholesky>
#include <Eigen/Geometry>
#include <fmt/format.h>

#include "rigid/common/error.hpp"
#include "rigid/common/format.hpp"

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

}  // namespace

struct TreeDynamics::Kinematics {
  std::vector<LinkPose> poses;
  Eigen::Matrix<double, 6, Eigen::Dynamic> S;  // joint motion axes, world frame at the origin
  std::vector<Matrix6d> inertia;               // link spatial inertias, same frame
};

TreeDynamics::TreeDynamics(io::RobotModel model) : model_(std::move(model)) {
  for (const io::RobotLink& link : model_.links) {
    first_dof_.push_back(n_);
    n_ += link.joints.size();
  }
  RIGID_REQUIRE_AS("TreeDynamics", n_ > 0,
                   "{}: the model has no joint, so it has no equations of motion", model_.source);
  const Eigen::MatrixXd M = mass_matrix(reference_configuration());
  const double scale = M.diagonal().cwiseAbs().maxCoeff();
  std::size_t j = 0;
  for (const io::RobotLink& link : model_.links) {
    for (const io::RobotJoint& joint : link.joints) {
      const auto k = static_cast<Eigen::Index>(j++);
      if (!(M(k, k) > 1e-14 * scale)) {
        rigid::detail::throw_error_at(
            SourceLocation{link.file.empty() ? model_.source : link.file, joint.line, 0},
            fmt::format("joint '{}' moves nothing: the links it carries have no {} about its axis, "
                        "so the mass matrix is singular; give them an inertial or an armature",
                        joint.name, joint.type == io::RobotJointType::kHinge ? "inertia" : "mass"));
      }
    }
  }
  RIGID_REQUIRE_AS("TreeDynamics", M.llt().info() == Eigen::Success,
                   "{}: the mass matrix at the reference configuration is not positive definite "
                   "(two joints move the same links the same way)",
                   model_.source);
}

Eigen::VectorXd TreeDynamics::reference_configuration() const {
  Eigen::VectorXd q(static_cast<Eigen::Index>(n_));
  Eigen::Index k = 0;
  for (const io::RobotLink& link : model_.links) {
    for (const io::RobotJoint& joint : link.joints) q(k++) = joint.ref;
  }
  return q;
}

void TreeDynamics::check_sizes(const char* what, const Eigen::VectorXd& v) const {
  RIGID_REQUIRE_AS("TreeDynamics", static_cast<std::size_t>(v.size()) == n_,
                   "{} has {} entries; the model has {} "
                   "coordinates",
                   what, v.size(), n_);
  RIGID_REQUIRE_AS("TreeDynamics", v.allFinite(), "{} is not finite", what);
}

void TreeDynamics::kinematics(const Eigen::VectorXd& q, Kinematics& k) const {
  check_sizes("q", q);
  const std::size_t links = model_.links.size();
  k.poses.assign(links, LinkPose{});
  k.S.resize(6, static_cast<Eigen::Index>(n_));
  k.inertia.resize(links);
  for (std::size_t i = 0; i < links; ++i) {
    const io::RobotLink& link = model_.links[i];
    LinkPose parent;
    if (link.parent >= 0) parent = k.poses[static_cast<std::size_t>(link.parent)];
    Eigen::Matrix3d R = parent.rotation * link.rotation;
    Eigen::Vector3d p = parent.position + parent.rotation * link.position;
    auto column = static_cast<Eigen::Index>(first_dof_[i]);
    for (const io::RobotJoint& joint : link.joints) {
      const double amount = q(column) - joint.ref;
      const Eigen::Vector3d u = R * joint.axis;
      Vector6d S;
      if (joint.type == io::RobotJointType::kHinge) {
        // a turn about the line through the anchor: the anchor stays where it is
        const Eigen::Vector3d a = p + R * joint.anchor;
        S << u, a.cross(u);
        R = R * Eigen::AngleAxisd(amount, joint.axis).toRotationMatrix();
        p = a - R * joint.anchor;
      } else {
        S << Eigen::Vector3d::Zero(), u;
        p += u * amount;
      }
      k.S.col(column++) = S;
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
    for (std::size_t j = 0; j < link.joints.size(); ++j) {
      const auto c = static_cast<Eigen::Index>(first_dof_[i] + j);
      const Vector6d S = k.S.col(c);
      a += cross_motion(v, S) * q_dot(c) + S * q_ddot(c);
      v += S * q_dot(c);
    }
    V[i] = v;
    A[i] = a;
    F[i] = k.inertia[i] * a + cross_force(v, k.inertia[i] * v);
  }
  Eigen::VectorXd tau(static_cast<Eigen::Index>(n_));
  for (std::size_t i = links; i-- > 0;) {
    const io::RobotLink& link = model_.links[i];
    for (std::size_t j = 0; j < link.joints.size(); ++j) {
      const auto c = static_cast<Eigen::Index>(first_dof_[i] + j);
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
  const auto n = static_cast<Eigen::Index>(n_);
  Eigen::MatrixXd M = Eigen::MatrixXd::Zero(n, n);
  for (std::size_t i = 0; i < links; ++i) {
    const std::size_t count = model_.links[i].joints.size();
    for (std::size_t j = 0; j < count; ++j) {
      const auto col = static_cast<Eigen::Index>(first_dof_[i] + j);
      const Vector6d F = Ic[i] * k.S.col(col);
      // the joints of this link and of every ancestor feel it
      for (int a = static_cast<int>(i); a >= 0;
           a = model_.links[static_cast<std::size_t>(a)].parent) {
        const auto ua = static_cast<std::size_t>(a);
        for (std::size_t jj = 0; jj < model_.links[ua].joints.size(); ++jj) {
          const auto row = static_cast<Eigen::Index>(first_dof_[ua] + jj);
          M(row, col) = M(col, row) = k.S.col(row).dot(F);
        }
      }
    }
  }
  Eigen::Index c = 0;
  for (const io::RobotLink& link : model_.links) {
    for (const io::RobotJoint& joint : link.joints) {
      M(c, c) += joint.armature;
      ++c;
    }
  }
  return M;
}

Eigen::VectorXd TreeDynamics::bias_forces(const Eigen::VectorXd& q,
                                          const Eigen::VectorXd& q_dot) const {
  check_sizes("q_dot", q_dot);
  Kinematics k;
  kinematics(q, k);
  return rnea(k, q_dot, Eigen::VectorXd::Zero(static_cast<Eigen::Index>(n_)));
}

Eigen::VectorXd TreeDynamics::passive_forces(const Eigen::VectorXd& q,
                                             const Eigen::VectorXd& q_dot) const {
  check_sizes("q", q);
  check_sizes("q_dot", q_dot);
  Eigen::VectorXd p(static_cast<Eigen::Index>(n_));
  Eigen::Index c = 0;
  for (const io::RobotLink& link : model_.links) {
    for (const io::RobotJoint& joint : link.joints) {
      p(c) = -joint.damping * q_dot(c) - joint.stiffness * (q(c) - joint.springref);
      ++c;
    }
  }
  return p;
}

Eigen::VectorXd TreeDynamics::inverse_dynamics(const Eigen::VectorXd& q,
                                               const Eigen::VectorXd& q_dot,
                                               const Eigen::VectorXd& q_ddot) const {
  check_sizes("q_dot", q_dot);
  check_sizes("q_ddot", q_ddot);
  Kinematics k;
  kinematics(q, k);
  Eigen::VectorXd tau = rnea(k, q_dot, q_ddot) - passive_forces(q, q_dot);
  Eigen::Index c = 0;
  for (const io::RobotLink& link : model_.links) {
    for (const io::RobotJoint& joint : link.joints) {
      tau(c) += joint.armature * q_ddot(c);
      ++c;
    }
  }
  return tau;
}

Eigen::VectorXd TreeDynamics::forward_dynamics(const Eigen::VectorXd& q,
                                               const Eigen::VectorXd& q_dot,
                                               const Eigen::VectorXd& tau) const {
  check_sizes("q_dot", q_dot);
  check_sizes("tau", tau);
  // one pass of kinematics for M and b
  Kinematics k;
  kinematics(q, k);
  const Eigen::LLT<Eigen::MatrixXd> llt(crba(k));
  RIGID_REQUIRE_AS("TreeDynamics", llt.info() == Eigen::Success,
                   "the mass matrix is not positive definite at q = {}",
                   rigid::to_string(q.transpose()));
  const Eigen::VectorXd b = rnea(k, q_dot, Eigen::VectorXd::Zero(static_cast<Eigen::Index>(n_)));
  return llt.solve(tau - b + passive_forces(q, q_dot));
}

double TreeDynamics::kinetic_energy(const Eigen::VectorXd& q, const Eigen::VectorXd& q_dot) const {
  check_sizes("q_dot", q_dot);
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
  Eigen::Index c = 0;
  for (const io::RobotLink& link : model_.links) {
    for (const io::RobotJoint& joint : link.joints) {
      const double d = q(c++) - joint.springref;
      V += 0.5 * joint.stiffness * d * d;
    }
  }
  return V;
}

}  // namespace rigid::robot
