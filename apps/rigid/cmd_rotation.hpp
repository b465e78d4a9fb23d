#pragma once

#include <string>

namespace rigid::cli {

/// Options of `rigid rotation`: exactly one input form; every form is printed.
struct RotationOptions {
  std::string axis_angle;   ///< "x,y,z,angle"
  std::string quaternion;   ///< four numbers in `order`
  std::string matrix;       ///< nine numbers, row-major
  std::string euler;        ///< three angles in `convention`
  std::string rotvec;       ///< "x,y,z": axis times angle (always radians)
  std::string unit = "deg";         ///< angle unit of input and output: deg or rad
  std::string order = "wxyz";       ///< quaternion order of input and output: wxyz or xyzw
  std::string convention = "ZYX";   ///< Euler axis sequence (one of the 12)
  bool extrinsic = false;           ///< Euler axes fixed in space instead of moving
  std::string out_convention;       ///< Euler sequence for output; empty = `convention`
};

/// `rigid rotation`: converts between axis-angle, quaternion, rotation matrix, rotation
/// vector and Euler angles. @throws rigid::Error on bad input.
void run_rotation(const RotationOptions& opts);

}  // namespace rigid::cli
