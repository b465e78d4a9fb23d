#include "rigid/integrate/integrator.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <optional>
#include <vector>

#include <Eigen/LU>
#include <boost/numeric/odeint/integrate/null_observer.hpp>
#include <boost/numeric/odeint/util/odeint_error.hpp>
#include <boost/numeric/odeint/stepper/generation.hpp>
#include <boost/numeric/odeint/stepper/runge_kutta4.hpp>
#include <boost/numeric/odeint/stepper/runge_kutta_dopri5.hpp>
#include <fmt/format.h>

#include "rigid/common/did_you_mean.hpp"
#include "rigid/common/error.hpp"

namespace rigid::integrate {
namespace {

namespace odeint = boost::numeric::odeint;

// The most memory the implicit midpoint's Jacobian and LU may take (2 GiB: a state of 11,585):
// a larger state is refused before the run rather than failing to allocate.
constexpr double kMaxJacobianBytes = 2.0 * 1024 * 1024 * 1024;
using StdState = std::vector<double>;

std::string component_name(const Problem& p, Eigen::Index i) {
  if (static_cast<std::size_t>(i) < p.names.size()) return p.names[static_cast<std::size_t>(i)];
  return fmt::format("y[{}]", i);
}

// the first non-finite component of y, named (checked after every step, as MuJoCo's
// mj_checkPos)
std::optional<NonFinite> find_nonfinite(const Problem& p, const Eigen::VectorXd& y) {
  if (auto i = first_nonfinite({y.data(), static_cast<std::size_t>(y.size())})) [[unlikely]] {
    return NonFinite{p.owner, component_name(p, static_cast<Eigen::Index>(*i)),
                     y[static_cast<Eigen::Index>(*i)]};
  }
  return std::nullopt;
}

// adapts the Eigen right-hand side to odeint's std::vector state
struct OdeintSystem {
  const Problem* problem;
  Eigen::VectorXd* y;
  Eigen::VectorXd* dydt;
  std::size_t* evaluations;
  void operator()(const StdState& x, StdState& dxdt, double t) const {
    *y = Eigen::Map<const Eigen::VectorXd>(x.data(), static_cast<Eigen::Index>(x.size()));
    problem->rhs(t, *y, *dydt);
    ++*evaluations;
    Eigen::Map<Eigen::VectorXd>(dxdt.data(), static_cast<Eigen::Index>(dxdt.size())) = *dydt;
  }
};

// one implicit-midpoint step y1 = y0 + h f(t + h/2, (y0 + y1)/2), solved by a simplified
// Newton iteration on k = (y1 - y0)/h: (1 - h/2 J) δk = f(t + h/2, y0 + h/2 k) - k, with a
// forward-difference Jacobian J ≈ ∂f/∂y. J and its LU factors are kept from step to step and
// refreshed when the step size changes or the iteration converges slowly (> 4 iterations)
// or fails; the fixed point does not depend on J, only the speed of convergence does. A step
// whose iteration does not converge, with the kept Jacobian and then with a fresh one, is
// refused with h, the residual of the implicit equation and the tolerance (the march puts the
// step number and t in front).
class ImplicitMidpoint {
 public:
  ImplicitMidpoint(const Problem& p, const Options& o, std::size_t* evals)
      : p_(p), o_(o), evals_(evals) {
    const auto n = p.y0.size();
    k_.resize(n);
    f_.resize(n);
    f0_.resize(n);
    fp_.resize(n);
    ym_.resize(n);
    J_.resize(n, n);
  }

