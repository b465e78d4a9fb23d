#pragma once

/// Lie groups: SO2, SO3, SE2, SE3 (templated on the scalar), SOn and SEn (n chosen at run
/// time), Euler angles and O(n) membership / projection.
#include "rigid/lie/angle_limit.hpp"
#include "rigid/lie/euler.hpp"
#include "rigid/lie/orthogonal.hpp"
#include "rigid/lie/se2.hpp"
#include "rigid/lie/se3.hpp"
#include "rigid/lie/sen.hpp"
#include "rigid/lie/so2.hpp"
#include "rigid/lie/so3.hpp"
#include "rigid/lie/son.hpp"
