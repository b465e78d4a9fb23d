// Linearisation about an equilibrium or a steady motion, and normal modes: the symbolic
// derivatives of the derived equations (GiNaC) compiled to a tape, a search for the point,
// Routh reduction of the ignorable coordinates, and the eigenproblem (Eigen).
#include "rigid/lagrange/linearize.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>

#include <Eigen/Cholesky>
#include <Eigen/Eigenvalues>
#include <Eigen/LU>
#include <Eigen/QR>
#include <Eigen/SVD>
#include <fmt/format.h>
#include <fmt/ranges.h>
#include <ginac/ginac.h>

#include "rigid/common/did_you_mean.hpp"
#include "rigid/common/error.hpp"
#include "rigid/common/wording.hpp"
#include "detail/symbolic_lock.hpp"
#include "detail/symbolic.hpp"
#include "detail/system_impl.hpp"
#include "detail/tape.hpp"

namespace rigid::lagrange {
namespace {

using Impl = System::Impl;
using GiNaC::ex;

// The public entry point that every refusal names.
constexpr const char* kWho = "normal_modes";

// M, f, K = −∂f/∂q, C = −∂f/∂q̇, and the constraints g, G = ∂g/∂q and their Hessians
// H_k = ∂²g_k/∂q², compiled once per call: inputs (q, q̇, t, parameters). K and C are symbolic
// derivatives of f, or, for a recursive derivation (f in terms of intermediates), the tape's
// forward-mode derivatives of f (exact but for rounding).
class Linearization {
 public:
  explicit Linearization(const Impl& s) : n_(s.n), m_(s.m), by_tangent_(!s.aux.empty()) {
    std::vector<GiNaC::symbol> inputs;
    inputs.insert(inputs.end(), s.q.begin(), s.q.end());
    inputs.insert(inputs.end(), s.qd.begin(), s.qd.end());
    inputs.push_back(s.t);
    inputs.insert(inputs.end(), s.params.begin(), s.params.end());
    detail::TapeBuilder b(inputs);
    detail::define_intermediates(b, s);
    const auto n = static_cast<std::size_t>(s.n);
    const auto m = static_cast<std::size_t>(s.m);
    for (std::size_t i = 0; i < n; ++i)
      for (std::size_t j = i; j < n; ++j) b.add_output(s.M[i * n + j]);
    for (const ex& fi : s.f) b.add_output(fi);
    if (!by_tangent_) {
      for (std::size_t i = 0; i < n; ++i)
        for (std::size_t j = 0; j < n; ++j) b.add_output(-detail::d(s.f[i], s.q[j]));
      for (std::size_t i = 0; i < n; ++i)
        for (std::size_t j = 0; j < n; ++j) b.add_output(-detail::d(s.f[i], s.qd[j]));
    }
    for (const ex& gk : s.g) b.add_output(gk);
    for (std::size_t k = 0; k < m; ++k)
      for (std::size_t i = 0; i < n; ++i) b.add_output(s.G[k * n + i]);
    for (std::size_t k = 0; k < m; ++k)
      for (std::size_t i = 0; i < n; ++i)
        for (std::size_t j = 0; j < n; ++j) b.add_output(detail::d(s.G[k * n + i], s.q[j]));
    tape_ = b.build();
    in_.assign(tape_.num_inputs(), 0.0);
    out_.assign(tape_.num_outputs(), 0.0);
    scratch_ = tape_.make_scratch();
    if (by_tangent_) {
      seed_.assign(tape_.num_inputs(), 0.0);
      dout_.assign(tape_.num_outputs(), 0.0);
      dscratch_ = tape_.make_scratch();
    }
  }

  void evaluate(const Eigen::VectorXd& q, const Eigen::VectorXd& qd,
                const std::vector<double>& params) {
    const int n = n_, m = m_;
    for (int i = 0; i < n; ++i) {
      in_[static_cast<std::size_t>(i)] = q[i];
      in_[static_cast<std::size_t>(n + i)] = qd[i];
    }
    in_[static_cast<std::size_t>(2 * n)] = 0.0;  // t: the equations do not depend on it
    std::copy(params.begin(), params.end(), in_.begin() + 2 * n + 1);
    tape_.evaluate(in_.data(), out_.data(), scratch_);
    M.resize(n, n);
    f.resize(n);
    K.resize(n, n);
    C.resize(n, n);
    g.resize(m);
    G.resize(m, n);
    H.assign(static_cast<std::size_t>(m), Eigen::MatrixXd(n, n));
    std::size_t k = 0;
    for (int i = 0; i < n; ++i)
      for (int j = i; j < n; ++j) M(i, j) = M(j, i) = out_[k++];
    const std::size_t f_at = k;
    for (int i = 0; i < n; ++i) f[i] = out_[k++];
    if (by_tangent_) {
      // column j of K and C: −∂f/∂q_j and −∂f/∂q̇_j, one forward-mode pass each
      for (int j = 0; j < 2 * n; ++j) {
        std::fill(seed_.begin(), seed_.end(), 0.0);
        seed_[static_cast<std::size_t>(j)] = 1.0;
        tape_.tangent(seed_.data(), dout_.data(), scratch_, dscratch_);
        for (int i = 0; i < n; ++i) (j < n ? K(i, j) : C(i, j - n)) = -dout_[f_at + static_cast<std::size_t>(i)];
      }
    } else {
      for (int i = 0; i < n; ++i)
        for (int j = 0; j < n; ++j) K(i, j) = out_[k++];
      for (int i = 0; i < n; ++i)
        for (int j = 0; j < n; ++j) C(i, j) = out_[k++];
    }
    for (int a = 0; a < m; ++a) g[a] = out_[k++];
    for (int a = 0; a < m; ++a)
      for (int i = 0; i < n; ++i) G(a, i) = out_[k++];
    for (int a = 0; a < m; ++a)
      for (int i = 0; i < n; ++i)
        for (int j = 0; j < n; ++j) H[static_cast<std::size_t>(a)](i, j) = out_[k++];
  }

