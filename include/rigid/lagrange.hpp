#pragma once
/// The Lagrangian engine: symbolic Euler–Lagrange equations, compiled, with constraints.
#include "rigid/lagrange/system.hpp"
#include "rigid/lagrange/linearize.hpp"
