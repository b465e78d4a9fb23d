#pragma once

/// Normal modes of a scene of generalized coordinates: the point given as `name=value`
/// assignments (values are expressions of the scene's parameters, e.g. `theta=pi`), the modes
/// of rigid::lagrange::normal_modes, and their JSON document — what `rigid modes` prints and
/// writes and Python's `Scene.modes()` returns.

#include <string>
#include <vector>

#include "rigid/lagrange/linearize.hpp"
#include "rigid/scene/model.hpp"

namespace rigid::scene {

/// Parses `name=value` assignments into points of the linearisation; each value is an
/// expression of the model's parameters (`pi/2`, `2*l`).
/// @throws rigid::Error naming the assignment when it is not of the form name=value or its
///   value does not evaluate.
[[nodiscard]] std::vector<lagrange::PointValue> point_values(const Model& model,
                                                             const std::vector<std::string>& at);

/// The modes of a coordinate scene (lagrange::normal_modes with `at` parsed by point_values).
/// @throws rigid::Error for a scene of free bodies (their state is not made of coordinates),
///   and as point_values and lagrange::normal_modes do.
[[nodiscard]] lagrange::NormalModes normal_modes(const Model& model, const std::vector<std::string>& at = {});

/// The JSON document of the modes (keys in a fixed order, numbers in shortest round-trip form):
/// scene, coordinates, ignorable, point {q, q_dot}, searched, iterations, residual,
/// stability, gyroscopic, constraints, multipliers {name: λ}, M, C, K (n × n, row-major
/// arrays), reduced {coordinates, M, C, K, tangent_basis},
/// eigenvalues [{re, im}], modes [{omega, hz, omega_squared (null for the state-space problem),
/// growth_rate, stability, shape {coordinate: {re, im}}}].
[[nodiscard]] std::string modes_json(const lagrange::NormalModes& modes, const std::string& scene_file);

}  // namespace rigid::scene
