#pragma once

/// Rigid-body dynamics on SO(3): Euler's equations, the exact free body, integrators.
#include "rigid/body/euler.hpp"
#include "rigid/body/euler_arnold.hpp"
#include "rigid/body/free_body_batch.hpp"
#include "rigid/body/free_body_exact.hpp"
#include "rigid/body/free_body_integrators.hpp"
#include "rigid/body/heavy_top.hpp"
#include "rigid/body/rigid_body.hpp"
