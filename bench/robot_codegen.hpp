#pragma once

// The flat exports of the robot benchmark's models, each compiled in its own translation unit
// (robot_codegen_<model>.cpp: the exported functions live at global scope) and called here
// through these out-of-line wrappers, as a program that links the exported code calls it.

namespace rigid_bench {

struct Codegen {
  int nv;
  void (*mass_matrix)(const double* q, double* M);
  void (*inverse_dynamics)(const double* q, const double* v, const double* a, double* tau);
  void (*forward_dynamics)(const double* q, const double* v, const double* tau, double* a);
  void (*inverse_dynamics_derivatives)(const double* q, const double* v, const double* a,
                                       double* dq, double* dv, double* da);
  void (*forward_dynamics_derivatives)(const double* q, const double* v, const double* tau,
                                       double* a, double* dq, double* dv, double* dtau);
};

/// examples/arm7.urdf
const Codegen& codegen_arm7();
/// MuJoCo's humanoid pinned at its root (21 hinges); no derivatives (nullptr)
const Codegen& codegen_humanoid_pinned();
/// MuJoCo's humanoid on its free root (nq = 28, nv = 27); the derivatives along the root's tangent
const Codegen& codegen_humanoid_free();

}  // namespace rigid_bench