  Eigen::MatrixXd M, K, C, G;
  Eigen::VectorXd f, g;
  std::vector<Eigen::MatrixXd> H;

 private:
  int n_, m_;
  bool by_tangent_;
  detail::Tape tape_;
  std::vector<double> in_, out_, scratch_;
  std::vector<double> seed_, dout_, dscratch_;  // forward-mode derivatives (by_tangent_)
};

Eigen::MatrixXd rows_cols(const Eigen::MatrixXd& A, const std::vector<int>& rows,
                          const std::vector<int>& cols) {
  Eigen::MatrixXd B(static_cast<Eigen::Index>(rows.size()), static_cast<Eigen::Index>(cols.size()));
  for (std::size_t i = 0; i < rows.size(); ++i)
    for (std::size_t j = 0; j < cols.size(); ++j) B(static_cast<Eigen::Index>(i), static_cast<Eigen::Index>(j)) = A(rows[i], cols[j]);
  return B;
}

Eigen::MatrixXd columns(const Eigen::MatrixXd& A, const std::vector<int>& cols) {
  Eigen::MatrixXd B(A.rows(), static_cast<Eigen::Index>(cols.size()));
  for (std::size_t j = 0; j < cols.size(); ++j) B.col(static_cast<Eigen::Index>(j)) = A.col(cols[j]);
  return B;
}

Eigen::VectorXd entries(const Eigen::VectorXd& v, const std::vector<int>& idx) {
  Eigen::VectorXd w(static_cast<Eigen::Index>(idx.size()));
  for (std::size_t i = 0; i < idx.size(); ++i) w[static_cast<Eigen::Index>(i)] = v[idx[i]];
  return w;
}

std::string point_text(const Impl& s, const Eigen::VectorXd& q) {
  std::string out;
  for (int i = 0; i < s.n; ++i) {
    out += fmt::format("{}{} = {}", i ? ", " : "", s.coord_names[static_cast<std::size_t>(i)], q[i]);
  }
  return out;
}

// The search for the free coordinates q_F and the multipliers λ with
//   R(q_F, λ) = (f_F + (Gᵀλ)_F, g) = 0,
// the other coordinates held. Its Jacobian, with ∂f/∂q = −K:
//   J = [−K_FF + Σ λ_k (H_k)_FF   (G_F)ᵀ]
//       [G_F                       0    ].
struct Search {
  Linearization& lin;
  const std::vector<double>& params;
  const std::vector<int>& unknowns;
  Eigen::VectorXd qd;
  int max_iterations;
  double force_scale = 0.0, length_scale = 1.0;  // what "0" is measured against
  int iterations = 0;

  [[nodiscard]] int num_unknowns() const { return static_cast<int>(unknowns.size()); }

  // R at (q, λ) and, with `jacobian`, J; lin holds the evaluation at q afterwards
  Eigen::VectorXd residual(const Eigen::VectorXd& q, const Eigen::VectorXd& lam, Eigen::MatrixXd* jacobian) {
    lin.evaluate(q, qd, params);
    const int nf = num_unknowns(), m = static_cast<int>(lin.g.size());
    const Eigen::MatrixXd GF = columns(lin.G, unknowns);
    Eigen::VectorXd R(nf + m);
    R.head(nf) = entries(lin.f, unknowns) + GF.transpose() * lam;
    R.tail(m) = lin.g;
    if (jacobian != nullptr) {
      Eigen::MatrixXd& J = *jacobian;
      J.setZero(nf + m, nf + m);
      J.topLeftCorner(nf, nf) = -rows_cols(lin.K, unknowns, unknowns);
      for (int k = 0; k < m; ++k) J.topLeftCorner(nf, nf) += lam[k] * rows_cols(lin.H[static_cast<std::size_t>(k)], unknowns, unknowns);
      J.topRightCorner(nf, m) = GF.transpose();
      J.bottomLeftCorner(m, nf) = GF;
    }
    return R;
  }

  // max of |force rows| / force scale and |constraint rows| / length scale: 0 at the point
  [[nodiscard]] double merit(const Eigen::VectorXd& R) const {
    const int nf = num_unknowns();
    const double forces = nf ? R.head(nf).lpNorm<Eigen::Infinity>() / force_scale : 0.0;
    const double lengths = R.size() > nf ? R.tail(R.size() - nf).lpNorm<Eigen::Infinity>() / length_scale : 0.0;
    return std::max(forces, lengths);
  }

  void apply(Eigen::VectorXd& q, Eigen::VectorXd& lam, const Eigen::VectorXd& step) const {
    for (std::size_t i = 0; i < unknowns.size(); ++i) q[unknowns[i]] += step[static_cast<Eigen::Index>(i)];
    lam += step.tail(lam.size());
  }

