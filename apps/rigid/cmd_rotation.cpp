#include "cmd_rotation.hpp"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <numbers>
#include <string_view>
#include <vector>

#include <fmt/core.h>

#include "cli_error.hpp"
#include "rigid/common/did_you_mean.hpp"
#include "rigid/common/error.hpp"
#include "rigid/lie.hpp"

namespace rigid::cli {

namespace {

std::vector<double> parse_numbers(std::string_view text, std::size_t count, std::string_view option) {
  std::vector<double> out;
  std::size_t start = 0;
  for (;;) {
    const std::size_t end = std::min(text.find(',', start), text.size());
    std::string_view item = text.substr(start, end - start);
    while (!item.empty() && item.front() == ' ') item.remove_prefix(1);
    while (!item.empty() && item.back() == ' ') item.remove_suffix(1);
    double v = 0;
    const auto [ptr, ec] = std::from_chars(item.data(), item.data() + item.size(), v);
    CLI_USAGE_REQUIRE(ec == std::errc() && ptr == item.data() + item.size() && !item.empty(),
                      "{}: '{}' is not a number", option, item);
    CLI_USAGE_REQUIRE(std::isfinite(v), "{}: value {} is not finite", option, item);
    out.push_back(v);
    if (end == text.size()) break;
    start = end + 1;
  }
  CLI_USAGE_REQUIRE(out.size() == count, "{} takes {} comma-separated numbers, got {} in '{}'", option,
                    count, out.size(), text);
  return out;
}

// The largest angle taken (rad): a million turns. An angle is reduced modulo 2π in double
// precision; at 2π·10⁶ rad its rounding is below 1e-9 rad, beyond it the rotation it names is
// lost to rounding (at 1e308 deg nothing is left, and the conversions gave NaN).
constexpr double kMaxAngle = 2 * std::numbers::pi * 1e6;

void require_angle(double angle_rad, std::string_view option, double given, std::string_view unit) {
  CLI_REQUIRE(std::abs(angle_rad) <= kMaxAngle,
              "{}: the angle {} {} is more than a million turns (|angle| ≤ {:.6g} rad); its "
              "rotation is lost to rounding: reduce it modulo 360 deg (2π rad) first",
              option, given, unit, kMaxAngle);
}

std::string list(const Eigen::VectorXd& v) {
  std::string s = "[";
  for (Eigen::Index i = 0; i < v.size(); ++i) s += fmt::format("{}{}", i ? ", " : "", v(i) + 0.0);  // + 0.0 prints −0 as 0
  return s + "]";
}

// An Euler sequence named by an option: the library's refusal (with its list and its guess),
// as a usage error.
EulerConvention parse_convention(const std::string& sequence, bool intrinsic) {
  try {
    return EulerConvention::parse(sequence, intrinsic);
  } catch (const UsageError&) {
    throw;
  } catch (const Error& e) {
    throw UsageError(e.what());
  }
}

}  // namespace

void run_rotation(const RotationOptions& o) {
  CLI_USAGE_REQUIRE(o.unit == "deg" || o.unit == "rad", "--unit is '{}', expected deg or rad{}", o.unit,
                    did_you_mean_hint(o.unit, {"deg", "rad"}));
  CLI_USAGE_REQUIRE(o.order == "wxyz" || o.order == "xyzw", "--order is '{}', expected wxyz or xyzw{}",
                    o.order, did_you_mean_hint(o.order, {"wxyz", "xyzw"}));
  const double to_rad = o.unit == "deg" ? std::numbers::pi / 180.0 : 1.0;
  const EulerConvention conv = parse_convention(o.convention, !o.extrinsic);
  const EulerConvention out_conv =
      o.out_convention.empty() ? conv : parse_convention(o.out_convention, !o.extrinsic);

  SO3d R = SO3d::identity();
  if (!o.axis_angle.empty()) {
    const auto v = parse_numbers(o.axis_angle, 4, "--axis-angle");
    require_angle(v[3] * to_rad, "--axis-angle", v[3], o.unit);
    // the axis is normalised: scaled first by its largest component, so that its norm is finite
    const double scale = std::max({std::abs(v[0]), std::abs(v[1]), std::abs(v[2])});
    R = SO3d::from_axis_angle(Eigen::Vector3d(v[0], v[1], v[2]) / (scale > 0 ? scale : 1.0), v[3] * to_rad);
  } else if (!o.quaternion.empty()) {
    auto v = parse_numbers(o.quaternion, 4, "--quaternion");
    // normalised: scaled first by its largest component, so that its norm is finite
    const double scale = std::max({std::abs(v[0]), std::abs(v[1]), std::abs(v[2]), std::abs(v[3])});
    for (double& x : v) x /= scale > 0 ? scale : 1.0;  // (0, 0, 0, 0) is refused by SO3d
    R = o.order == "wxyz" ? SO3d::from_quaternion(v[0], v[1], v[2], v[3])
                          : SO3d::from_quaternion(v[3], v[0], v[1], v[2]);
  } else if (!o.matrix.empty()) {
    const auto v = parse_numbers(o.matrix, 9, "--matrix");
    Eigen::Matrix3d M;
    M << v[0], v[1], v[2], v[3], v[4], v[5], v[6], v[7], v[8];
    R = SO3d::from_matrix(M);
  } else if (!o.euler.empty()) {
    const auto v = parse_numbers(o.euler, 3, "--euler");
    for (double a : v) require_angle(a * to_rad, "--euler", a, o.unit);
    R = from_euler(Eigen::Vector3d(v[0], v[1], v[2]) * to_rad, conv);
  } else {
    const auto v = parse_numbers(o.rotvec, 3, "--rotvec");
    for (double a : v) require_angle(a, "--rotvec", a, "rad");
    require_angle(Eigen::Vector3d(v[0], v[1], v[2]).norm(), "--rotvec", Eigen::Vector3d(v[0], v[1], v[2]).norm(), "rad");
    R = SO3d::exp(Eigen::Vector3d(v[0], v[1], v[2]));
  }

  // every number printed is finite, or nothing is printed
  CLI_REQUIRE(R.matrix().allFinite(), "the rotation could not be computed from the input (a non-finite "
              "result); expected an input of moderate magnitude");
  const Eigen::Vector3d w = R.log();
  const double angle = w.norm();
  const Eigen::Vector3d axis = angle > 0 ? Eigen::Vector3d(w / angle) : Eigen::Vector3d(1, 0, 0);
  fmt::print("axis-angle: axis {}, angle {} {}{}\n", list(axis), angle / to_rad, o.unit,
             angle > 0 ? "" : " (identity: axis arbitrary)");
  fmt::print("rotation vector (rad): {}\n", list(w));
  const Eigen::Vector4d q = R.quaternion();
  // Sign chosen with w ≥ 0 (q and −q are the same rotation).
  const Eigen::Vector4d qp = q(0) < 0 ? Eigen::Vector4d(-q) : q;
  if (o.order == "wxyz") {
    fmt::print("quaternion (w, x, y, z): {}\n", list(qp));
  } else {
    fmt::print("quaternion (x, y, z, w): {}\n", list(Eigen::Vector4d(qp(1), qp(2), qp(3), qp(0))));
  }
  const Eigen::Matrix3d M = R.matrix();
  fmt::print("matrix:\n");
  for (int i = 0; i < 3; ++i) fmt::print("  {}\n", list(M.row(i).transpose()));
  const Eigen::Vector3d e = to_euler(R, out_conv) / to_rad;
  fmt::print("euler {} {} ({}): {}\n", out_conv.name(), out_conv.intrinsic ? "intrinsic" : "extrinsic", o.unit,
             list(e));
}

}  // namespace rigid::cli
