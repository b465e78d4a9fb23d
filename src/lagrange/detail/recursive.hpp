#pragma once

// M(q) and f(q, q̇) of a tree of bodies by the tree's recursions in symbols: forward
// kinematics link by link, the composite-rigid-body algorithm for M and recursive
// Newton–Euler for the bias forces (Featherstone, "Rigid Body Dynamics Algorithms", 2008,
// ch. 5–6), every spatial quantity in world coordinates about the world origin. Each
// quantity of a link is a named intermediate (System::Impl::aux) defined by a short
// expression of its parent's, so the equations grow linearly with the depth of the tree
// where the expanded Lagrangian grows exponentially.

#include <set>
#include <string>
#include <utility>
#include <vector>

#include <Eigen/Core>
#include <ginac/ginac.h>

#include "symbolic.hpp"
#include "system_impl.hpp"
#include "tree_body.hpp"

namespace rigid::lagrange::detail {

/// What the recursions give, in terms of the intermediates they appended to s.aux/aux_def.
struct TreeEquations {
  std::vector<GiNaC::ex> M;          ///< n × n, row-major
  std::vector<GiNaC::ex> inertial;   ///< −C(q, q̇) q̇: Coriolis and centrifugal forces
  std::vector<GiNaC::ex> gravity;    ///< the generalized forces of gravity
  GiNaC::ex T, V;                    ///< kinetic energy; potential of gravity
  std::vector<std::pair<Vec3, Mat3>> poses;  ///< per body: p_WB, R_WB
};

/// The inverse dynamics of the tree, τ = M q̈ − (Coriolis, centrifugal and gravity forces), by
/// recursive Newton–Euler in each body's own coordinates (constant inertias, one rotation per
/// joint: fewer operations than the world coordinates of tree_equations), for the exported
/// dynamics. Its intermediates are its own (not in s.aux).
struct TreeInverseDynamics {
  std::vector<GiNaC::symbol> aux;
  std::vector<GiNaC::ex> defs;
  std::vector<GiNaC::ex> tau;  ///< per coordinate, in q, q̇, q̈, the parameters and aux
};
[[nodiscard]] TreeInverseDynamics tree_inverse_dynamics(const System::Impl& s,
                                                        const std::vector<TreeBody>& bodies,
                                                        const Vec3& gravity,
                                                        const std::set<std::string>& taken);

/// ∂τ/∂q and ∂τ/∂q̇ of the tree's inverse dynamics (τ of tree_inverse_dynamics) in closed
/// form (recursive.cpp: the derivatives of Newton–Euler in world coordinates, an O(n) pass
/// and a dot product per pair of joints on one path), for the exported derivatives. Its
/// intermediates are its own, named apart from `taken`. A ball's columns of ∂τ/∂q are along
/// its tangent: q ⊗ exp(δθ), δθ in its body's frame (MuJoCo's convention), one per velocity.
struct TreeDerivatives {
  std::vector<GiNaC::symbol> aux;
  std::vector<GiNaC::ex> defs;
  /// n × 2n (n velocities), row-major: ∂τ_i/∂q_j at [i·2n + j] (∂τ_i/∂δθ_k for a ball's
  /// column k), ∂τ_i/∂q̇_j at [i·2n + n + j]
  std::vector<GiNaC::ex> d;
  /// the tree's M (n × n) and τ at q̈ = 0 (= −bias, gravity included) from the same
  /// intermediates, so that code holding the derivatives computes no second recursion
  std::vector<GiNaC::ex> M, tau_rest;
};
[[nodiscard]] TreeDerivatives tree_inverse_dynamics_derivatives(
    const System::Impl& s, const std::vector<TreeBody>& bodies, const Vec3& gravity,
    const std::set<std::string>& taken);

/// Derives the tree's M, bias forces and energies; `taken` holds the names the intermediates
/// must not take (the system's own symbols).
[[nodiscard]] TreeEquations tree_equations(System::Impl& s, const std::vector<TreeBody>& bodies,
                                           const Vec3& gravity, const std::set<std::string>& taken);

}  // namespace rigid::lagrange::detail
