#pragma once

/// The stiff body: spring networks of point masses converging to a rigid body as k → ∞.
#include "rigid/spring/network.hpp"
