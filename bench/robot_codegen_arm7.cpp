// The flat export of arm7 (generated at build time by rigid_robot_codegen_gen), compiled with
// the project's flags, behind the wrappers of robot_codegen.hpp.
#include <cmath>

// in an unnamed namespace: each model's export declares the same names, which would otherwise
// be one inline function (or variable) of the program with different definitions
namespace {
#include "arm7_flat.hpp"
}  // namespace

#define RIGID_CODEGEN_NAME codegen_arm7
#define RIGID_CODEGEN_DERIVATIVES 1
#include "robot_codegen_wrappers.inc"
