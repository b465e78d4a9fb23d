#include "rigid/body/free_body_batch.hpp"

#include <cmath>
#include <algorithm>

#include "rigid/common/error.hpp"
#include "rigid/common/format.hpp"

namespace rigid::body {

namespace {

// The refusal of body b when its moments are not positive and finite or its state is not
// finite (out of line: the check in the loop is a few comparisons). Returns when the state is
// finite after all (finite components whose sum overflowed).
[[gnu::cold, gnu::noinline]] void refuse_body_input(std::size_t b, const Eigen::Vector3d& I,
                                                   const FreeBodyState& state) {
  RIGID_REQUIRE_AS("step_free_bodies", (I.array() > 0.0).all() && I.allFinite(),
                   "body {}: principal moments {} kg·m² must be positive and finite", b,
                   rigid::to_string(I.transpose()));
  if (const auto bad = find_nonfinite(state)) {
    ::rigid::detail::throw_error("step_free_bodies",
                        fmt::format("body {}: the state is not finite: {} = {}, expected a "
                                    "finite state",
                                    b, bad->component, bad->value));
  }
}

// The refusal of the first body whose state after the step is not finite; returns when there
// is none (finite components whose sum overflowed).
[[gnu::cold, gnu::noinline]] void refuse_body_result(std::span<const FreeBodyState> states,
                                                    double h) {
  for (std::size_t b = 0; b < states.size(); ++b) {
    if (const auto bad = find_nonfinite(states[b])) {
      ::rigid::detail::throw_error("step_free_bodies",
                          fmt::format("body {}: the step of h = {} s diverged: {} = {} after it, "
                                      "expected a finite state (a smaller step h)",
                                      b, h, bad->component, bad->value));
    }
  }
}

}  // namespace

void step_free_bodies(FreeBodyMethod method, std::span<const Eigen::Vector3d> I_B,
                      std::span<FreeBodyState> states, double h) {
  RIGID_REQUIRE(I_B.size() == states.size(), "{} principal-moment vectors for {} states; expected one per body",
                I_B.size(), states.size());
  RIGID_REQUIRE(std::isfinite(h) && h > 0, "step h must be positive and finite, got {} s", h);
  // Each body's input is checked as it is loaded for its step (a separate pass over the batch
  // first would read it from memory twice: 5-10 % of a splitting2 step at 1e5 bodies): the
  // smallest moment positive (false for NaN) and a finite sum of the moments and the state's
  // components (non-finite if one of them is; finite values whose sum overflows fall through
  // to the scan, which accepts them). `&`, not `&&`: one branch per body. One kernel for one body and for many:
  // step_free_body's splitting path is already the merged half-angle kernel
  // (free_body_integrators.cpp), so there is no second copy here.
  double sum = 0.0;  // of every component after the step: non-finite iff one of them is (or overflow)
  for (std::size_t b = 0; b < states.size(); ++b) {
    const Eigen::Vector3d& I = I_B[b];
    const bool ok = (std::min({I(0), I(1), I(2)}) > 0.0) &
                    std::isfinite(I.sum() + states[b].R_WB.quaternion().sum() + states[b].w_B.sum());
    if (!ok) [[unlikely]]
      refuse_body_input(b, I, states[b]);
    try {
      states[b] = step_free_body(method, I, states[b], h);
    } catch (const Error& e) {
      RIGID_THROW("body {}: {}", b, e.what());  // an implicit step that did not converge
    }
    sum += states[b].R_WB.quaternion().sum() + states[b].w_B.sum();
  }
  if (!std::isfinite(sum)) [[unlikely]]
    refuse_body_result(states, h);
}

}  // namespace rigid::body
