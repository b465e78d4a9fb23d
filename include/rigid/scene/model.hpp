#pragma once

/// A scene turned into the libraries' own models, and run. The scene is a thin front end: it
/// evaluates and checks what the file says, then hands over to
///  - rigid::lagrange::System for a scene of generalized coordinates (its bodies' masses and
///    gravity stay expressions of the parameters, so the equations print their names),
///    integrated by rigid::integrate (rk4, dopri5, implicit_midpoint, stormer_verlet);
///  - rigid::body::RigidBody (a free body in uniform gravity) and rigid::body::HeavyTop (a body
///    on a pivot) for a scene of free bodies, all marched together by rigid::integrate::march
///    with the free-body methods of rigid::body as the rotation's flow, or evaluated in closed
///    form (rigid::body::FreeBodyMotion, "exact").
/// Run outputs are rigid::io::RunResult and are written by rigid::io::write_run, so every front
/// end writes the same files.

#include <cstdint>
#include <filesystem>
#include <memory>
#include <optional>
#include <span>
#include <string>
#include <utility>
#include <vector>

#include "rigid/integrate/march.hpp"
#include "rigid/io/run_output.hpp"
#include "rigid/lagrange/system.hpp"
#include "rigid/mass/density.hpp"
#include "rigid/mass/mass_properties.hpp"
#include "rigid/scene/scene.hpp"

namespace rigid::scene {

/// What a scene's model integrates: generalized coordinates, or free bodies (io::RunKind, the
/// kind its runs record).
using SceneKind = io::RunKind;

using RunSummary = io::RunSummary;
using RunResult = io::RunResult;

struct RunOptions {
  /// Overrides [simulation] integrator when not empty.
  std::string integrator;
  /// Progress reports and cancellation (the command line's progress bar and Ctrl-C, Python's
  /// KeyboardInterrupt).
  integrate::MarchControl control{};
  /// Most bytes the trajectory may take (rows × columns × 8); unset: [output] max_memory, else
  /// rigid::io::kDefaultMaxMemory (2 GiB). Checked before the run (check() and run()); when
  /// dopri5 records every step, the rows are counted as they come.
  std::optional<std::uint64_t> max_memory{};
};

/// A body of the model with its mass properties in its own frame B (the numbers of the scene's
/// parameters).
struct ModelBody {
  std::string name;
  MassProperties mass;
  bool free = false;
  /// A primitive's sizes (m) by their canonical names in the catalogue (rigid::mass::
  /// primitive_table), in the catalogue's order; empty for other bodies.
  std::vector<std::pair<std::string, double>> sizes{};
  /// For a body with a `density_field`: the cubature's result with its estimated errors
  /// (describe() in density_field.hpp words them); empty for other bodies.
  std::optional<mass::DensityIntegration> density_field{};
};

class Model {
 public:
  /// Evaluates the parameters (in file order; each may use the ones before it), the
  /// coordinates' initial values, gravity and every body's mass properties, and builds the
  /// library models (the equations of a coordinate scene are derived here).
  /// @throws rigid::Error at file:line:col for an undefined name or a parse error in an
  ///   expression, a non-finite value, a physically invalid body (non-positive mass,
  ///   sizes, an inertia violating the triangle inequality, an open mesh), a free body
  ///   whose rotation is undefined (a principal moment 0), an unknown integrator.
  explicit Model(const Scene& scene);
  /// A model of `scene` that shares the equations already derived for `like` instead of deriving
  /// them again, and every mesh file `like` read (same file, units and hole filling) instead of
  /// reading it again: what a sweep does for each run. `scene` must differ from like.scene() only
  /// in what apply_overrides changes: parameter values, initial conditions, [simulation]
  /// settings, a free body's initial state. Runs and check() use this model's values (a mesh is
  /// measured again for this model's mass or density, with the result mesh_mass_from_file
  /// gives); system() is like's System, whose own default values are like's.
  /// @throws rigid::Error as Model(scene), and when the names of the parameters, coordinates or
  ///   bodies differ from like's.
  Model(const Scene& scene, const Model& like);
  ~Model();
  Model(Model&&) noexcept;
  Model& operator=(Model&&) noexcept;
  Model(const Model&) = delete;
  Model& operator=(const Model&) = delete;

  [[nodiscard]] SceneKind kind() const;
  /// End time of a run (s), from [simulation] t_end.
  [[nodiscard]] double t_end() const;
  [[nodiscard]] const Scene& scene() const;
  /// The scene's parameters with their values, then the derived constants of bodies whose
  /// mass properties come from a file or from points (named <body>_mass, <body>_ixx, …).
  [[nodiscard]] const std::vector<lagrange::Parameter>& parameters() const;
  [[nodiscard]] const std::vector<ModelBody>& bodies() const;
  /// Warnings found while building (e.g. a mesh that was repaired).
  [[nodiscard]] const std::vector<std::string>& warnings() const;
  /// What run() returns, known before it runs: every column of the trajectory after [output]
  /// quantities (quantity, body or other owner, component, unit), the parameters' units (the
  /// scene's state none; the derived constants' are kg, m, kg·m²), the diagnostics' and the
  /// metrics' units (a drift whose absolute change is reported instead says so in its run).
  [[nodiscard]] const io::RunSchema& schema() const;

