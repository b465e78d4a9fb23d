#pragma once

/// A scene turned into something that runs: parameters evaluated, mass properties built,
/// equations derived, and a simulation that produces a trajectory table and a summary.
///
/// Two kinds of scene (see docs/scene-format.md):
///  - generalized coordinates: a rigid::lagrange::System derived from the bodies' poses,
///    integrated by rigid::integrate (rk4, dopri5, implicit_midpoint, stormer_verlet);
///  - free bodies: each body's COM moves on its exact parabola under uniform gravity and
///    its rotation is integrated on SO(3) by the free-body methods of rigid::body, or
///    evaluated in closed form ("exact"); a body with a pivot is a heavy top, integrated by
///    the gravity-kick splitting.

#include <functional>
#include <memory>
#include <string>
#include <utility>
#include <vector>

#include "rigid/io/table.hpp"
#include "rigid/lagrange/system.hpp"
#include "rigid/mass/mass_properties.hpp"
#include "rigid/scene/scene.hpp"

namespace rigid::scene {

enum class SceneKind { kCoordinates, kFreeBodies };

/// What a run measured, for summary.json and the printed summary.
struct RunSummary {
  std::string kind;        ///< "coordinates" or "free_bodies"
  std::string integrator;  ///< the method that ran
  double t_end = 0;        ///< s
  double dt = 0;           ///< fixed or initial step (s)
  double tolerance = 0;    ///< adaptive methods' tolerance (0 when fixed-step)
  std::size_t steps = 0;
  std::size_t rhs_evaluations = 0;  ///< 0 for the free-body methods (they count steps)
  std::size_t samples = 0;          ///< rows of the trajectory
  double wall_seconds = 0;
  std::vector<std::pair<std::string, double>> parameters;
  /// Conservation and constraint diagnostics, name → value (SI units; see docs/scene-format.md).
  std::vector<std::pair<std::string, double>> diagnostics;
  std::vector<std::string> warnings;
};

struct RunResult {
  io::Table trajectory{{"t"}};
  RunSummary summary;
};

struct RunOptions {
  /// Overrides [simulation] integrator when not empty.
  std::string integrator;
  /// Called with the simulated time reached (s) as the run advances; may throw
  /// rigid::Error to stop it (the CLI does on Ctrl-C). Empty: not called.
  std::function<void(double t)> progress;
};

/// A body of the model with its mass properties in its own frame B.
struct ModelBody {
  std::string name;
  MassProperties mass;
  bool free = false;
};

class Model {
 public:
  /// Evaluates the parameters (in file order; each may use the ones before it), the
  /// coordinates' initial values, gravity and every body's mass properties, and derives
  /// the equations of a coordinate scene.
  /// @throws rigid::Error at file:line:col for an undefined name or a parse error in an
  ///   expression, a non-finite value, a physically invalid body (non-positive mass,
  ///   sizes, an inertia violating the triangle inequality, an open mesh), a free body
  ///   whose rotation is undefined (a principal moment 0), an unknown integrator.
  explicit Model(const Scene& scene);
  ~Model();
  Model(Model&&) noexcept;
  Model& operator=(Model&&) noexcept;
  Model(const Model&) = delete;
  Model& operator=(const Model&) = delete;

  [[nodiscard]] SceneKind kind() const;
  /// End time of a run (s), from [simulation] t_end.
  [[nodiscard]] double t_end() const;
  [[nodiscard]] const Scene& scene() const;
  [[nodiscard]] const std::vector<lagrange::Parameter>& parameters() const;
  [[nodiscard]] const std::vector<ModelBody>& bodies() const;
  /// Warnings found while building (e.g. a mesh that was repaired).
  [[nodiscard]] const std::vector<std::string>& warnings() const;

  /// The integrator a run uses: `requested` if not empty, else [simulation] integrator,
  /// else the default of the kind (dopri5 for coordinates, splitting4 for free bodies).
  /// Free bodies also accept "exact" (closed form; not with a pivot).
  /// @throws rigid::Error naming the accepted methods if it is unknown for this kind.
  [[nodiscard]] std::string integrator(const std::string& requested = {}) const;

  /// The equations of motion: Euler–Lagrange equations of a coordinate scene, Euler's
  /// equations (with the numbers of each body) of a free-body scene; text or LaTeX.
  [[nodiscard]] std::string equations(bool latex) const;

  /// The coordinate system (only for kind() == kCoordinates). @throws rigid::Error otherwise.
  [[nodiscard]] const lagrange::System& system() const;

  /// Checks what a run would check before stepping (consistent initial conditions,
  /// a positive-definite mass matrix, valid step sizes) without integrating.
  /// @throws rigid::Error naming the problem.
  void check(const RunOptions& options = {}) const;

  /// Simulates from t = 0 to t_end. Columns of the trajectory (one row per output time):
  ///  - coordinates: t, each q and q_dot, each body's pose `<body>.x .y .z .qw .qx .qy .qz`
  ///    (origin of B in W, m; q_WB), energy, jacobi, `lambda_<constraint>` (the
  ///    multipliers: generalized constraint forces, N or N·m), constraint_residual,
  ///    `p_<q>` for each cyclic coordinate;
  ///  - free bodies: t, each body's pose, `<body>.vx .vy .vz` (COM velocity in W, m/s),
  ///    `<body>.wx .wy .wz` (ω in B, rad/s), `<body>.Lx .Ly .Lz` (angular momentum in W
  ///    about the COM, or about the pivot for a heavy top, kg·m²/s), energy (J, total).
  /// @throws rigid::Error for anything that stops the run (diverging state, singular mass
  ///   matrix, a progress callback that throws).
  [[nodiscard]] RunResult run(const RunOptions& options = {}) const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace rigid::scene
