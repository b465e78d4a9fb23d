// The flat export of humanoid_pinned (generated at build time by rigid_robot_codegen_gen), compiled with
// the project's flags, behind the wrappers of robot_codegen.hpp.
#include "robot_codegen.hpp"

#include "humanoid_pinned_flat.hpp"

namespace rigid_bench {
namespace {

void M(const double* q, double* out) { mass_matrix(q, out); }
void id(const double* q, const double* v, const double* a, double* tau) {
  inverse_dynamics(q, v, a, tau);
}
void fd(const double* q, const double* v, const double* tau, double* a) {
  forward_dynamics(q, v, tau, a);
}

}  // namespace

const Codegen& codegen_humanoid_pinned() {
  static const Codegen c{nv, M, id, fd, nullptr, nullptr};
  return c;
}

}  // namespace rigid_bench
