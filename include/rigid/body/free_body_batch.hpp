#pragma once

/// Many free rigid bodies stepped together by the methods of `free_body_integrators.hpp`.
/// The splittings run four bodies at a time: each block of four is held in vectors of four
/// doubles (one AVX2 register on CPUs that have it, chosen at run time; two SSE2 registers
/// otherwise) and taken through the kernel of `step_free_body` (merged same-axis sub-flows, one
/// half-angle sin/cos pair per sub-flow) with the same operations in the same order, so the
/// results are bitwise equal to calling `step_free_body` for each body, on either kind of CPU.
/// The other methods step body by body.

#include <span>

#include <Eigen/Core>

#include "rigid/body/free_body_integrators.hpp"

namespace rigid::body {

/// Advances every `states[i]` by one step h (s) of `method` with principal moments
/// `I_B[i]` (kg·m²), bitwise equal to `step_free_body(method, I_B[i], states[i], h)`.
/// @throws rigid::Error if the spans differ in length or h is not positive and finite, or, with
/// "body i: " in front, a body's moments are not positive and finite or its state is not finite,
/// or the step of a body does not converge (midpoint, moser_veselov: step_free_body's error) —
/// the bodies before i have been stepped, body i and those after it not — or a body's state
/// after the step is not finite (the step diverged: the first such body is named; every body
/// has been stepped). The checks are a few comparisons per body as it is loaded for its step
/// and one running sum of the results, not a test per sub-step.
void step_free_bodies(FreeBodyMethod method, std::span<const Eigen::Vector3d> I_B,
                      std::span<FreeBodyState> states, double h);

}  // namespace rigid::body
