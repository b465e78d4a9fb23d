#include "cmd_demo.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <vector>

#include <fmt/core.h>

#include "rigid/body/free_body_exact.hpp"
#include "rigid/body/free_body_integrators.hpp"
#include "rigid/common/format.hpp"
#include "rigid/lie.hpp"
#include "rigid/version.hpp"

namespace rigid::cli {
namespace {

// Times in `t` where `f` changes sign, refined by linear interpolation between samples.
std::vector<double> sign_changes(const std::vector<double>& t, const std::vector<double>& f) {
  std::vector<double> out;
  for (std::size_t i = 1; i < t.size(); ++i) {
    if ((f[i - 1] < 0) != (f[i] < 0)) {
      out.push_back(t[i - 1] + (t[i] - t[i - 1]) * f[i - 1] / (f[i - 1] - f[i]));
    }
  }
  return out;
}

// The tennis-racket (Dzhanibekov) flips: a 4th-order splitting run against the exact
// elliptic-function solution, with the conserved quantities.
void tennis_racket_tour() {
  const Eigen::Vector3d I_B(1, 2, 3);
  const Eigen::Vector3d w0_B(0.01, 1, 0.01);
  const body::FreeBodyExact exact(I_B, w0_B);
  const double t_end = 60, h = 1e-2;
  std::vector<double> times;
  for (int i = 1; i <= 6000; ++i) times.push_back(i * t_end / 6000);
  body::FreeBodyState initial;
  initial.w_B = w0_B;
  const auto run =
      body::simulate_free_body(body::FreeBodyMethod::kSplitting4, I_B, initial, h, times);

  std::vector<double> wy_sim, wy_exact;
  double max_err = 0;
  for (std::size_t i = 0; i < times.size(); ++i) {
    const Eigen::Vector3d we = exact.omega_body(times[i]);
    wy_sim.push_back(run.states[i].w_B.y());
    wy_exact.push_back(we.y());
    max_err = std::max(max_err, (run.states[i].w_B - we).cwiseAbs().maxCoeff());
  }
  const auto flips_sim = sign_changes(times, wy_sim);
  const auto flips_exact = sign_changes(times, wy_exact);

  const auto d0 = body::diagnose(I_B, initial);
  const auto& d1 = run.diagnostics.back();
  fmt::print("\nTennis racket: I = (1, 2, 3) kg m^2, w0 = (0.01, 1, 0.01) rad/s, spun about "
             "the middle axis.\n");
  fmt::print(
      "  period of w(t) from Jacobi elliptic functions: 4K(k)/lambda = {:.6f} s (k = {:.6f})\n",
      exact.period(), exact.modulus());
  fmt::print("  flips (w_y changes sign), splitting4 with h = {} s vs exact:\n", h);
  for (std::size_t i = 0; i < std::min(flips_sim.size(), flips_exact.size()); ++i) {
    fmt::print("    t = {:9.5f} s   exact {:9.5f} s\n", flips_sim[i], flips_exact[i]);
  }
  fmt::print("  max |w - w_exact| over {} s: {:.2e} rad/s\n", t_end, max_err);
  fmt::print("  energy drift {:.2e} J, |L| drift {:.2e} kg m^2/s, |R^T R - 1| = {:.1e}\n",
             d1.energy - d0.energy, d1.L_W.norm() - d0.L_W.norm(), d1.orthonormality_error);
}

}  // namespace

void run_demo() {
  using std::numbers::pi;
  fmt::print("rigid {}: a short tour (every number below is computed now).\n\n",
             RIGID_VERSION_STRING);

  const SO3d Rz = SO3d::from_axis_angle(Eigen::Vector3d(0, 0, 1), pi / 2);
  const SO3d Rx = SO3d::from_axis_angle(Eigen::Vector3d(1, 0, 0), pi / 2);
  fmt::print("Rz = 90 deg about z, Rx = 90 deg about x.\n");
  fmt::print("  Rz * (1, 0, 0)         = {}\n", to_string((Rz * Eigen::Vector3d(1, 0, 0)).transpose()));
  const SO3d A = Rz * Rx, B = Rx * Rz;
  fmt::print("  Rz*Rx rotation vector  = {}\n", to_string(A.log().transpose()));
  fmt::print("  Rx*Rz rotation vector  = {}   (rotations do not commute)\n", to_string(B.log().transpose()));
  fmt::print("  angle(Rz*Rx)           = {} deg (120 deg: the cube's body-diagonal turn)\n\n",
             A.angle() * 180 / pi);

  const double t = pi - 1e-9;
  const Eigen::Vector3d w = Eigen::Vector3d(1, 2, 2) / 3.0 * t;
  const double err = (SO3d::exp(w).log() - w).norm();
  fmt::print("exp/log round trip at angle pi - 1e-9: |log(exp(w)) - w| = {:.3g}\n", err);

  const EulerConvention zyx = EulerConvention::parse("ZYX", true);
  const Eigen::Vector3d e = to_euler(A, zyx) * 180 / pi;
  fmt::print("Rz*Rx as intrinsic ZYX Euler angles (deg): {}\n", to_string(e.transpose()));

  const SO3d mid = Rz.interpolate(Rx, 0.5);
  fmt::print("Geodesic midpoint of Rz and Rx: angle from each = {} deg and {} deg\n",
             (Rz.inverse() * mid).angle() * 180 / pi, (Rx.inverse() * mid).angle() * 180 / pi);
  tennis_racket_tour();
  fmt::print("\nTry: rigid rotation --euler 30,20,10 --convention ZYX --unit deg\n"
             "     rigid inertia cone --radius 0.3 --height 1.2 --mass 2.5 --format urdf\n");
}

}  // namespace rigid::cli
