#pragma once
// Included by main.cpp only (the one translation unit that sees CLI11).
#include <memory>

#include "cmd_rotation.hpp"

inline void add_rotation_command(CLI::App& app) {
  auto opts = std::make_shared<rigid::cli::RotationOptions>();
  auto* cmd = app.add_subcommand(
      "rotation",
      "Convert a rotation between axis-angle, quaternion, matrix, rotation vector and Euler angles");
  auto* in = cmd->add_option_group("input", "the rotation, in exactly one form");
  in->add_option("--axis-angle", opts->axis_angle, "x,y,z,angle (axis need not be unit; angle in --unit)");
  in->add_option("--quaternion", opts->quaternion, "four numbers in --order (normalised)");
  in->add_option("--matrix", opts->matrix, "nine numbers, row-major; must be a rotation within 1e-9");
  in->add_option("--euler", opts->euler, "three angles in --unit for --convention");
  in->add_option("--rotvec", opts->rotvec, "x,y,z: axis times angle, radians");
  in->require_option(1);
  cmd->add_option("--unit", opts->unit, "angle unit for input and output: deg or rad")->default_str("deg");
  cmd->add_option("--order", opts->order, "quaternion order: wxyz or xyzw")->default_str("wxyz");
  cmd->add_option("--convention", opts->convention,
                  "Euler axis sequence: XYZ XZY YXZ YZX ZXY ZYX XYX XZX YXY YZY ZXZ ZYZ")
      ->default_str("ZYX");
  cmd->add_flag("--extrinsic", opts->extrinsic, "Euler axes fixed in space (default: intrinsic, moving)");
  cmd->add_option("--out-convention", opts->out_convention, "Euler sequence of the output (default: --convention)");
  cmd->callback([opts] { rigid::cli::run_rotation(*opts); });
}
