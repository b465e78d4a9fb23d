#pragma once

// Velocity (nonholonomic) constraints A(q, t) q̇ + a(q, t) = 0 of a System: derived with the
// rest of the equations (system.cpp calls derive_velocity_constraints) and evaluated next to
// the holonomic rows (evaluate.cpp calls evaluate_velocity_constraints), as extra rows of the
// constraint Jacobian, so the one solve of evaluate.cpp gives q̈, λ and μ.

#include <map>
#include <string>
#include <vector>

#include <ginac/ginac.h>

#include "system_impl.hpp"

namespace rigid::lagrange::detail {

/// Parses and derives spec.velocity_constraints into s (r, names, A, a, η, c, the tape `vel`);
/// marks in `constrained` the coordinates a row involves. `names` is the symbol table of the
/// System (parameters, coordinates, velocities, t). Needs s.q, s.qd, s.t, s.params, s.q0 and
/// s.param_values.
/// @throws rigid::Error as System::System documents for velocity constraints.
void derive_velocity_constraints(const SystemSpec& spec, System::Impl& s,
                                 const std::map<std::string, GiNaC::ex>& names,
                                 std::vector<bool>& constrained);

/// Fills rows m … m + r − 1 of w.Gw (A), w.gammaw (η), w.cw (A q̇ + a) and w.gw (0) from the
/// inputs evaluate_dynamics loaded into w.in.
void evaluate_velocity_constraints(const System::Impl& s, Workspace::Impl& w);

}  // namespace rigid::lagrange::detail
