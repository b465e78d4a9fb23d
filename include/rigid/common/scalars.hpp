#pragma once

#include <Eigen/Core>
#include <unsupported/Eigen/AutoDiff>

namespace rigid {

/// Forward-mode automatic-differentiation scalar with a dynamic number of partials.
/// Templated code (lie/, the right-hand sides in body/) is instantiated for double
/// and for this type.
using AutoDiffXd = Eigen::AutoDiffScalar<Eigen::VectorXd>;

}  // namespace rigid
