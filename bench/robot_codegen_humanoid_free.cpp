// The flat export of MuJoCo's humanoid as shipped, on its free root (nq = 28, nv = 27; generated
// at build time by rigid_robot_codegen_gen), compiled with the project's flags, behind
// robot_codegen.hpp's wrappers.
#include <cmath>

// in an unnamed namespace: each model's export declares the same names, which would otherwise
// be one inline function (or variable) of the program with different definitions
namespace {
#include "humanoid_free_flat.hpp"
}  // namespace

#define RIGID_CODEGEN_NAME codegen_humanoid_free
#define RIGID_CODEGEN_DERIVATIVES 1
#include "robot_codegen_wrappers.inc"
