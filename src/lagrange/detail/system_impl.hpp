#pragma once

// The compiled model behind rigid::lagrange::System (system.cpp derives it, evaluate.cpp
// evaluates and simulates it) and the per-run scratch behind rigid::lagrange::Workspace.

#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include <Eigen/Cholesky>
#include <Eigen/Core>
#include <ginac/ginac.h>

#include "tape.hpp"
#include "tree_body.hpp"
#include "rigid/lagrange/system.hpp"

namespace rigid::lagrange {

struct System::Impl {
  // names: coord_names of q's nq entries, velocity_names of the n velocities (equal lists
  // but for the ball coordinates)
  std::vector<std::string> velocity_names;
  std::vector<std::string> coord_names, constraint_names, cyclic_names, param_names, body_names;
  std::vector<double> param_values;  // defaults; a Workspace copies them
  // symbols (GiNaC: used only while deriving and printing)
  // q (nq), the velocities qd and their rates qdd (n)
  std::vector<GiNaC::symbol> q, qd, qdd, params, lambda;
  // the ball coordinates: the index of their quaternion's w in q and of ω_x in the velocities
  struct Ball {
    std::size_t q = 0, v = 0;
    std::string name;
  };
  std::vector<Ball> balls;
  // per velocity: the entry of q it is the rate of, or −1 for a ball's ω
  std::vector<int> q_of_v;
  // per entry of q: dq/dt as an expression of q and the velocities (½ q ⊗ (0, ω) for a ball)
  std::vector<GiNaC::ex> q_rate;
  GiNaC::symbol t{"t"};
  Eigen::VectorXd q0, qd0;
  // derived expressions
  GiNaC::ex L, T, V, h;
  std::vector<GiNaC::ex> M, f, G, gamma, g, c, p;
  std::vector<GiNaC::ex> Q;  // generalized forces, per coordinate (printed apart from f)
  // a tree derived by its recursions (recursive.cpp): M, f, T, V and the poses use the named
  // intermediates aux, each defined by aux_def in terms of q, q̇, the parameters and the
  // intermediates before it; f_potential is the part of f from V (−∂V/∂q through them)
  std::vector<GiNaC::symbol> aux;
  std::vector<GiNaC::ex> aux_def;
  std::vector<GiNaC::ex> f_potential;
  // the tree itself (empty for an expanded derivation), its gravity, and its own M and bias
  // forces: the flat export derives the tree's inverse dynamics in body coordinates from them
  // when asked (recursive.cpp), τ = τ_tree + (M − tree_M) q̈ − (f − tree_bias)
  std::vector<detail::TreeBody> tree_bodies;
  detail::Vec3 tree_gravity{0, 0, 0};
  std::vector<GiNaC::ex> tree_M, tree_bias;
  // per coordinate: "m" when it is the amount of a slide joint, "rad" of a turn, else empty
  // (the printed equations' units; set from the joints as written)
  std::vector<std::string> joint_unit;
  std::vector<int> cyclic_index;
  bool verlet_ok = false;
  // compiled: inputs (q, q̇, t, parameters) for dyn, diag and pose; the parameters alone for
  // masses (per body: mass, COM (3), inertia xx yy zz xy xz yz)
  detail::Tape dyn, diag, pose, masses;
  int n = 0, m = 0;  // n: velocities (M is n × n); m: holonomic constraints
  int nq = 0;        // entries of q (n + one per ball)
  // velocity (nonholonomic) constraints (velocity_constraints.cpp): r rows A q̇ + a = 0; the
  // tape `vel` (inputs as dyn) gives A (r × n, row-major), η = −(Ȧ q̇ + ȧ) and c = A q̇ + a
  int r = 0;
  std::vector<std::string> velocity_constraint_names;
  std::vector<GiNaC::symbol> mu;
  std::vector<GiNaC::ex> A, a, eta, cv;
  detail::Tape vel;
  // the printed equations, made by the first equations() call (under the symbolic lock, which
  // guards this cache too) and returned by every later one
  mutable std::optional<Equations> equations;

  [[nodiscard]] std::size_t num_inputs() const {
    return static_cast<std::size_t>(nq + n + 1) + param_values.size();
  }
  [[nodiscard]] std::size_t parameter_index(const std::string& name) const;
  /// Throws naming the body if a parameter set makes a body's mass properties unphysical.
  void check_masses(const std::vector<double>& values, std::string_view context) const;
  [[nodiscard]] std::string state_text(double time, const Eigen::VectorXd& qv) const;
  /// Refuses, naming `what`, a system with ball coordinates (for what does not take them yet).
  void refuse_balls(std::string_view what) const;
  /// dq/dt (nq) at (q, v) into `out`.
  void coordinate_rates(const double* qv, const double* v, double* out) const;
};

namespace detail {
/// Defines the intermediates of `s` in `b` (before any output that uses them).
inline void define_intermediates(TapeBuilder& b, const System::Impl& s) {
  for (std::size_t k = 0; k < s.aux.size(); ++k) b.define(s.aux[k], s.aux_def[k]);
}
}  // namespace detail

struct Workspace::Impl {
  const System::Impl* owner = nullptr;
  std::vector<double> params;
  std::vector<double> in, out, diag_out, pose_out;
  std::vector<double> dyn_scratch, diag_scratch, pose_scratch;
  std::vector<double> vel_out, vel_scratch;  // velocity constraints; rows m.. of Gw, γ, ċ, g
  Eigen::MatrixXd Mw, Gw, Yw, Sw;
  Eigen::VectorXd fw, gammaw, cw, gw, Minv_f, rhs_m;
  Eigen::LLT<Eigen::MatrixXd> llt_M;
  Eigen::LDLT<Eigen::MatrixXd> ldlt_S;
  double mass_scale = 0.0;  // largest pivot of M at the start of a run
};

struct Workspace::Access {
  static Workspace::Impl* impl(Workspace& w) { return w.impl_.get(); }
};

}  // namespace rigid::lagrange
