// The flat export of MuJoCo's pinned humanoid (generated at build time by
// rigid_robot_codegen_gen), compiled with the project's flags, behind robot_codegen.hpp's wrappers.
#include "humanoid_pinned_flat.hpp"

#define RIGID_CODEGEN_NAME codegen_humanoid_pinned
#define RIGID_CODEGEN_DERIVATIVES 0
#include "robot_codegen_wrappers.inc"
