#pragma once

/// Lie groups: SO3, SE3 (templated on the scalar) and O(n) membership / projection.
#include "rigid/lie/euler.hpp"
#include "rigid/lie/orthogonal.hpp"
#include "rigid/lie/se3.hpp"
#include "rigid/lie/so3.hpp"
