// The flat export of arm7 (generated at build time by rigid_robot_codegen_gen), compiled with
// the project's flags, behind the wrappers of robot_codegen.hpp.
#include "robot_codegen.hpp"

#include "arm7_flat.hpp"

namespace rigid_bench {
namespace {

void M(const double* q, double* out) { mass_matrix(q, out); }
void id(const double* q, const double* v, const double* a, double* tau) {
  inverse_dynamics(q, v, a, tau);
}
void fd(const double* q, const double* v, const double* tau, double* a) {
  forward_dynamics(q, v, tau, a);
}
void id_derivatives(const double* q, const double* v, const double* a, double* dq, double* dv,
                    double* da) {
  inverse_dynamics_derivatives(q, v, a, dq, dv, da);
}
void fd_derivatives(const double* q, const double* v, const double* tau, double* a, double* dq,
                    double* dv, double* dtau) {
  forward_dynamics_derivatives(q, v, tau, a, dq, dv, dtau);
}

}  // namespace

const Codegen& codegen_arm7() {
  static const Codegen c{nv, M, id, fd, id_derivatives, fd_derivatives};
  return c;
}

}  // namespace rigid_bench