  // Newton's method with steps of at most 0.5 per coordinate and a step accepted only if it
  // lowers the merit. Returns whether it converged.
  bool newton(Eigen::VectorXd& q, Eigen::VectorXd& lam) {
    constexpr double kMaxStep = 0.5;
    Eigen::MatrixXd J;
    for (int it = 0; it < max_iterations; ++it, ++iterations) {
      const Eigen::VectorXd R = residual(q, lam, &J);
      const double before = merit(R);
      if (before <= 1e-13) return true;
      Eigen::ColPivHouseholderQR<Eigen::MatrixXd> qr(J);
      qr.setThreshold(1e-10);
      if (qr.rank() < J.rows()) return false;  // a neutral or turning direction: stalled
      Eigen::VectorXd step = -qr.solve(R);
      const double longest = step.head(num_unknowns()).lpNorm<Eigen::Infinity>();
      if (!step.allFinite()) return false;
      if (longest > kMaxStep) step *= kMaxStep / longest;
      bool accepted = false;
      for (int h = 0; h < 30 && !accepted; ++h, step /= 2) {
        Eigen::VectorXd trial = q, trial_lam = lam;
        apply(trial, trial_lam, step);
        const double after = merit(residual(trial, trial_lam, nullptr));
        if (after < before) {
          const bool tiny = step.head(num_unknowns()).lpNorm<Eigen::Infinity>() <=
                            4e-16 * std::max(1.0, q.lpNorm<Eigen::Infinity>());
          q = trial;
          lam = trial_lam;
          accepted = true;
          if (tiny) return after <= 1e-9;
        }
      }
      if (!accepted) return before <= 1e-9;
    }
    return false;
  }

