#include "cmd_demo.hpp"

#include <algorithm>
#include <filesystem>
#include <cmath>
#include <numbers>
#include <vector>

#include <fmt/format.h>

#include "rigid/body/free_body_exact.hpp"
#include "cli_error.hpp"
#include "rigid/common/error.hpp"
#include "rigid/io/atomic_file.hpp"
#include "rigid/io/run_output.hpp"
#include "rigid/io/table.hpp"
#include "rigid/report/report.hpp"
#include "rigid/scene/model.hpp"
#include "rigid/scene/scene.hpp"
#include "scene_output.hpp"
#include "rigid/common/format.hpp"
#include "rigid/lie.hpp"
#include "rigid/version.hpp"

namespace rigid::cli {
namespace {

namespace fs = std::filesystem;

// Where the example scenes are: next to an installed rigid (<prefix>/bin/rigid →
// <prefix>/share/rigid/examples, as `cmake --install` lays them out), else, for the rigid of a
// build directory, the source tree it was built from. An installed rigid never reads the source
// tree (which may have moved on, or be gone).
fs::path examples_directory() {
  std::error_code ec;
  const fs::path exe = fs::read_symlink("/proc/self/exe", ec);
  const fs::path bin = ec ? fs::path() : exe.parent_path();
  const fs::path installed = bin.empty() ? fs::path("<prefix>/bin") / RIGID_EXAMPLES_FROM_BIN
                                         : (bin / RIGID_EXAMPLES_FROM_BIN).lexically_normal();
  if (!bin.empty() && fs::is_directory(installed, ec)) return installed;
  const fs::path build_bin = RIGID_BUILD_BIN_DIR;
  const bool from_build = !bin.empty() && fs::equivalent(bin, build_bin, ec);
  const fs::path source = RIGID_SOURCE_EXAMPLES;
  if (from_build && fs::is_directory(source, ec)) return source;
  throw Error(fmt::format(
      "no example scenes for rigid demo: not in '{}' (where `cmake --install` puts them for {}/rigid), nor in "
      "'{}' ({}); install rigid with `cmake --install BUILD_DIR --prefix PREFIX` and run PREFIX/bin/rigid, or "
      "run the rigid of the build directory",
      installed.string(), bin.empty() ? std::string("<prefix>/bin") : bin.string(), source.string(),
      from_build ? std::string("the source tree this rigid was built from")
                 : fmt::format("the source tree's, used only by the rigid of its build directory {}",
                               build_bin.string())));
}

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

// The demo's scene: the tennis-racket (Dzhanibekov) effect. Written next to its outputs
// so that `rigid run rigid-demo/tennis_racket.toml` repeats it.
constexpr const char* kRacketScene = R"(# The tennis-racket (Dzhanibekov) effect: a free body spun about its middle
# principal axis flips over every half period of its angular velocity.
# Principal moments I = (1, 2, 3) kg m^2, body angular velocity w0 = (0.01, 1, 0.01) rad/s.
[[bodies]]
name = "racket"
free = true
inertia = {mass = 0.35, ixx = 1, iyy = 2, izz = 3}
angular_velocity = [0.01, 1, 0.01]

[simulation]
t_end = 60.0
integrator = "splitting4"
dt = 0.01
output_dt = 0.01

[output]
directory = "rigid-demo"
formats = ["csv", "npy", "json"]
)";

double diagnostic(const scene::RunSummary& s, const std::string& name) {
  for (const auto& [n, v] : s.diagnostics) {
    if (n == name) return v;
  }
  CLI_THROW("the run has no diagnostic '{}'", name);
}

// Runs the embedded racket scene into ./rigid-demo/ and says what to look at: the flips
// against the exact elliptic-function solution, and the conserved quantities.
void tennis_racket_scene(bool report) {
  const std::filesystem::path dir = "rigid-demo";
  std::filesystem::create_directories(dir);
  const std::filesystem::path scene_file = dir / "tennis_racket.toml";
  io::write_file_atomically(scene_file, kRacketScene);
  const scene::Model model(scene::parse_scene(kRacketScene, scene_file));
  const scene::RunResult result = model.run();
  const io::OutputFormat formats[] = {io::OutputFormat::kCsv, io::OutputFormat::kNpy, io::OutputFormat::kJson};
  // the page of the run (when this build has it), in the same set as the other files
  std::vector<io::ExtraFile> extra;
  const bool page = report && report::available();
  if (page) extra.push_back({std::string(io::kReportFileName), report::report_page(model, result)});
  const auto written = io::write_run(dir, result, formats, extra);

  const io::Table& tr = result.trajectory;
  const std::size_t ct = tr.column("t");
  const std::size_t cw[3] = {tr.column("racket.wx"), tr.column("racket.wy"), tr.column("racket.wz")};
  const Eigen::Vector3d I_B(1, 2, 3);
  const Eigen::Vector3d w0_B(0.01, 1, 0.01);
  const body::FreeBodyExact exact(I_B, w0_B);
  std::vector<double> times, wy_sim, wy_exact;
  double max_err = 0;
  for (std::size_t k = 0; k < tr.rows(); ++k) {
    const double t = tr(k, ct);
    const Eigen::Vector3d we = exact.omega_body(t);
    const Eigen::Vector3d ws(tr(k, cw[0]), tr(k, cw[1]), tr(k, cw[2]));
    times.push_back(t);
    wy_sim.push_back(ws.y());
    wy_exact.push_back(we.y());
    max_err = std::max(max_err, (ws - we).cwiseAbs().maxCoeff());
  }
  const auto flips_sim = sign_changes(times, wy_sim);
  const auto flips_exact = sign_changes(times, wy_exact);
  const scene::RunSummary& s = result.summary;
  fmt::print("Tennis racket: I = (1, 2, 3) kg m^2, w0 = (0.01, 1, 0.01) rad/s, spun about "
             "the middle axis.\n");
  fmt::print("  scene {}: {} with h = {} s to t = {} s, {} steps in {:.3f} s\n", scene_file.string(),
             s.integrator, s.dt, s.t_end, s.steps, s.wall_seconds);
  fmt::print(
      "  period of w(t) from Jacobi elliptic functions: 4K(k)/lambda = {:.6f} s (k = {:.6f})\n",
      exact.period(), exact.modulus());
  fmt::print("  flips (w_y changes sign), simulated vs exact:\n");
  for (std::size_t i = 0; i < std::min(flips_sim.size(), flips_exact.size()); ++i) {
    fmt::print("    t = {:9.5f} s   exact {:9.5f} s\n", flips_sim[i], flips_exact[i]);
  }
  fmt::print("  max |w - w_exact| over {} s: {:.2e} rad/s\n", s.t_end, max_err);
  fmt::print("  energy drift {:.2e} J, |L| drift {:.2e} kg m^2/s, |R^T R - 1| = {:.1e}\n",
             diagnostic(s, "energy_max_change"), diagnostic(s, "racket.L_norm_max_change"),
             diagnostic(s, "racket.orthonormality_max"));
  std::vector<std::string> names;
  for (const auto& p : written) names.push_back(p.string());
  fmt::print("  wrote {}\n", fmt::join(names, ", "));
  if (page) {
    fmt::print("  report: {} (open it in a browser: the racket turning, the plots, the equations)\n",
               (std::filesystem::absolute(dir) / io::kReportFileName).string());
  } else if (report) {
    fmt::print("  (no report page: this rigid was built without it, RIGID_REPORT=OFF)\n");
  }
  fmt::print("  look at: racket.wy (flips sign every half period), racket.Lx/Ly/Lz (the world\n"
             "  angular momentum: constant), energy (constant), racket.qw..qz (the orientation:\n"
             "  a half turn at each flip)\n");
}

}  // namespace

void run_demo(bool report) {
  using std::numbers::pi;
  // before anything is written: the commands the tour ends with run these files
  const fs::path examples = examples_directory();
  fmt::print("rigid {}: a short tour (every number below is computed now).\n\n",
             RIGID_VERSION_STRING);
  tennis_racket_scene(report);
  fmt::print("\nRotations:\n");

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
  fmt::print("\nExample scenes: {}\n", examples.string());
  fmt::print("Try: rigid run {} -o out/atwood && rigid eom {}\n"
             "     rigid rotation --euler 30,20,10 --convention ZYX --unit deg\n"
             "     rigid inertia cone --radius 0.3 --height 1.2 --mass 2.5 --format urdf\n",
             (examples / "atwood.toml").string(), (examples / "heavy_top.toml").string());
}

}  // namespace rigid::cli