  void step(double t, double h, Eigen::VectorXd& y) {
    const double tm = t + 0.5 * h;
    // explicit predictor k = f(t + h/2, y0)
    p_.rhs(tm, y, f0_);
    ++*evals_;
    if (!have_jacobian_ || h != h_) refresh(tm, h, y);
    for (int attempt = 0; attempt < 2; ++attempt) {
      k_ = f0_;
      const int iterations = newton(tm, h, y);
      if (iterations >= 0) {
        y += h * k_;
        if (iterations > 4) have_jacobian_ = false;
        return;
      }
      refresh(tm, h, y);  // a stale Jacobian may be the cause: retry once with a fresh one
    }
    detail::throw_error(
        "integrate",
        fmt::format("implicit midpoint: the Newton iteration did not converge in {} iterations "
                    "(with the kept Jacobian, then with a fresh one): h = {} s; the residual of "
                    "the implicit equation, |y1 − y0 − h f(t + h/2, (y0 + y1)/2)|∞ = {:.3g}, and "
                    "the last correction {:.3g} are above the tolerance {:.3g} (newton_tol · "
                    "max(1, |y0|∞)); use a smaller step dt",
                    o_.max_newton, h, residual_, correction_, o_.newton_tol * scale_of(y)));
  }

 private:
  // forward-difference Jacobian at y0 (step √ε·max(1, |y_j|)) and the LU of 1 - h/2 J
  void refresh(double tm, double h, const Eigen::VectorXd& y) {
    const auto n = y.size();
    for (Eigen::Index j = 0; j < n; ++j) {
      ym_ = y;
      const double e = 1.4901161193847656e-08 * std::max(1.0, std::abs(y[j]));
      ym_[j] += e;
      p_.rhs(tm, ym_, fp_);
      ++*evals_;
      J_.col(j) = (fp_ - f0_) / e;
    }
    lu_.compute(Eigen::MatrixXd::Identity(n, n) - 0.5 * h * J_);
    have_jacobian_ = true;
    h_ = h;
  }

  static double scale_of(const Eigen::VectorXd& y) {
    return std::max(1.0, y.lpNorm<Eigen::Infinity>());
  }

  // iterations used, or -1 when not converged (residual_ and correction_ then say how far)
  int newton(double tm, double h, const Eigen::VectorXd& y) {
    double prev = std::numeric_limits<double>::infinity();
    const double scale = scale_of(y);
    for (int it = 1; it <= o_.max_newton; ++it) {
      ym_ = y + 0.5 * h * k_;
      p_.rhs(tm, ym_, f_);
      ++*evals_;
      // residual of y1 = y0 + h k in y1 − y0 − h f(t + h/2, (y0 + y1)/2) = −h (f − k)
      residual_ = h * (f_ - k_).lpNorm<Eigen::Infinity>();
      dk_ = lu_.solve(f_ - k_);
      k_ += dk_;
      const double size = h * dk_.lpNorm<Eigen::Infinity>();
      correction_ = size;
      if (!std::isfinite(size)) return -1;
      // converged at the tolerance, or stalled at round-off just above it
      if (size <= o_.newton_tol * scale || (size >= prev && size <= 1e3 * o_.newton_tol * scale)) {
        return it;
      }
      prev = size;
    }
    return -1;
  }