  /// The integrator a run uses: `requested` if not empty, else [simulation] integrator,
  /// else the default of the kind (dopri5 for coordinates, splitting4 for free bodies).
  /// Free bodies also accept "exact" (closed form; not with a pivot).
  /// @throws rigid::Error naming the accepted methods if it is unknown for this kind.
  [[nodiscard]] std::string integrator(const std::string& requested = {}) const;

  /// The equations of motion: Euler–Lagrange equations of a coordinate scene, Euler's
  /// equations of each free body; text or LaTeX. Parameters keep their names; constants
  /// derived from files are named and listed with their values.
  [[nodiscard]] std::string equations(bool latex) const;
  /// The equations as a document: text, LaTeX (align* environments) or JSON (every quantity
  /// as text and LaTeX; rigid::lagrange::format_equations). The same bytes on every run.
  [[nodiscard]] std::string equations(lagrange::EquationFormat format) const;

  /// The coordinate system (only for kind() == kCoordinates), with the model's parameter values
  /// and initial state as its defaults (for a model built with `like`: like's). @throws
  /// rigid::Error otherwise.
  [[nodiscard]] const lagrange::System& system() const;

  /// Checks what a run would check before stepping (consistent initial conditions,
  /// a positive-definite mass matrix, valid step sizes, the step count of fixed-step methods,
  /// the memory of the trajectory against options.max_memory) without integrating.
  /// @throws rigid::Error naming the problem.
  void check(const RunOptions& options = {}) const;

  /// Simulates from t = 0 to t_end. Columns of the trajectory (one row per output time):
  ///  - coordinates: t, each q and q_dot, each body's pose `<body>.x .y .z .qw .qx .qy .qz`
  ///    (origin of B in W, m; R_WB as a quaternion), energy, jacobi, `lambda_<constraint>`
  ///    (the multipliers: generalized constraint forces, N or N·m), constraint_residual,
  ///    `p_<q>` for each cyclic coordinate;
  ///  - free bodies: t, each body's pose, `<body>.vx .vy .vz` (COM velocity in W, m/s),
  ///    `<body>.wx .wy .wz` (ω in B, rad/s), `<body>.Lx .Ly .Lz` (angular momentum in W
  ///    about the COM, or about the pivot for a heavy top, kg·m²/s), energy (J, total).
  /// A run is const: a Model may run on several threads at once.
  /// @throws rigid::Error for anything that stops the run (a diverging state naming the body,
  ///   the component and t; a singular mass matrix), rigid::Cancelled from options.control.
  [[nodiscard]] RunResult run(const RunOptions& options = {}) const;

  /// Whether run_batch steps this model's run with `options` together with others: a scene of
  /// free bodies in uniform gravity (no pivot, no applied load) stepped by splitting2,
  /// splitting4 or splitting6, with no progress or step observer in options.control.
  [[nodiscard]] bool batches(const RunOptions& options = {}) const;

  /// A run of run_batch: its result, or the message of the rigid::Error its run() throws.
  struct BatchedRun {
    std::optional<RunResult> result;
    std::string error;
  };
  /// Runs every model with `options` as run() runs it. When every model batches() and all share
  /// t_end, dt, output_dt and the integrator, they march together: each step's rotations, of
  /// every body of every run, go through one call of rigid::body::step_free_bodies (four bodies
  /// at a time in vector registers), whose results are step_free_body's bits, so each run's
  /// trajectory, diagnostics, metrics and error message are those of its run() alone (tested);
  /// a run that fails leaves the batch and the others go on. Only summary.wall_seconds
  /// differs: it is the batch's. Otherwise the models run one after the other.
  /// @throws rigid::Cancelled from options.control (no result is returned then).
  [[nodiscard]] static std::vector<BatchedRun> run_batch(std::span<const Model* const> models,
                                                         const RunOptions& options = {});

  /// The directory a run writes to: `requested` if not empty, else [output] directory, else
  /// "out/<stem of the scene file>" (one directory per scene).
  [[nodiscard]] std::filesystem::path output_directory(const std::string& requested = {}) const;
  /// The files a run writes: `requested` if not empty, else [output] formats.
  /// @throws rigid::Error for an unknown format name.
  [[nodiscard]] std::vector<io::OutputFormat> output_formats(const std::vector<std::string>& requested = {}) const;

 private:
  Model(const Scene& scene, const Model* like);
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

/// Reads a scene file (a robot model file read with `model`'s settings, or a TOML scene whose
/// `[model]` settings they override), applies `name=value` parameter overrides and builds the
/// model: what the command line and Python do with a scene path.
/// @throws rigid::Error as load_scene, apply_overrides and Model do.
[[nodiscard]] Model load_model(const std::filesystem::path& file, const std::vector<std::string>& overrides = {},
                               const ModelOptions& model = {});

}  // namespace rigid::scene
