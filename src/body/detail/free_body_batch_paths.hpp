#pragma once

// The code paths of step_free_bodies (free_body_batch.cpp), named so that tests and benchmarks
// can run each one and compare: they return the same bits.

#include <span>

#include <Eigen/Core>

#include "rigid/body/free_body_integrators.hpp"

namespace rigid::body::detail {

enum class BatchPath {
  kScalar,     ///< step_free_body for each body in turn
  kLanes,      ///< the splittings four bodies at a time, in vectors of the baseline ISA (SSE2)
  kLanesAvx2,  ///< the same four-body kernel compiled for AVX2 (on CPUs that have it)
};

/// True if this CPU runs `path` (kLanesAvx2 needs AVX2; the others always run).
[[nodiscard]] bool batch_path_available(BatchPath path);

/// The path step_free_bodies takes for `method`: the four-body kernel for the splittings (AVX2
/// where available), kScalar for the other methods.
[[nodiscard]] BatchPath batch_path_of(FreeBodyMethod method);

/// step_free_bodies on the given path (a path the CPU lacks, or a four-body path for a method
/// other than the splittings, is refused).
void step_free_bodies_on(BatchPath path, FreeBodyMethod method,
                         std::span<const Eigen::Vector3d> I_B, std::span<FreeBodyState> states,
                         double h);

}  // namespace rigid::body::detail