  const Problem& p_;
  const Options& o_;
  std::size_t* evals_;
  Eigen::VectorXd k_, f_, f0_, fp_, ym_, dk_;
  Eigen::MatrixXd J_;
  Eigen::PartialPivLU<Eigen::MatrixXd> lu_;
  bool have_jacobian_ = false;
  double h_ = 0.0;
  double residual_ = 0.0;    // of the last iterate evaluated
  double correction_ = 0.0;  // the last Newton correction h |δk|∞
};

MarchControl control_of(const Options& o) {
  MarchControl c = o.control;
  c.max_steps = std::min(c.max_steps, o.max_steps);
  return c;
}

Solution run_fixed(const Problem& p, const Options& o) {
  // outputs every output_dt (or every step); between two outputs the fewest equal steps ≤ dt
  const TimeGrid grid = TimeGrid::uniform(p.t0, p.t_end, o.output_dt > 0 ? o.output_dt : o.dt);
  Solution sol;
  sol.t.reserve(grid.size());
  sol.y.reserve(grid.size());
  Eigen::VectorXd y = p.y0;
  const auto n = y.size();
  Eigen::VectorXd a(n);

  Eigen::Index np = p.n_position;
  if (o.method == Method::kStormerVerlet) {
    if (np < 0) {
      RIGID_REQUIRE_AS("integrate", n % 2 == 0,
                    "Störmer–Verlet needs y = (q, v) of even size or n_position, got size {}", n);
      np = n / 2;
    }
    RIGID_REQUIRE_AS("integrate", 2 * np == n, "Störmer–Verlet needs y = (q, v) with |q| = |v|, got n_position "
                  "= {} for a state of size {}", np, n);
  }

  odeint::runge_kutta4<StdState> rk4;
  StdState x(static_cast<std::size_t>(n));
  Eigen::VectorXd ybuf(n), dbuf(n);
  OdeintSystem sys{&p, &ybuf, &dbuf, &sol.rhs_evaluations};
  // only the implicit midpoint keeps a Jacobian (dense, n × n, and its LU): the other methods
  // need memory linear in the state's size
  std::optional<ImplicitMidpoint> midpoint;
  if (o.method == Method::kImplicitMidpoint) {
    const double bytes = 2.0 * sizeof(double) * static_cast<double>(n) * static_cast<double>(n);
    RIGID_REQUIRE_AS("integrate", bytes <= kMaxJacobianBytes,
                     "implicit midpoint keeps a dense n × n Jacobian and its LU: a state of size {} "
                     "needs {:.3g} GB for them, more than the {:.3g} GB allowed; use rk4, "
                     "stormer_verlet or dopri5, whose memory is linear in the state's size",
                     n, bytes / 1e9, kMaxJacobianBytes / 1e9);
    midpoint.emplace(p, o, &sol.rhs_evaluations);
  }

  bool have_accel = false;  // Störmer–Verlet reuses a(t1, q1) as the next step's a(t0, q0)
  auto step = [&](double t, double h) {
    switch (o.method) {
      case Method::kRk4:
        Eigen::Map<Eigen::VectorXd>(x.data(), n) = y;
        rk4.do_step(sys, x, t, h);
        y = Eigen::Map<const Eigen::VectorXd>(x.data(), n);
        break;
      case Method::kImplicitMidpoint:
        midpoint->step(t, h, y);
        break;
      case Method::kStormerVerlet:
        // v_{1/2} = v0 + h/2 a(t0, q0); q1 = q0 + h v_{1/2}; v1 = v_{1/2} + h/2 a(t1, q1)
        if (!have_accel) {
          p.rhs(t, y, a);
          ++sol.rhs_evaluations;
        }
        y.tail(np) += 0.5 * h * a.tail(np);
        y.head(np) += h * y.tail(np);
        p.rhs(t + h, y, a);
        ++sol.rhs_evaluations;
        y.tail(np) += 0.5 * h * a.tail(np);
        have_accel = true;
        break;
      case Method::kDopri5:
        RIGID_ASSERT(false);
        break;
    }
  };
  auto observe = [&](std::size_t, double t) {
    sol.t.push_back(t);
    sol.y.push_back(y);
  };
  MarchControl control = control_of(o);
  if (control.on_step) {
    // the march knows the step's span; the state is ours
    control.on_step = [&y, &outer = o.control.on_step](const StepView& v) {
      outer(StepView{v.t0, v.t1, {y.data(), static_cast<std::size_t>(y.size())}, {}});
    };
  }
  sol.steps = march(grid, o.dt, step, [&] { return find_nonfinite(p, y); }, observe, control).steps;
  return sol;
}

Solution run_dopri5(const Problem& p, const Options& o) {
  Solution sol;
  const MarchControl control = control_of(o);
  const auto n = p.y0.size();
  Eigen::VectorXd ybuf(n), dbuf(n);
  OdeintSystem sys{&p, &ybuf, &dbuf, &sol.rhs_evaluations};
  auto stepper = odeint::make_dense_output(o.atol, o.rtol, odeint::runge_kutta_dopri5<StdState>());
  StdState x0(p.y0.data(), p.y0.data() + n);
  stepper.initialize(x0, p.t0, std::min(o.dt, p.t_end - p.t0));
  // output times of the one grid rule (dense output between steps), or every accepted step
  StdState xo(static_cast<std::size_t>(n));
  std::optional<TimeGrid> grid;
  if (o.output_dt > 0) grid = TimeGrid::uniform(p.t0, p.t_end, o.output_dt);
  // the rows of a grid are known before the run (the front end checks them); only every-step
  // sampling is capped here, as the rows come
  const std::size_t max_outputs = grid ? TimeGrid::kMaxOutputs : std::min(control.max_outputs, TimeGrid::kMaxOutputs);
  auto sample = [&](double t, const StdState& state) {
    RIGID_REQUIRE_AS("integrate", sol.t.size() < max_outputs,
                  "dopri5 without an output spacing records every step: more than {} rows before "
                  "t_end = {} s (at t = {} s), the most this run may record; set an output spacing "
                  "(output_dt)",
                  max_outputs, p.t_end, t);
    sol.t.push_back(t);
    sol.y.emplace_back(Eigen::Map<const Eigen::VectorXd>(state.data(), n));
  };
  sol.t.push_back(p.t0);
  sol.y.push_back(p.y0);
  std::size_t next_output = 1;  // grid index of the next sample (output 0 is t0)
  double h_last = 0.0;
  while (stepper.current_time() < p.t_end) {
    RIGID_REQUIRE_AS("integrate", sol.steps < control.max_steps, "dopri5 took more than max_steps = {} steps before "
                  "t_end = {} s (at t = {} s)", control.max_steps, p.t_end, stepper.current_time());
    const double before = stepper.current_time();
    try {
      stepper.do_step(sys);
    } catch (const odeint::step_adjustment_error&) {
      // odeint gave up shrinking the step (500 rejections in a row)
      detail::throw_error("integrate",
                          fmt::format("dopri5 found no step size that meets the tolerance (rtol = {}, "
                                      "atol = {}) at t = {} s after 500 rejected tries; the problem is "
                                      "stiff or not smooth here: loosen the tolerance or use "
                                      "implicit_midpoint",
                                      o.rtol, o.atol, before));
    }
    ++sol.steps;
    const StdState& xc = stepper.current_state();
    const double tc = stepper.current_time();
    h_last = tc - before;
    // a step at the round-off of t: the time would stand still (and every-step output grow)
    const double floor = kStepFloor * std::numeric_limits<double>::epsilon() *
                         std::max(std::abs(before), p.t_end - p.t0);
    if (!(h_last > floor) && tc < p.t_end) [[unlikely]] {
      detail::throw_error("integrate",
                          fmt::format("dopri5 step size underflow at t = {} s: the accepted step {} s "
                                      "is at the round-off of t (below {} s), so time no longer "
                                      "advances; the problem is stiff or singular here: loosen the "
                                      "tolerance (rtol = {}) or use implicit_midpoint",
                                      before, h_last, floor, o.rtol));
    }
    const Eigen::Map<const Eigen::VectorXd> yc(xc.data(), n);
    if (auto bad = find_nonfinite(p, yc)) throw_nonfinite(*bad, sol.steps, tc, h_last);
    if (control.on_step) {
      // the continuous extension of the step just taken (valid on [before, tc])
      control.on_step(StepView{before, tc, {xc.data(), xc.size()}, [&stepper](double t, std::span<double> out) {
                                 StdState x(out.size());
                                 stepper.calc_state(t, x);
                                 std::copy(x.begin(), x.end(), out.begin());
                               }});
    }
    if (grid) {
      // dense output at every sample time passed by this step
      while (next_output < grid->size() && (*grid)[next_output] <= tc) {
        stepper.calc_state((*grid)[next_output], xo);
        sample((*grid)[next_output], xo);
        ++next_output;
      }
    } else if (tc <= p.t_end) {
      sample(tc, xc);
    } else {
      stepper.calc_state(p.t_end, xo);
      sample(p.t_end, xo);
    }
    poll(control, std::min(tc, p.t_end));
  }
  if (sol.t.back() < p.t_end) {  // round-off in the sample times: close on t_end exactly
    stepper.calc_state(p.t_end, xo);
    sample(p.t_end, xo);
  }
  return sol;
}

}  // namespace

std::string_view to_string(Method method) {
  switch (method) {
    case Method::kRk4: return "rk4";
    case Method::kDopri5: return "dopri5";
    case Method::kImplicitMidpoint: return "implicit_midpoint";
    case Method::kStormerVerlet: return "stormer_verlet";
  }
  return "?";
}

Method parse_method(std::string_view name) {
  for (Method m : {Method::kRk4, Method::kDopri5, Method::kImplicitMidpoint,
                   Method::kStormerVerlet}) {
    if (name == to_string(m)) return m;
  }
  RIGID_THROW("unknown integrator '{}'; expected one of rk4, dopri5, implicit_midpoint, "
              "stormer_verlet{}",
              name, did_you_mean_hint(name, {"rk4", "dopri5", "implicit_midpoint", "stormer_verlet"}));
}

std::string tolerance_above_bound(std::string_view what, double value) {
  return fmt::format("{} = {} is above {}, the loosest tolerance an error control honours (10% "
                     "of the state per step; beyond it the steps are limited by stability "
                     "alone and the result is not a solution); expected {} ≤ {}",
                     what, value, kMaxTolerance, what, kMaxTolerance);
}

Solution integrate(const Problem& problem, const Options& options) {
  RIGID_REQUIRE(static_cast<bool>(problem.rhs), "the problem has no right-hand side");
  RIGID_REQUIRE(problem.y0.size() > 0, "the initial state is empty");
  RIGID_REQUIRE(std::isfinite(problem.t0) && std::isfinite(problem.t_end) &&
                    problem.t_end > problem.t0,
                "t_end = {} s must be finite and greater than t0 = {} s", problem.t_end,
                problem.t0);
  RIGID_REQUIRE(std::isfinite(options.dt) && options.dt > 0,
                "dt must be positive and finite, got {} s", options.dt);
  RIGID_REQUIRE(std::isfinite(options.output_dt) && options.output_dt >= 0,
                "output_dt must be ≥ 0 (0: every step), got {} s", options.output_dt);
  RIGID_REQUIRE(options.rtol > 0 && options.atol > 0 && std::isfinite(options.rtol) &&
                    std::isfinite(options.atol),
                "tolerances must be positive and finite, got rtol = {}, atol = {}", options.rtol,
                options.atol);
  RIGID_REQUIRE(
      options.method != Method::kImplicitMidpoint ||
          (options.max_newton >= 1 && std::isfinite(options.newton_tol) && options.newton_tol > 0),
      "the implicit midpoint needs max_newton ≥ 1 and a positive, finite newton_tol, got {} "
      "and {}",
      options.max_newton, options.newton_tol);
  RIGID_REQUIRE(options.method != Method::kDopri5 || options.rtol >= kMinRelativeTolerance,
                "dopri5 relative tolerance rtol = {} is below what double precision can deliver; "
                "expected rtol ≥ {:.3g} (10 ε)",
                options.rtol, kMinRelativeTolerance);
  if (options.method == Method::kDopri5) {
    if (options.rtol > kMaxTolerance) RIGID_THROW("{}", tolerance_above_bound("rtol", options.rtol));
    if (options.atol > kMaxTolerance) RIGID_THROW("{}", tolerance_above_bound("atol", options.atol));
  }
  if (auto bad = find_nonfinite(problem, problem.y0)) {
    RIGID_THROW("the initial state is not finite: {}{} = {}",
                bad->owner.empty() ? "" : bad->owner + " ", bad->component, bad->value);
  }
  if (options.method == Method::kDopri5) return run_dopri5(problem, options);
  return run_fixed(problem, options);
}

}  // namespace rigid::integrate
