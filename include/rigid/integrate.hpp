#pragma once
/// Integrators on R^n behind one interface: rk4, dopri5, implicit midpoint, Störmer–Verlet.
#include "rigid/integrate/integrator.hpp"
