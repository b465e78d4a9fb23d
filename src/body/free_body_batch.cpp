#include "rigid/body/free_body_batch.hpp"

#include <cmath>

#include "rigid/common/error.hpp"

namespace rigid::body {

void step_free_bodies(FreeBodyMethod method, std::span<const Eigen::Vector3d> I_B,
                      std::span<FreeBodyState> states, double h) {
  RIGID_REQUIRE(I_B.size() == states.size(), "{} principal-moment vectors for {} states; expected one per body",
                I_B.size(), states.size());
  RIGID_REQUIRE(std::isfinite(h) && h > 0, "step h must be positive and finite, got {} s", h);
  // One kernel for one body and for many: step_free_body's splitting path is already the
  // merged half-angle kernel (free_body_integrators.cpp), so there is no second copy here.
  for (std::size_t b = 0; b < states.size(); ++b) {
    try {
      states[b] = step_free_body(method, I_B[b], states[b], h);
    } catch (const Error& e) {
      RIGID_THROW("body {}: {}", b, e.what());  // an implicit step that did not converge
    }
  }
}

}  // namespace rigid::body
