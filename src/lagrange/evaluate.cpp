// Numeric side of rigid::lagrange::System: workspaces, evaluation of the compiled tapes, the
// solve for q̈ and λ, and simulation. Nothing here touches GiNaC, and nothing here writes into
// the System: every scratch value lives in a Workspace, so one System serves many threads.
#include "rigid/lagrange/system.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include <Eigen/Cholesky>
#include <Eigen/LU>
#include <Eigen/SVD>
#include <fmt/format.h>

#include "detail/system_impl.hpp"
#include "detail/velocity_constraints.hpp"
#include "rigid/common/format.hpp"

namespace rigid::lagrange {
namespace {

using Impl = System::Impl;
using WorkImpl = Workspace::Impl;

void load_inputs(const Impl& s, WorkImpl& w, double time, const Eigen::VectorXd& qv,
                 const Eigen::VectorXd& qdv) {
  for (int i = 0; i < s.nq; ++i) w.in[static_cast<std::size_t>(i)] = qv[i];
  for (int i = 0; i < s.n; ++i) w.in[static_cast<std::size_t>(s.nq + i)] = qdv[i];
  w.in[static_cast<std::size_t>(s.nq + s.n)] = time;
  std::copy(w.params.begin(), w.params.end(), w.in.begin() + s.nq + s.n + 1);
}

void evaluate_dynamics(const Impl& s, WorkImpl& w, double time, const Eigen::VectorXd& qv,
                       const Eigen::VectorXd& qdv) {
  load_inputs(s, w, time, qv, qdv);
  s.dyn.evaluate(w.in.data(), w.out.data(), w.dyn_scratch);
  const int n = s.n, m = s.m;
  std::size_t k = 0;
  for (int i = 0; i < n; ++i)
    for (int j = i; j < n; ++j) w.Mw(i, j) = w.Mw(j, i) = w.out[k++];
  for (int i = 0; i < n; ++i) w.fw[i] = w.out[k++];
  for (int a = 0; a < m; ++a)
    for (int i = 0; i < n; ++i) w.Gw(a, i) = w.out[k++];
  for (int a = 0; a < m; ++a) w.gammaw[a] = w.out[k++];
  for (int a = 0; a < m; ++a) w.cw[a] = w.out[k++];
  for (int a = 0; a < m; ++a) w.gw[a] = w.out[k++];
  if (s.r > 0) detail::evaluate_velocity_constraints(s, w);  // rows m … m + r − 1
}

void evaluate_diagnostics(const Impl& s, WorkImpl& w, double time, const Eigen::VectorXd& qv,
                          const Eigen::VectorXd& qdv) {
  load_inputs(s, w, time, qv, qdv);
  s.diag.evaluate(w.in.data(), w.diag_out.data(), w.diag_scratch);
}

void solve(const Impl& s, WorkImpl& w, double time, const Eigen::VectorXd& qv,
           Eigen::VectorXd& qdd_out, Eigen::VectorXd& lambda_out, double alpha) {
  const int n = s.n, m = s.m + s.r;  // holonomic rows, then velocity rows
  w.llt_M.compute(w.Mw);
  bool singular = w.llt_M.info() != Eigen::Success;
  if (!singular) {
    // pivots of the Cholesky factor: M is numerically singular when the smallest squared
    // pivot falls below 1e-13 of the largest (condition number ≳ 1e13) (or of the largest at
    // the start of the run) (a loop rather than minCoeff(): g++ 12 -O3 reports a false null
    // dereference in Eigen's vectorised reduction here)
    double dmin = std::numeric_limits<double>::infinity(), dmax = 0.0;
    for (Eigen::Index i = 0; i < n; ++i) {
      const double di = w.llt_M.matrixLLT()(i, i) * w.llt_M.matrixLLT()(i, i);
      dmin = std::min(dmin, di);
      dmax = std::max(dmax, di);
    }
    singular = !(dmin > 1e-13 * std::max(dmax, w.mass_scale));
  }
  if (singular) {
    throw Error(fmt::format("the mass matrix M = ∂²L/∂q̇∂q̇ is singular or not positive definite "
                            "at {}; M = {}. Every coordinate needs a positive kinetic energy term",
                            s.state_text(time, qv), rigid::to_string(w.Mw)));
  }
  if (m == 0) {
    // straight into the caller's vector (one copy fewer: a tenth of a 2-link call)
    qdd_out = w.llt_M.solve(w.fw);
    lambda_out.resize(0);
    return;
  }
  w.Minv_f = w.llt_M.solve(w.fw);
  w.Yw = w.llt_M.solve(w.Gw.transpose());
  w.Sw.noalias() = w.Gw * w.Yw;
  w.ldlt_S.compute(w.Sw);
  const auto dS = w.ldlt_S.vectorD();  // an expression: no copy
  if (w.ldlt_S.info() != Eigen::Success ||
      !(dS.minCoeff() > 1e-12 * std::max(1e-300, dS.cwiseAbs().maxCoeff()))) {
    throw Error(fmt::format("the constraint Jacobian {} lost rank at {}: the constraints are "
                            "dependent there ({} = {})",
                            s.r ? "[∂g/∂q; A] (with the velocity constraints' rows A)" : "∂g/∂q",
                            s.state_text(time, qv), s.r ? "[G; A]" : "G", rigid::to_string(w.Gw)));
  }
  // λ = (G M⁻¹ Gᵀ)⁻¹ (γ − 2α ġ − α² g − G M⁻¹ f);  q̈ = M⁻¹ f + M⁻¹ Gᵀ λ
  // (velocity rows: G ← A, γ ← η, ġ ← A q̇ + a, g ← 0; λ ← μ)
  // (the products are written into the destinations with noalias(): a product inside a
  // sum would be evaluated into a temporary, one allocation per call)
  w.rhs_m = w.gammaw - 2.0 * alpha * w.cw - alpha * alpha * w.gw;
  w.rhs_m.noalias() -= w.Gw * w.Minv_f;
  lambda_out = w.ldlt_S.solve(w.rhs_m);
  qdd_out = w.Minv_f;
  qdd_out.noalias() += w.Yw * lambda_out;
}

WorkImpl& checked(const Impl& s, Workspace& w);

void require_sizes(const Impl& s, const Eigen::VectorXd& q, const Eigen::VectorXd& q_dot) {
  if (q.size() == s.nq && q_dot.size() == s.n) return;
  rigid::detail::throw_error(
      "System", s.nq == s.n ? fmt::format("expected q and q_dot of size {} (one per coordinate), got {} and {}",
                                          s.n, q.size(), q_dot.size())
                            : fmt::format("expected q of size {} (four per ball coordinate) and q_dot of size {} "
                                          "(three per ball), got {} and {}",
                                          s.nq, s.n, q.size(), q_dot.size()));
}

}  // namespace

// ---------------------------------------------------------------------------------------------
// Workspace

Workspace::Workspace(std::unique_ptr<Impl> impl) : impl_(std::move(impl)) {}
Workspace::Workspace(Workspace&&) noexcept = default;
Workspace& Workspace::operator=(Workspace&&) noexcept = default;
Workspace::~Workspace() = default;

void Workspace::set_parameter(const std::string& name, double value) {
  const System::Impl& s = *impl_->owner;
  const std::size_t k = s.parameter_index(name);
  RIGID_REQUIRE(std::isfinite(value), "parameter '{}' must be finite, got {}", name, value);
  std::vector<double> values = impl_->params;
  values[k] = value;
  s.check_masses(values, fmt::format("with {} = {}", name, value));
  impl_->params = std::move(values);
}

void Workspace::set_parameters(const std::vector<Parameter>& parameters) {
  if (parameters.empty()) return;
  const System::Impl& s = *impl_->owner;
  std::vector<double> values = impl_->params;
  for (const Parameter& p : parameters) {
    RIGID_REQUIRE(std::isfinite(p.value), "parameter '{}' must be finite, got {}", p.name, p.value);
    values[s.parameter_index(p.name)] = p.value;
  }
  // the masses are checked once, for the values together: one at a time, a valid set of new
  // values could pass through an invalid one (a new ixx with the old iyy and izz)
  s.check_masses(values, "for the run's parameter values");
  impl_->params = std::move(values);
}

Workspace System::make_workspace() const {
  const Impl& s = *impl_;
  auto w = std::make_unique<Workspace::Impl>();
  w->owner = &s;
  w->params = s.param_values;
  w->in.assign(s.num_inputs(), 0.0);
  w->out.assign(s.dyn.num_outputs(), 0.0);
  w->diag_out.assign(s.diag.num_outputs(), 0.0);
  w->pose_out.assign(s.pose.num_outputs(), 0.0);
  w->dyn_scratch = s.dyn.make_scratch();
  w->diag_scratch = s.diag.make_scratch();
  w->pose_scratch = s.pose.make_scratch();
  w->Mw.resize(s.n, s.n);
  w->fw.resize(s.n);
  w->Gw.resize(s.m + s.r, s.n);
  w->gammaw.resize(s.m + s.r);
  w->cw.resize(s.m + s.r);
  w->gw.resize(s.m + s.r);
  w->vel_out.assign(s.vel.num_outputs(), 0.0);
  w->vel_scratch = s.vel.make_scratch();
  return Workspace(std::move(w));
}

namespace {
WorkImpl& checked(const Impl& s, Workspace& w) {
  WorkImpl* impl = Workspace::Access::impl(w);
  RIGID_REQUIRE_AS("System", impl != nullptr && impl->owner == &s,
                "the workspace belongs to another System (or was moved from); make one with "
                "this System's make_workspace()");
  return *impl;
}
}  // namespace

// ---------------------------------------------------------------------------------------------
// Evaluation

void System::mass_matrix_and_forces(Workspace& ws, double t, const Eigen::VectorXd& q,
                                    const Eigen::VectorXd& q_dot, Eigen::MatrixXd& M,
                                    Eigen::VectorXd& f) const {
  const Impl& s = *impl_;
  WorkImpl& w = checked(s, ws);
  require_sizes(s, q, q_dot);
  evaluate_dynamics(s, w, t, q, q_dot);
  M = w.Mw;
  f = w.fw;
}

void System::accelerations(Workspace& ws, double t, const Eigen::VectorXd& q,
                           const Eigen::VectorXd& q_dot, Eigen::VectorXd& q_ddot,
                           Eigen::VectorXd& lambda, double stabilization) const {
  const Impl& s = *impl_;
  WorkImpl& w = checked(s, ws);
  require_sizes(s, q, q_dot);
  evaluate_dynamics(s, w, t, q, q_dot);
  solve(s, w, t, q, q_ddot, lambda, stabilization);
}

double System::energy(Workspace& ws, double t, const Eigen::VectorXd& q,
                      const Eigen::VectorXd& q_dot) const {
  const Impl& s = *impl_;
  WorkImpl& w = checked(s, ws);
  require_sizes(s, q, q_dot);
  evaluate_diagnostics(s, w, t, q, q_dot);
  return w.diag_out[0];
}

double System::jacobi_integral(Workspace& ws, double t, const Eigen::VectorXd& q,
                               const Eigen::VectorXd& q_dot) const {
  const Impl& s = *impl_;
  WorkImpl& w = checked(s, ws);
  require_sizes(s, q, q_dot);
  evaluate_diagnostics(s, w, t, q, q_dot);
  return w.diag_out[1];
}

Eigen::VectorXd System::constraint_residual(Workspace& ws, double t, const Eigen::VectorXd& q) const {
  const Impl& s = *impl_;
  WorkImpl& w = checked(s, ws);
  RIGID_REQUIRE(q.size() == s.nq, "expected q of size {} (one per coordinate), got {}", s.nq, q.size());
  evaluate_dynamics(s, w, t, q, Eigen::VectorXd::Zero(s.n));
  return w.gw.head(s.m);
}

Eigen::VectorXd System::velocity_constraint_residual(double t, const Eigen::VectorXd& q,
                                                     const Eigen::VectorXd& q_dot) const {
  const Impl& s = *impl_;
  Workspace ws = make_workspace();
  WorkImpl& w = checked(s, ws);
  require_sizes(s, q, q_dot);
  evaluate_dynamics(s, w, t, q, q_dot);
  return w.cw.tail(s.r);
}

std::vector<BodyPose> System::body_poses(Workspace& ws, double time, const Eigen::VectorXd& q) const {
  const Impl& s = *impl_;
  WorkImpl& w = checked(s, ws);
  RIGID_REQUIRE(q.size() == s.nq, "expected q of size {} (one per coordinate), got {}", s.nq, q.size());
  load_inputs(s, w, time, q, Eigen::VectorXd::Zero(s.n));
  s.pose.evaluate(w.in.data(), w.pose_out.data(), w.pose_scratch);
  std::vector<BodyPose> poses(s.body_names.size());
  for (std::size_t b = 0; b < poses.size(); ++b) {
    const double* o = w.pose_out.data() + 12 * b;
    poses[b].p_WB = Eigen::Vector3d(o[0], o[1], o[2]);
    Eigen::Matrix3d R;
    R << o[3], o[4], o[5], o[6], o[7], o[8], o[9], o[10], o[11];
    // R is a product of exact rotations, orthonormal to round-off; the sign is made
    // canonical (w ≥ 0) so that equal poses give equal quaternions
    const SO3d R_WB = SO3d::from_matrix(R);
    poses[b].R_WB = R_WB.w() < 0 ? SO3d::from_unit_quaternion(-R_WB.w(), -R_WB.x(), -R_WB.y(), -R_WB.z())
                                 : R_WB;
  }
  return poses;
}

void System::mass_matrix_and_forces(double t, const Eigen::VectorXd& q, const Eigen::VectorXd& q_dot,
                                    Eigen::MatrixXd& M, Eigen::VectorXd& f) const {
  Workspace w = make_workspace();
  mass_matrix_and_forces(w, t, q, q_dot, M, f);
}

void System::accelerations(double t, const Eigen::VectorXd& q, const Eigen::VectorXd& q_dot,
                           Eigen::VectorXd& q_ddot, Eigen::VectorXd& lambda, double stabilization) const {
  Workspace w = make_workspace();
  accelerations(w, t, q, q_dot, q_ddot, lambda, stabilization);
}

double System::energy(double t, const Eigen::VectorXd& q, const Eigen::VectorXd& q_dot) const {
  Workspace w = make_workspace();
  return energy(w, t, q, q_dot);
}

double System::jacobi_integral(double t, const Eigen::VectorXd& q, const Eigen::VectorXd& q_dot) const {
  Workspace w = make_workspace();
  return jacobi_integral(w, t, q, q_dot);
}

Eigen::VectorXd System::constraint_residual(double t, const Eigen::VectorXd& q) const {
  Workspace w = make_workspace();
  return constraint_residual(w, t, q);
}

std::vector<BodyPose> System::body_poses(double t, const Eigen::VectorXd& q) const {
  Workspace w = make_workspace();
  return body_poses(w, t, q);
}

// ---------------------------------------------------------------------------------------------
// Simulation

Trajectory System::simulate(const SimulationOptions& options) const {
  return simulate(options, impl_->q0, impl_->qd0);
}

Trajectory System::simulate(const SimulationOptions& o, const Eigen::VectorXd& q0_in,
                            const Eigen::VectorXd& qd0_in) const {
  const Impl& s = *impl_;
  RIGID_REQUIRE(q0_in.size() == s.nq && qd0_in.size() == s.n,
                "expected initial q and q_dot of size {}, got {} and {}",
                s.nq == s.n ? fmt::format("{}", s.n) : fmt::format("{} and {}", s.nq, s.n), q0_in.size(),
                qd0_in.size());
  for (const Impl::Ball& b : s.balls) {
    const double norm = q0_in.segment(static_cast<Eigen::Index>(b.q), 4).norm();
    RIGID_REQUIRE(std::abs(norm - 1) <= 1e-6, "the initial orientation of the ball coordinate '{}' "
                  "has norm {}; expected a unit quaternion (w, x, y, z) within 1e-6", b.name, norm);
  }
  RIGID_REQUIRE(std::isfinite(o.stabilization) && o.stabilization >= 0,
                "stabilization rate must be ≥ 0 and finite, got {} 1/s", o.stabilization);
  RIGID_REQUIRE(o.consistency_tolerance > 0, "consistency_tolerance must be positive, got {}",
                o.consistency_tolerance);
  // the one tolerance is dopri5's rtol and atol: refused by its own name, not as rtol
  if (o.method == integrate::Method::kDopri5 && o.tolerance > integrate::kMaxTolerance) {
    RIGID_THROW("{}", integrate::tolerance_above_bound("tolerance", o.tolerance));
  }
  if (o.method == integrate::Method::kStormerVerlet) {
    RIGID_REQUIRE(s.verlet_ok, "stormer_verlet needs T = ½ q̇ᵀ M q̇ with a constant M, forces "
                  "that do not depend on q̇ and no constraints; use implicit_midpoint");
  }
  Workspace workspace = make_workspace();
  WorkImpl& w = *Workspace::Access::impl(workspace);
  workspace.set_parameters(o.parameters);
  Eigen::VectorXd q0 = q0_in, qd0 = qd0_in;
  const double t0 = 0.0;

  const int mr = s.m + s.r;  // holonomic rows, then velocity rows
  if (mr > 0) {
    // "constraints 'a', 'b'", "velocity constraints 'c'" or both, joined by "and"
    auto names_of = [&](const Eigen::VectorXd& weights) {
      std::string holonomic, velocity;
      for (int k = 0; k < mr; ++k) {
        if (std::abs(weights[k]) > 1e-8) {
          std::string& out = k < s.m ? holonomic : velocity;
          out += fmt::format("{}'{}'", out.empty() ? "" : ", ",
                             k < s.m ? s.constraint_names[static_cast<std::size_t>(k)]
                                     : s.velocity_constraint_names[static_cast<std::size_t>(k - s.m)]);
        }
      }
      if (velocity.empty()) return "constraints " + holonomic;
      if (holonomic.empty()) return "velocity constraints " + velocity;
      return "constraints " + holonomic + " and velocity constraints " + velocity;
    };
    // dependent constraints: a left null vector u of G (uᵀG = 0) combines them into 0 = uᵀg,
    // which is redundant if uᵀg = 0 and inconsistent otherwise (with velocity rows, also
    // 0 = uᵀ(G q̇ + g_t; A q̇ + a) = uᵀ(g_t; a) for every q̇)
    evaluate_dynamics(s, w, t0, q0, qd0);
    Eigen::JacobiSVD<Eigen::MatrixXd> svd(w.Gw, Eigen::ComputeFullU);
    const Eigen::VectorXd sv = svd.singularValues();
    const double smax = sv.size() ? sv.maxCoeff() : 0.0;
    for (int k = 0; k < mr; ++k) {
      const double sk = k < sv.size() ? sv[k] : 0.0;
      if (sk <= 1e-10 * std::max(smax, 1e-300)) {
        const Eigen::VectorXd u = svd.matrixU().col(k);
        const double combined = u.dot(w.gw);
        const double combined_rate = s.r > 0 ? u.dot(w.cw) : 0.0;
        if (std::abs(combined) > o.consistency_tolerance) {
          RIGID_THROW("{} are inconsistent: their gradients ∂g/∂q are dependent at "
                      "q(0) and no q satisfies all of them (the combination Σ uₖ gₖ = {} "
                      "cannot vanish)", names_of(u), combined);
        }
        if (std::abs(combined_rate) > o.consistency_tolerance) {
          RIGID_THROW("{} are inconsistent: their rows are dependent at q(0) and no "
                      "q̇ satisfies all of them (the combination of their residuals is {} for "
                      "every q̇)", names_of(u), combined_rate);
        }
        RIGID_THROW("{} are redundant: their {} linearly dependent at q(0) (rank "
                    "{} < {}); remove one", names_of(u),
                    s.r ? "rows (gradients ∂g/∂q and velocity rows A) are" : "gradients ∂g/∂q are",
                    k, mr);
      }
    }
    const double res = w.gw.head(s.m).lpNorm<Eigen::Infinity>();
    const double vres = w.cw.head(s.m).lpNorm<Eigen::Infinity>();
    const double nres = w.cw.tail(s.r).lpNorm<Eigen::Infinity>();
    if (res > o.consistency_tolerance || vres > o.consistency_tolerance ||
        nres > o.consistency_tolerance) {
      if (!o.project_initial) {
        Eigen::Index worst = 0;
        if (res > o.consistency_tolerance || vres > o.consistency_tolerance) {
          (res > o.consistency_tolerance ? w.gw : w.cw).head(s.m).cwiseAbs().maxCoeff(&worst);
          RIGID_THROW("initial conditions violate constraint '{}': |g| = {}, |ġ| = {} (tolerance "
                      "{}); fix q(0), q̇(0) or set project_initial to project them",
                      s.constraint_names[static_cast<std::size_t>(worst)], res, vres,
                      o.consistency_tolerance);
        }
        w.cw.tail(s.r).cwiseAbs().maxCoeff(&worst);
        RIGID_THROW("initial velocities violate velocity constraint '{}': |A q̇ + a| = {} "
                    "(tolerance {}); fix q̇(0) or set project_initial to project them",
                    s.velocity_constraint_names[static_cast<std::size_t>(worst)], nres,
                    o.consistency_tolerance);
      }
      // minimum-norm Newton on the holonomic rows: q ← q − Gᵀ (G Gᵀ)⁻¹ g, then on every row
      // q̇ ← q̇ − Gᵀ (G Gᵀ)⁻¹ ġ (ġ = G q̇ + g_t and A q̇ + a are affine in q̇)
      for (int it = 0; s.m > 0 && it < 50 &&
                       w.gw.head(s.m).lpNorm<Eigen::Infinity>() > 1e-3 * o.consistency_tolerance;
           ++it) {
        const Eigen::MatrixXd G = w.Gw.topRows(s.m);
        const Eigen::MatrixXd GGt = G * G.transpose();
        q0 -= G.transpose() * GGt.ldlt().solve(w.gw.head(s.m));
        evaluate_dynamics(s, w, t0, q0, qd0);
      }
      RIGID_REQUIRE(w.gw.head(s.m).lpNorm<Eigen::Infinity>() <= o.consistency_tolerance,
                    "projection of q(0) onto the constraints did not converge: |g| = {}",
                    w.gw.head(s.m).lpNorm<Eigen::Infinity>());
      const Eigen::MatrixXd GGt = w.Gw * w.Gw.transpose();
      qd0 -= w.Gw.transpose() * GGt.ldlt().solve(w.cw);
    }
  }
  // the mass matrix at the start (named error if not positive definite) sets the scale
  // against which it is called singular during the run
  const Eigen::Index n = s.n, nq = s.nq;
  Eigen::VectorXd qv(nq), qdv(n), acc(n), lw(mr);
  w.mass_scale = 0.0;
  evaluate_dynamics(s, w, t0, q0, qd0);
  solve(s, w, t0, q0, acc, lw, o.stabilization);
  w.mass_scale = w.llt_M.matrixLLT().diagonal().cwiseAbs2().maxCoeff();
  // a q̈ that is not finite at the start is the model's, not the step's: said so here, before
  // the first step would call it a divergence
  for (Eigen::Index i = 0; i < n; ++i) {
    if (!std::isfinite(acc[i])) {
      throw Error(fmt::format(
          "the acceleration of '{}' is {} at the start ({}): a term of the model is not finite "
          "there (a division by zero, or a number outside a function's real domain: a negative "
          "number to a non-integer power, sqrt or log of a negative number, asin or acos beyond "
          "[-1, 1]); check the model's expressions and parameters at the initial state",
          s.q_of_v[static_cast<std::size_t>(i)] >= 0
              ? s.coord_names[static_cast<std::size_t>(s.q_of_v[static_cast<std::size_t>(i)])]
              : s.velocity_names[static_cast<std::size_t>(i)],
          std::isnan(acc[i]) ? "NaN" : fmt::format("{}", acc[i]),
          s.state_text(t0, q0)));
    }
  }

  integrate::Problem problem;
  problem.y0.resize(nq + n);
  problem.y0 << q0, qd0;
  problem.t0 = t0;
  problem.t_end = o.t_end;
  problem.n_position = s.nq;
  problem.owner = "";
  for (const auto& c : s.coord_names) problem.names.push_back(c);
  for (const auto& c : s.velocity_names) problem.names.push_back(c);
  const double alpha = o.stabilization;
  // a ball's quaternion moves by q̇ = ½ q ⊗ (0, ω); the equations take any q ≠ 0 as the
  // rotation q/|q| (recursive.cpp), so its drift off the unit sphere changes nothing
  problem.rhs = [&, alpha](double t, const Eigen::VectorXd& y, Eigen::VectorXd& dydt) {
    qv = y.head(nq);
    qdv = y.tail(n);
    // a Runge–Kutta stage can blow up inside a step (the step's end is checked by the march)
    if (!y.allFinite()) [[unlikely]] {
      std::string velocities;
      for (Eigen::Index i = 0; i < n; ++i) {
        velocities += fmt::format("{}{} = {}", i ? ", " : "", s.velocity_names[static_cast<std::size_t>(i)], qdv[i]);
      }
      throw Error(fmt::format("non-finite state inside a step at {}, q̇ = ({}); the motion diverged: "
                              "reduce the step or check the model",
                              s.state_text(t, qv), velocities));
    }
    evaluate_dynamics(s, w, t, qv, qdv);
    solve(s, w, t, qv, acc, lw, alpha);
    if (s.balls.empty()) {
      dydt.head(n) = qdv;
    } else {
      s.coordinate_rates(qv.data(), qdv.data(), dydt.data());
    }
    dydt.tail(n) = acc;
  };
  const integrate::Solution sol = integrate::integrate(
      problem, integrate::Options{.method = o.method, .dt = o.dt, .rtol = o.tolerance,
                                  .atol = o.tolerance, .output_dt = o.output_dt, .control = o.control});

  Trajectory tr;
  tr.coordinate_names = s.coord_names;
  tr.velocity_names = s.velocity_names;
  tr.constraint_names = s.constraint_names;
  tr.cyclic_names = s.cyclic_names;
  const auto rows = static_cast<Eigen::Index>(sol.t.size());
  tr.t.resize(rows);
  tr.q.resize(rows, nq);
  tr.q_dot.resize(rows, n);
  tr.lambda.resize(rows, s.m);
  tr.energy.resize(rows);
  tr.jacobi.resize(rows);
  tr.cyclic_momenta.resize(rows, static_cast<Eigen::Index>(s.cyclic_index.size()));
  tr.residual.resize(rows);
  tr.velocity_residual.resize(rows);
  tr.velocity_constraint_names = s.velocity_constraint_names;
  tr.mu.resize(rows, s.r);
  tr.velocity_constraint_residual.resize(rows);
  for (Eigen::Index k = 0; k < rows; ++k) {
    const double t = sol.t[static_cast<std::size_t>(k)];
    const Eigen::VectorXd& y = sol.y[static_cast<std::size_t>(k)];
    qv = y.head(nq);
    qdv = y.tail(n);
    for (const Impl::Ball& b : s.balls) qv.segment(static_cast<Eigen::Index>(b.q), 4).normalize();
    tr.t[k] = t;
    tr.q.row(k) = qv;
    tr.q_dot.row(k) = qdv;
    evaluate_dynamics(s, w, t, qv, qdv);
    tr.residual[k] = s.m ? w.gw.head(s.m).lpNorm<Eigen::Infinity>() : 0.0;
    tr.velocity_residual[k] = s.m ? w.cw.head(s.m).lpNorm<Eigen::Infinity>() : 0.0;
    tr.velocity_constraint_residual[k] = s.r ? w.cw.tail(s.r).lpNorm<Eigen::Infinity>() : 0.0;
    solve(s, w, t, qv, acc, lw, alpha);
    if (s.m) tr.lambda.row(k) = lw.head(s.m);
    if (s.r) tr.mu.row(k) = lw.tail(s.r);
    evaluate_diagnostics(s, w, t, qv, qdv);
    tr.energy[k] = w.diag_out[0];
    tr.jacobi[k] = w.diag_out[1];
    for (Eigen::Index c = 0; c < tr.cyclic_momenta.cols(); ++c) {
      tr.cyclic_momenta(k, c) = w.diag_out[static_cast<std::size_t>(2 + c)];
    }
  }
  tr.steps = sol.steps;
  tr.rhs_evaluations = sol.rhs_evaluations;
  return tr;
}

}  // namespace rigid::lagrange