  // Pseudo-transient continuation [Kelley1998]: (D/τ − J) Δ = R with D = diag(M_FF, 0)
  // follows the motion with strong damping towards rest where Newton stalls (J singular: a
  // pendulum held horizontally), and becomes Newton's method as τ grows with the merit's
  // decrease (τ_{k+1} = τ_k φ_k / φ_{k+1}).
  bool continuation(Eigen::VectorXd& q, Eigen::VectorXd& lam) {
    const int nf = num_unknowns();
    Eigen::MatrixXd J;
    Eigen::VectorXd R = residual(q, lam, &J);
    // the first step moves the coordinates by about 0.1 (rad or m)
    const Eigen::VectorXd a = rows_cols(lin.M, unknowns, unknowns).ldlt().solve(R.head(nf));
    double tau = 0.1 / std::max(a.lpNorm<Eigen::Infinity>(), 1e-300);
    for (int it = 0; it < 4 * max_iterations; ++it, ++iterations) {
      R = residual(q, lam, &J);
      const double before = merit(R);
      if (before <= 1e-13) return true;
      Eigen::MatrixXd A = -J;
      A.topLeftCorner(nf, nf) += rows_cols(lin.M, unknowns, unknowns) / tau;
      const Eigen::VectorXd step = A.partialPivLu().solve(R);
      if (!step.allFinite()) return false;
      apply(q, lam, step);
      const double after = merit(residual(q, lam, nullptr));
      if (!std::isfinite(after)) return false;
      tau = std::min(tau * before / std::max(after, 1e-300), 1e300);
      if (step.head(nf).lpNorm<Eigen::Infinity>() <= 4e-16 * std::max(1.0, q.lpNorm<Eigen::Infinity>())) {
        return after <= 1e-9;
      }
    }
    return false;
  }
};

const char* mode_word(const Mode& m) {
  switch (m.stability) {
    case Stability::kStable: return m.growth_rate < 0 ? (m.omega > 0 ? "decaying oscillation" : "decaying") : "oscillating";
    case Stability::kUnstable: return "growing";
    case Stability::kMarginal: return "neutral";
  }
  return "";
}

// The shape with φᴴ M φ = 1 and its largest component real and positive (so that two runs,
// and the symmetric and state-space paths, give the same sign).
Eigen::VectorXcd normalised(Eigen::VectorXcd v, const Eigen::MatrixXd& M) {
  const double norm2 = (v.adjoint() * M.cast<std::complex<double>>() * v)(0, 0).real();
  if (norm2 > 0) v /= std::sqrt(norm2);
  Eigen::Index k = 0;
  v.cwiseAbs().maxCoeff(&k);
  if (std::abs(v[k]) > 0) v *= std::abs(v[k]) / v[k];
  v[k] = std::abs(v[k]);
  return v;
}


// Refuses a system whose linearisation this does not form: velocity constraints, or equations
// that change with time.
void require_holonomic_and_autonomous(const System& system, const Impl& s) {
  const auto nu = static_cast<std::size_t>(s.n);
  s.refuse_balls("normal modes");
  // rolling (velocity) constraints restrict the motions, not the configurations: their
  // linearisation needs the reduced (Chaplygin/Voronets) equations, which this does not form
  if (system.num_velocity_constraints() > 0) {
    rigid::detail::throw_error(kWho, fmt::format(
        "the system has velocity constraints ({}); normal modes are computed for holonomic "
        "systems only",
        fmt::join(system.velocity_constraint_names(), ", ")));
  }

  for (std::size_t i = 0; i < nu; ++i) {
    bool timed = s.f[i].has(s.t);
    for (std::size_t j = 0; j < nu; ++j) timed = timed || s.M[i * nu + j].has(s.t);
    if (timed) {
      rigid::detail::throw_error(kWho, fmt::format(
          "the equation of '{}' depends on the time t; an equilibrium or a steady motion needs "
          "equations that do not change with time",
          s.coord_names[i]));
    }
  }
}

// The parameters' values for this call: the System's, with the options' values in place.
std::vector<double> parameters_for_call(const Impl& s, const LinearizeOptions& options) {
  std::vector<double> params = s.param_values;
  for (const Parameter& p : options.parameters) {
    const std::size_t k = s.parameter_index(p.name);
    RIGID_REQUIRE_AS(kWho, std::isfinite(p.value), "parameter '{}' must be finite, got {}", p.name, p.value);
    params[k] = p.value;
  }
  if (!options.parameters.empty()) s.check_masses(params, "for the parameters of the linearisation");
  return params;
}

// Ignorable coordinates: cyclic, and no equation depends on them.
std::vector<bool> ignorable_coordinates(const Impl& s) {
  const auto nu = static_cast<std::size_t>(s.n);
  std::vector<bool> ignorable(nu, false);
  for (int c : s.cyclic_index) {
    bool appears = false;
    for (std::size_t i = 0; i < nu && !appears; ++i) {
      appears = s.f[i].has(s.q[static_cast<std::size_t>(c)]);
      for (std::size_t j = 0; j < nu && !appears; ++j) appears = s.M[i * nu + j].has(s.q[static_cast<std::size_t>(c)]);
    }
    ignorable[static_cast<std::size_t>(c)] = !appears;
  }
  return ignorable;
}

// The point to start from, and which coordinates the caller holds at a given value.
struct StartPoint {
  Eigen::VectorXd q, qd;
  std::vector<bool> held;
};

// The point: given values, else the initial state; rates only for ignorable coordinates.
StartPoint start_point(const Impl& s, const LinearizeOptions& options,
                       const std::vector<bool>& ignorable) {
  const auto nu = static_cast<std::size_t>(s.n);
  Eigen::VectorXd q = s.q0, qd = Eigen::VectorXd::Zero(s.n);
  for (std::size_t i = 0; i < nu; ++i) {
    if (ignorable[i]) qd[static_cast<Eigen::Index>(i)] = s.qd0[static_cast<Eigen::Index>(i)];
  }
  std::vector<bool> held(nu, false);
  std::vector<std::string> names;
  for (const auto& c : s.coord_names) {
    names.push_back(c);
    names.push_back(c + "_dot");
  }
  for (const PointValue& v : options.at) {
    RIGID_REQUIRE_AS(kWho, std::isfinite(v.value), "the value of '{}' must be finite, got {}", v.name, v.value);
    auto it = std::find(s.coord_names.begin(), s.coord_names.end(), v.name);
    if (it != s.coord_names.end()) {
      const auto i = static_cast<std::size_t>(it - s.coord_names.begin());
      q[static_cast<Eigen::Index>(i)] = v.value;
      held[i] = true;
      continue;
    }
    if (v.name.ends_with("_dot")) {
      it = std::find(s.coord_names.begin(), s.coord_names.end(), v.name.substr(0, v.name.size() - 4));
      if (it != s.coord_names.end()) {
        const auto i = static_cast<std::size_t>(it - s.coord_names.begin());
        if (!ignorable[i]) {
          rigid::detail::throw_error(kWho, fmt::format(
              "'{}' = {}: only a cyclic coordinate on which no equation depends may move at a "
              "steady rate; '{}' is not one{}, so it is at rest (0) at an equilibrium",
              v.name, v.value, *it,
              s.cyclic_names.empty() ? " (the system has no cyclic coordinates)"
                                     : fmt::format(" (cyclic: {})", fmt::join(s.cyclic_names, ", "))));
        }
        qd[static_cast<Eigen::Index>(i)] = v.value;
        continue;
      }
    }
    rigid::detail::throw_error(kWho, fmt::format(
        "unknown coordinate '{}'{}; expected a coordinate ({}) or the rate of a cyclic one "
        "(<name>_dot)",
        v.name, did_you_mean_hint(v.name, names), fmt::join(s.coord_names, ", ")));
  }
  return {q, qd, held};
}

// The coordinates by role: the reduced ones (not ignorable), the ignorable (cyclic) ones, and
// the unknowns of the search (reduced and not held).
struct Partition {
  std::vector<int> reduced, cyc, unknowns;
};

// Sorts the coordinates into their roles, and names the ignorable and reduced ones in `out`.
Partition partition_coordinates(const Impl& s, const std::vector<bool>& ignorable,
                                const std::vector<bool>& held, NormalModes& out) {
  Partition part;
  for (int i = 0; i < s.n; ++i) {
    const auto iu = static_cast<std::size_t>(i);
    (ignorable[iu] ? part.cyc : part.reduced).push_back(i);
    if (ignorable[iu]) out.ignorable_names.push_back(s.coord_names[iu]);
    else out.reduced_names.push_back(s.coord_names[iu]);
    if (!ignorable[iu] && !held[iu]) part.unknowns.push_back(i);
  }
  return part;
}

// Multipliers that balance the forces best (least squares): λ = −(G Gᵀ)⁻¹ G f.
Eigen::VectorXd best_multipliers(const Impl& s, const Linearization& lin) {
  if (s.m == 0) return Eigen::VectorXd(0);
  return Eigen::VectorXd((lin.G * lin.G.transpose()).completeOrthogonalDecomposition().solve(-lin.G * lin.f));
}

// What 0 is measured against: the forces at the start and the stiffness times the size of q.
double force_scale_at(const Impl& s, const Linearization& lin, const Eigen::VectorXd& q,
                      const Eigen::VectorXd& lambda) {
  return std::max(
      {lin.f.lpNorm<Eigen::Infinity>(),
       lin.K.cwiseAbs().rowwise().sum().maxCoeff() * std::max(1.0, q.lpNorm<Eigen::Infinity>()),
       (s.m ? (lin.G.transpose() * lambda).lpNorm<Eigen::Infinity>() : 0.0), 1e-300});
}

// Searches the unknown coordinates (and the multipliers) for the point: Newton from the
// start, else continuation from the start; moves q there, or refuses with where it ended.
void search_point(const Impl& s, Linearization& lin, const std::vector<double>& params,
                  const std::vector<int>& unknowns, Eigen::VectorXd& q, const Eigen::VectorXd& qd,
                  const Eigen::VectorXd& lambda, int max_iterations, double force_scale,
                  double length_scale, NormalModes& out) {
  out.searched = true;
  Search search{lin, params, unknowns, qd, max_iterations};
  search.force_scale = force_scale;
  search.length_scale = length_scale;
  Eigen::VectorXd found = q, found_lambda = lambda;
  bool ok = search.newton(found, found_lambda);
  if (!ok) {
    found = q;
    found_lambda = lambda;
    ok = search.continuation(found, found_lambda);
  }
  out.iterations = search.iterations;
  if (!ok) {
    lin.evaluate(found, qd, params);
    rigid::detail::throw_error(kWho, fmt::format(
        "no equilibrium found from ({}): the search ended at ({}) after {} iterations with "
        "generalized forces of up to {}{}; give the equilibrium's coordinates with {}",
        point_text(s, q), point_text(s, found), search.iterations,
        (entries(lin.f, unknowns) + columns(lin.G, unknowns).transpose() * found_lambda).lpNorm<Eigen::Infinity>(),
        s.m ? fmt::format(" and constraints violated by up to {}", lin.g.lpNorm<Eigen::Infinity>()) : "",
        setting("at", "name=value")));
  }
  q = found;
}

// Checks that q (with the rates qd) is an equilibrium or steady motion in every equation, on
// the constraints, with a positive definite M there; leaves lin evaluated at the point, the
// multipliers in `lambda` and max |q̈| in out.residual.
void require_equilibrium(const Impl& s, Linearization& lin, const std::vector<double>& params,
                         const Eigen::VectorXd& q, const Eigen::VectorXd& qd,
                         const std::vector<bool>& held, bool steady, double force_scale,
                         double length_scale, Eigen::VectorXd& lambda, NormalModes& out) {
  lin.evaluate(q, qd, params);
  Eigen::LLT<Eigen::MatrixXd> llt(lin.M);
  if (llt.info() != Eigen::Success) {
    rigid::detail::throw_error(kWho, fmt::format("the mass matrix is not positive definite at ({}); M = {}",
                                          point_text(s, q), fmt::join(lin.M.reshaped(), ", ")));
  }
  if (s.m > 0) {
    Eigen::Index worst = 0;
    const double gmax = lin.g.cwiseAbs().maxCoeff(&worst);
    if (!(gmax <= 1e-9 * length_scale)) {
      rigid::detail::throw_error(kWho, fmt::format(
          "({}) violates the constraint '{}' by {}; give coordinates on the constraints or leave "
          "them to the search",
          point_text(s, q), s.constraint_names[static_cast<std::size_t>(worst)], lin.g[worst]));
    }
    // the singular values, descending: G (m × n, m ≥ 1) has full row rank when the smallest
    // is not negligible against the largest
    const Eigen::JacobiSVD<Eigen::MatrixXd> svd(lin.G);
    const double smallest = svd.singularValues().tail<1>()(0), largest = svd.singularValues().head<1>()(0);
    if (!(smallest > 1e-10 * largest)) {
      rigid::detail::throw_error(kWho, fmt::format(
          "the constraints' gradients ∂g/∂q are dependent at ({}); the constraint manifold has no "
          "tangent space of dimension n − m there (G = {})",
          point_text(s, q), fmt::join(lin.G.reshaped<Eigen::RowMajor>(), ", ")));
    }
    lambda = best_multipliers(s, lin);
  }
  const Eigen::VectorXd f_total = lin.f + lin.G.transpose() * lambda;
  const Eigen::VectorXd acc = llt.solve(f_total);
  out.residual = acc.lpNorm<Eigen::Infinity>();
  const double k = lin.K.cwiseAbs().rowwise().sum().maxCoeff() +
                   lin.C.cwiseAbs().rowwise().sum().maxCoeff() * std::max(1.0, qd.lpNorm<Eigen::Infinity>());
  // What 0 is measured against. A coordinate's value is resolved to 1e-9 (rad or m), or to
  // 64 ulps of |q| where that is coarser, and the forces an error of that size leaves,
  // k · resolution, are round-off. (A tolerance growing with |q| itself, 1e-9 k |q|, took a
  // pendulum held at 1e9π + 0.5 rad, half a radian from hanging, for an equilibrium.) Where
  // the search found the point, its own acceptance (forces at most 1e-9 of those at the
  // start) holds too: at a degenerate minimum (V = x⁴) the stiffness vanishes with the
  // forces, and the search ends where they are round-off of the start's but k · resolution is
  // smaller still.
  const double resolution =
      std::max(1e-9, 64 * std::numeric_limits<double>::epsilon() * q.lpNorm<Eigen::Infinity>());
  const double tol = std::max({k * resolution, s.m ? 1e-9 * force_scale : 0.0,
                               out.searched ? 1e-9 * force_scale : 0.0});
  Eigen::Index worst = 0;
  const double fmax = f_total.cwiseAbs().maxCoeff(&worst);
  if (!(fmax <= tol)) {
    const auto w = static_cast<std::size_t>(worst);
    rigid::detail::throw_error(kWho, fmt::format(
        "({}) is not an equilibrium{}: the generalized force on '{}' is {}{} (its acceleration "
        "{}); {}",
        point_text(s, q), steady ? " or steady motion" : "", s.coord_names[w], f_total[worst],
        s.m ? " with the constraint forces" : "", acc[worst],
        held[w] ? fmt::format("'{}' is held at the given value: give another or leave it to "
                              "the search", s.coord_names[w])
                : "give values that balance the forces"));
  }
}

// Routh reduction of the ignorable coordinates (constraints do not involve them): M̃, C̃, K̃
// over the reduced coordinates, and M_cc⁻¹ M_cr, M_cc⁻¹ C_cr for the ignorable ones' motion.
struct RouthReduction {
  Eigen::MatrixXd Mt, Ct, Kt;
  Eigen::MatrixXd Mcc_inv_Mcr, Mcc_inv_Ccr;
};

// Reduces out.M, out.C, out.K by Routh (see RouthReduction).
RouthReduction routh_reduce(const NormalModes& out, const std::vector<int>& reduced,
                            const std::vector<int>& cyc) {
  RouthReduction r;
  r.Mt = rows_cols(out.M, reduced, reduced);
  r.Ct = rows_cols(out.C, reduced, reduced);
  r.Kt = rows_cols(out.K, reduced, reduced);
  if (!cyc.empty()) {
    const Eigen::LDLT<Eigen::MatrixXd> Mcc(rows_cols(out.M, cyc, cyc));
    r.Mcc_inv_Mcr = Mcc.solve(rows_cols(out.M, cyc, reduced));
    r.Mcc_inv_Ccr = Mcc.solve(rows_cols(out.C, cyc, reduced));
    const Eigen::MatrixXd Mrc = rows_cols(out.M, reduced, cyc), Crc = rows_cols(out.C, reduced, cyc);
    r.Mt -= Mrc * r.Mcc_inv_Mcr;
    r.Ct -= Mrc * r.Mcc_inv_Ccr + Crc * r.Mcc_inv_Mcr;
    r.Kt -= Crc * r.Mcc_inv_Ccr;
  }
  return r;
}

// The constraint manifold's tangent space: δq_r = N δy with G_r N = 0 (N orthonormal, from
// the SVD of G_r); the identity without constraints.
Eigen::MatrixXd tangent_basis(const Impl& s, const Linearization& lin,
                              const std::vector<int>& reduced) {
  const auto nr = static_cast<Eigen::Index>(reduced.size());
  Eigen::MatrixXd N = Eigen::MatrixXd::Identity(nr, nr);
  if (s.m > 0) {
    Eigen::JacobiSVD<Eigen::MatrixXd> svd(columns(lin.G, reduced), Eigen::ComputeFullV);
    N = svd.matrixV().rightCols(nr - s.m);
  }
  return N;
}

// The full shape of a reduced one: δq_r = N ψ, δq̇_c = −M_cc⁻¹ (M_cr δq̇_r + C_cr δq_r),
// δq ∝ e^{λt}.
struct ShapeMap {
  int n;
  const Eigen::MatrixXd& N;
  const std::vector<int>& reduced;
  const std::vector<int>& cyc;
  const RouthReduction& routh;

