#pragma once

/// Many free rigid bodies stepped together by the body-axis splittings of
/// `free_body_integrators.hpp`, with a cheaper kernel than calling `step_free_body` per body:
/// - each axis sub-flow takes one sin/cos pair of the half angle θ/2 and gets cos θ and
///   sin θ from it (cos θ = 1 − 2 sin²(θ/2), sin θ = 2 sin(θ/2) cos(θ/2)), where the
///   single-body stepper evaluates both angles;
/// - consecutive sub-flows about the same axis are merged into one (the flow of
///   H_i = L_i²/(2 I_i) keeps L_i, so flows of lengths a and b compose to one of a + b):
///   Yoshida-4 needs 13 sub-flows instead of 15, Yoshida-6 37 instead of 45.
/// Both are exact rewritings, so the result equals `step_free_body` up to round-off.

#include <span>

#include <Eigen/Core>

#include "rigid/body/free_body_integrators.hpp"

namespace rigid::body {

/// Advances every `states[i]` by one step h (s) of `method` with principal moments
/// `I_B[i]` (kg·m²). kSplitting2/4/6 use the merged kernel above; kRk4 and
/// kLiePoissonMidpoint call `step_free_body` for each body.
/// @throws rigid::Error if the spans differ in length or h is not positive and finite.
/// Moments and states are not checked per body (this is the hot loop): pass moments > 0.
void step_free_bodies(FreeBodyMethod method, std::span<const Eigen::Vector3d> I_B,
                      std::span<FreeBodyState> states, double h);

}  // namespace rigid::body
