#pragma once
/// The one time-marching loop (output times, the step rule, the finiteness check, progress and
/// cancellation) and the integrators on R^n behind one interface: rk4, dopri5, implicit
/// midpoint, Störmer–Verlet.
#include "rigid/integrate/integrator.hpp"
#include "rigid/integrate/march.hpp"