  [[nodiscard]] Eigen::VectorXcd operator()(const Eigen::VectorXcd& psi, std::complex<double> lambda_k) const {
    const auto nr = static_cast<Eigen::Index>(reduced.size());
    Eigen::VectorXcd phi = N.cast<std::complex<double>>() * psi;
    // the sign (phase) of the shape in the coordinates: its largest component real and positive
    Eigen::Index largest = 0;
    phi.cwiseAbs().maxCoeff(&largest);
    if (std::abs(phi[largest]) > 0) phi *= std::abs(phi[largest]) / phi[largest];
    phi[largest] = std::abs(phi[largest]);
    Eigen::VectorXcd shape = Eigen::VectorXcd::Zero(n);
    for (Eigen::Index i = 0; i < nr; ++i) shape[reduced[static_cast<std::size_t>(i)]] = phi[i];
    if (!cyc.empty() && std::abs(lambda_k) > 0) {
      const Eigen::VectorXcd rate = -(routh.Mcc_inv_Mcr.cast<std::complex<double>>() * lambda_k +
                                      routh.Mcc_inv_Ccr.cast<std::complex<double>>()) * phi;
      for (std::size_t c = 0; c < cyc.size(); ++c) shape[cyc[c]] = rate[static_cast<Eigen::Index>(c)] / lambda_k;
    }
    return shape;
  }
};

// The modes of K φ = ω² M φ with φᵀ M φ = 1 (Cholesky of M, then a symmetric eigenproblem),
// in the tangent coordinates: their eigenvalues ±iω (or ±√−ω²) and shapes into `out`.
void symmetric_modes(const Impl& s, const Eigen::VectorXd& q, const Eigen::MatrixXd& Mh,
                     const Eigen::MatrixXd& Kh, const ShapeMap& full_shape, NormalModes& out) {
  using cd = std::complex<double>;
  const Eigen::Index nt = Mh.rows();
  const Eigen::MatrixXd Ks = (Kh + Kh.transpose()) / 2;
  Eigen::GeneralizedSelfAdjointEigenSolver<Eigen::MatrixXd> es(Ks, Mh);
  RIGID_REQUIRE_AS(kWho, es.info() == Eigen::Success, "the eigenproblem K φ = ω² M φ did not converge at ({})",
                   point_text(s, q));
  const Eigen::VectorXd mu = es.eigenvalues();  // ascending
  double largest = 0.0;  // max |μ| (a loop: GCC cannot bound Eigen's reduction of a dynamic vector)
  for (const double m : mu) largest = std::max(largest, std::abs(m));
  const double zero = 1e-9 * largest;
  out.eigenvalues.resize(2 * nt);
  for (Eigen::Index k = 0; k < nt; ++k) {
    Mode md;
    md.omega_squared = mu[k];
    if (mu[k] > zero) {
      md.eigenvalue = cd(0.0, std::sqrt(mu[k]));
      md.stability = Stability::kStable;
    } else if (mu[k] < -zero) {
      md.eigenvalue = cd(std::sqrt(-mu[k]), 0.0);
      md.stability = Stability::kUnstable;
    } else {
      md.eigenvalue = cd(0.0, 0.0);
      md.stability = Stability::kMarginal;
    }
    md.omega = md.eigenvalue.imag();
    md.hz = md.omega / (2 * std::numbers::pi);
    md.growth_rate = md.eigenvalue.real();
    const Eigen::VectorXcd psi = normalised(es.eigenvectors().col(k).cast<cd>(), Mh);
    md.shape = full_shape(psi, md.eigenvalue);
    out.eigenvalues[2 * k] = md.eigenvalue;
    out.eigenvalues[2 * k + 1] = md.stability == Stability::kUnstable ? -md.eigenvalue : std::conj(md.eigenvalue);
    out.modes.push_back(std::move(md));
  }
}

// The modes of λ x = A x with x = (δy, δẏ), A = [0 1; −M⁻¹K −M⁻¹C] (tangent coordinates):
// one per real eigenvalue or conjugate pair, sorted by ω; the eigenvalues sorted too.
void state_space_modes(const Impl& s, const Eigen::VectorXd& q, const Eigen::MatrixXd& Mh,
                       const Eigen::MatrixXd& Ch, const Eigen::MatrixXd& Kh,
                       const ShapeMap& full_shape, NormalModes& out) {
  using cd = std::complex<double>;
  const Eigen::Index nt = Mh.rows();
  const Eigen::LLT<Eigen::MatrixXd> Mr(Mh);
  Eigen::MatrixXd A = Eigen::MatrixXd::Zero(2 * nt, 2 * nt);
  A.topRightCorner(nt, nt).setIdentity();
  A.bottomLeftCorner(nt, nt) = -Mr.solve(Kh);
  A.bottomRightCorner(nt, nt) = -Mr.solve(Ch);
  Eigen::EigenSolver<Eigen::MatrixXd> es(A);
  RIGID_REQUIRE_AS(kWho, es.info() == Eigen::Success, "the state-space eigenproblem did not converge at ({})",
                   point_text(s, q));
  out.eigenvalues = es.eigenvalues();
  const double zero = 1e-6 * out.eigenvalues.cwiseAbs().maxCoeff();
  for (Eigen::Index k = 0; k < 2 * nt; ++k) {
    const cd ev_k = out.eigenvalues[k];
    const bool real = std::abs(ev_k.imag()) <= zero;
    if (!real && ev_k.imag() < 0) continue;  // its conjugate is the mode
    Mode md;
    md.eigenvalue = real ? cd(ev_k.real(), 0.0) : ev_k;
    md.omega = real ? 0.0 : ev_k.imag();
    md.hz = md.omega / (2 * std::numbers::pi);
    md.growth_rate = ev_k.real();
    md.omega_squared = std::numeric_limits<double>::quiet_NaN();
    md.stability = ev_k.real() > zero       ? Stability::kUnstable
                   : std::abs(ev_k) <= zero ? Stability::kMarginal
                                            : Stability::kStable;
    const Eigen::VectorXcd psi = normalised(es.eigenvectors().col(k).head(nt), Mh);
    md.shape = full_shape(psi, md.eigenvalue);
    out.modes.push_back(std::move(md));
  }
  std::stable_sort(out.modes.begin(), out.modes.end(), [](const Mode& a, const Mode& b) {
    return a.omega != b.omega ? a.omega < b.omega : a.growth_rate > b.growth_rate;
  });
  std::vector<cd> ev(out.eigenvalues.begin(), out.eigenvalues.end());
  std::stable_sort(ev.begin(), ev.end(), [](cd a, cd b) {
    return a.real() != b.real() ? a.real() > b.real() : a.imag() > b.imag();
  });
  for (Eigen::Index k = 0; k < 2 * nt; ++k) out.eigenvalues[k] = ev[static_cast<std::size_t>(k)];
}

// The stability of the whole motion: unstable if a mode is, else marginal if a mode is.
Stability overall_stability(const std::vector<Mode>& modes) {
  Stability stability = Stability::kStable;
  for (const Mode& md : modes) {
    if (md.stability == Stability::kUnstable) stability = Stability::kUnstable;
    else if (md.stability == Stability::kMarginal && stability == Stability::kStable) stability = Stability::kMarginal;
  }
  return stability;
}

}  // namespace

const char* to_string(Stability stability) {
  switch (stability) {
    case Stability::kStable: return "stable";
    case Stability::kMarginal: return "marginal";
    case Stability::kUnstable: return "unstable";
  }
  return "";
}

NormalModes normal_modes(const System& system, const LinearizeOptions& options) {
  // the derivatives of M and f are taken and compiled here (GiNaC)
  detail::SymbolicLock lock;
  // the System's compiled model, through a workspace's owner (the System stays immutable)
  Workspace workspace = system.make_workspace();
  const Impl& s = *Workspace::Access::impl(workspace)->owner;
  require_holonomic_and_autonomous(system, s);

  // parameters for this call
  const std::vector<double> params = parameters_for_call(s, options);
  RIGID_REQUIRE_AS(kWho, options.max_iterations > 0, "max_iterations must be positive, got {}",
                   options.max_iterations);

  const std::vector<bool> ignorable = ignorable_coordinates(s);
  StartPoint start = start_point(s, options, ignorable);
  Eigen::VectorXd& q = start.q;
  const Eigen::VectorXd& qd = start.qd;

  Linearization lin(s);
  NormalModes out;
  out.coordinate_names = s.coord_names;
  const Partition part = partition_coordinates(s, ignorable, start.held, out);
  const std::vector<int>& reduced = part.reduced;
  const std::vector<int>& cyc = part.cyc;

  // the search: Newton from the start, else continuation from the start
  lin.evaluate(q, qd, params);
  RIGID_REQUIRE_AS(kWho, lin.f.allFinite() && lin.M.allFinite() && lin.g.allFinite() && lin.G.allFinite(),
                   "the equations are not finite at the start ({}); give the point with its "
                   "coordinates' values",
                   point_text(s, q));
  Eigen::VectorXd lambda = best_multipliers(s, lin);
  const double force_scale = force_scale_at(s, lin, q, lambda);
  const double length_scale = std::max(1.0, q.lpNorm<Eigen::Infinity>());
  if (!part.unknowns.empty()) {
    search_point(s, lin, params, part.unknowns, q, qd, lambda, options.max_iterations, force_scale,
                 length_scale, out);
  }

  // the point must be an equilibrium (or steady motion) in every equation, on the constraints
  require_equilibrium(s, lin, params, q, qd, start.held, !cyc.empty(), force_scale, length_scale,
                      lambda, out);
  out.q = q;
  out.q_dot = qd;
  out.constraint_names = s.constraint_names;
  out.lambda = lambda;
  out.M = lin.M;
  out.C = lin.C;
  // the constraint forces Gᵀλ change with q too: K − Σ λ_k ∂²g_k/∂q²
  out.K = lin.K;
  for (int k = 0; k < s.m; ++k) out.K -= lambda[k] * lin.H[static_cast<std::size_t>(k)];

  // Routh reduction of the ignorable coordinates (constraints do not involve them)
  const RouthReduction routh = routh_reduce(out, reduced, cyc);
  out.M_reduced = routh.Mt;
  out.C_reduced = routh.Ct;
  out.K_reduced = routh.Kt;

  // the eigenproblem on the constraints' tangent space: Nᵀ M̃ N, Nᵀ C̃ N, Nᵀ K̃ N
  const Eigen::MatrixXd N = tangent_basis(s, lin, reduced);
  out.tangent_basis = N;
  const Eigen::MatrixXd Mh = N.transpose() * routh.Mt * N, Ch = N.transpose() * routh.Ct * N,
                        Kh = N.transpose() * routh.Kt * N;
  const Eigen::Index nt = N.cols();
  const ShapeMap full_shape{s.n, N, reduced, cyc, routh};

  if (nt == 0) {
    out.eigenvalues.resize(0);
    out.stability = Stability::kMarginal;
    return out;
  }
  const double k_norm = Kh.cwiseAbs().maxCoeff();
  const bool symmetric = (Kh - Kh.transpose()).cwiseAbs().maxCoeff() <= 1e-12 * k_norm;
  out.gyroscopic = !(Ch.cwiseAbs().maxCoeff() == 0.0 && symmetric);
  if (!out.gyroscopic) {
    symmetric_modes(s, q, Mh, Kh, full_shape, out);
  } else {
    state_space_modes(s, q, Mh, Ch, Kh, full_shape, out);
  }
  out.stability = overall_stability(out.modes);
  return out;
}

std::string to_text(const NormalModes& r) {
  std::string out = "point:";
  for (std::size_t i = 0; i < r.coordinate_names.size(); ++i) {
    const auto k = static_cast<Eigen::Index>(i);
    out += fmt::format(" {} = {}", r.coordinate_names[i], r.q[k]);
    if (r.q_dot[k] != 0.0) out += fmt::format(" ({}_dot = {})", r.coordinate_names[i], r.q_dot[k]);
  }
  out += fmt::format("\n{}, max |q̈| = {:.3g} there\n", r.searched ? fmt::format("found in {} iterations", r.iterations) : "given",
                     r.residual);
  if (!r.ignorable_names.empty()) {
    out += fmt::format("ignorable (momentum held): {}\n", fmt::join(r.ignorable_names, ", "));
  }
  out += fmt::format("stability: {}{}\n", to_string(r.stability),
                     r.gyroscopic ? " (state-space eigenproblem: gyroscopic, damping or circulatory terms)" : "");
  for (std::size_t k = 0; k < r.modes.size(); ++k) {
    const Mode& m = r.modes[k];
    out += fmt::format("mode {}: {}", k + 1, mode_word(m));
    if (m.omega > 0) out += fmt::format(", omega = {:.10g} rad/s, f = {:.10g} Hz", m.omega, m.hz);
    if (m.growth_rate != 0) out += fmt::format(", growth rate = {:.10g} 1/s", m.growth_rate);
    if (!std::isnan(m.omega_squared)) out += fmt::format(", omega^2 = {:.10g} 1/s^2", m.omega_squared);
    out += "\n  shape:";
    // parts below 1e-12 of the shape's largest component are round-off: printed as 0
    const double tiny = 1e-12 * (m.shape.size() ? m.shape.cwiseAbs().maxCoeff() : 0.0);
    for (std::size_t i = 0; i < r.coordinate_names.size(); ++i) {
      std::complex<double> c = m.shape[static_cast<Eigen::Index>(i)];
      if (std::abs(c.real()) <= tiny) c.real(0.0);
      if (std::abs(c.imag()) <= tiny) c.imag(0.0);
      if (c.imag() == 0.0) {
        out += fmt::format(" {} {:.6g}", r.coordinate_names[i], c.real());
      } else {
        out += fmt::format(" {} {:.6g}{:+.6g}i", r.coordinate_names[i], c.real(), c.imag());
      }
    }
    out += "\n";
  }
  return out;
}

}  // namespace rigid::lagrange
