#include "rigid/mass/density.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <numbers>
#include <queue>
#include <vector>

#include <boost/math/quadrature/gauss.hpp>
#include <boost/math/quadrature/gauss_kronrod.hpp>

#include "rigid/common/error.hpp"
#include "rigid/common/format.hpp"

namespace rigid::mass {
namespace {

using std::numbers::pi;

// The ten moments integrated at once: m, F = ∫ρx (3), S = ∫ρ x xᵀ (6: xx yy zz xy xz yz).
using Moments = Eigen::Matrix<double, 10, 1>;

// 15 Kronrod nodes on [−1, 1] with Kronrod weights, and the 7-point Gauss weights on the
// nodes shared with the Gauss rule (zero elsewhere).
struct Rule {
  std::array<double, 15> x{};
  std::array<double, 15> wk{};
  std::array<double, 15> wg{};
};

Rule make_rule() {
  using GK = boost::math::quadrature::gauss_kronrod<double, 15>;
  using G = boost::math::quadrature::gauss<double, 7>;
  Rule rule;
  const auto& ak = GK::abscissa();
  const auto& wk = GK::weights();
  const auto& ag = G::abscissa();
  const auto& wg = G::weights();
  auto gauss_weight = [&](double a) {
    for (std::size_t i = 0; i < ag.size(); ++i) {
      if (std::abs(ag[i] - a) < 1e-14) return wg[i];
    }
    return 0.0;
  };
  std::size_t n = 0;
  for (std::size_t i = 0; i < ak.size(); ++i) {
    rule.x[n] = ak[i];
    rule.wk[n] = wk[i];
    rule.wg[n] = gauss_weight(ak[i]);
    ++n;
    if (ak[i] != 0.0) {
      rule.x[n] = -ak[i];
      rule.wk[n] = wk[i];
      rule.wg[n] = gauss_weight(ak[i]);
      ++n;
    }
  }
  RIGID_ASSERT(n == 15);
  return rule;
}

const Rule& rule() {
  static const Rule r = make_rule();
  return r;
}

// Maps parameter coordinates t to a point x (m) and returns the Jacobian |∂x/∂t|.
using ParameterMap = std::function<double(const Eigen::Vector3d& t, Eigen::Vector3d& x)>;

struct Cell {
  Eigen::Vector3d lo;
  Eigen::Vector3d hi;
  Moments kronrod;
  Moments error;
  double worst;  // error scaled by the moment scales
};

struct Integrand {
  const DensityFunction& rho;
  const ParameterMap& map;
  const char* function;
};

void evaluate(const Integrand& f, Cell& cell) {
  const Rule& q = rule();
  const Eigen::Vector3d mid = 0.5 * (cell.lo + cell.hi);
  const Eigen::Vector3d half = 0.5 * (cell.hi - cell.lo);
  const double volume = half.prod();
  Moments k = Moments::Zero();
  Moments g = Moments::Zero();
  Eigen::Vector3d x;
  for (int i = 0; i < 15; ++i) {
    for (int j = 0; j < 15; ++j) {
      for (int l = 0; l < 15; ++l) {
        const Eigen::Vector3d t = mid + half.cwiseProduct(Eigen::Vector3d(q.x[i], q.x[j], q.x[l]));
        const double jac = f.map(t, x);
        const double density = f.rho(x);
        if (!std::isfinite(density) || density < 0.0) {
          detail::throw_error(f.function,
                              fmt::format("density must be non-negative and finite, got {} kg/m³ "
                                          "at {} m",
                                          density, to_string(x.transpose())));
        }
        const double w = density * jac * volume;
        Moments v;
        v << 1.0, x(0), x(1), x(2), x(0) * x(0), x(1) * x(1), x(2) * x(2), x(0) * x(1),
            x(0) * x(2), x(1) * x(2);
        k += (q.wk[i] * q.wk[j] * q.wk[l] * w) * v;
        const double wg = q.wg[i] * q.wg[j] * q.wg[l];
        if (wg != 0.0) g += (wg * w) * v;
      }
    }
  }
  cell.kronrod = k;
  // the Gauss–Kronrod difference [Piessens1983] overestimates the Kronrod error for smooth
  // integrands,
  // which is what makes it a safe estimate
  cell.error = (k - g).cwiseAbs();
}

DensityIntegration integrate(const Integrand& f, const Eigen::Vector3d& lo,
                             const Eigen::Vector3d& hi, double length_scale,
                             const CubatureOptions& options) {
  RIGID_REQUIRE_AS(f.function, options.relative_tolerance > 0.0 && options.max_cells >= 1,
                "relative_tolerance must be positive and max_cells at least 1, got {} and {}",
                options.relative_tolerance, options.max_cells);
  // first pass: one cell, to learn the scales
  std::vector<Cell> cells(1);
  cells[0].lo = lo;
  cells[0].hi = hi;
  evaluate(f, cells[0]);
  const double mass_scale = std::abs(cells[0].kronrod(0));
  Moments scale;
  scale << mass_scale, Eigen::Vector3d::Constant(mass_scale * length_scale),
      Eigen::Matrix<double, 6, 1>::Constant(mass_scale * length_scale * length_scale);
  auto worst = [&](const Moments& e) {
    return (e.array() / scale.array().max(1e-300)).maxCoeff();
  };
  cells[0].worst = worst(cells[0].error);
  auto cmp = [&](std::size_t a, std::size_t b) { return cells[a].worst < cells[b].worst; };
  std::priority_queue<std::size_t, std::vector<std::size_t>, decltype(cmp)> queue(cmp);
  queue.push(0);
  Moments total_error = cells[0].error;
  bool converged = worst(total_error) <= options.relative_tolerance;
  int active = 1;
  while (!converged && active + 7 <= options.max_cells) {
    // split the worst cell into 8 and replace its contribution
    const std::size_t w = queue.top();
    queue.pop();
    const Cell parent = cells[w];
    total_error -= parent.error;
    cells[w].kronrod.setZero();
    cells[w].error.setZero();
    const Eigen::Vector3d mid = 0.5 * (parent.lo + parent.hi);
    for (int c = 0; c < 8; ++c) {
      Cell child;
      for (int d = 0; d < 3; ++d) {
        const bool upper = (c >> d) & 1;
        child.lo(d) = upper ? mid(d) : parent.lo(d);
        child.hi(d) = upper ? parent.hi(d) : mid(d);
      }
      evaluate(f, child);
      child.worst = worst(child.error);
      total_error += child.error;
      cells.push_back(child);
      queue.push(cells.size() - 1);
    }
    active += 7;
    converged = worst(total_error) <= options.relative_tolerance;
  }
  Moments total = Moments::Zero();
  for (const Cell& c : cells) total += c.kronrod;
  const double m = total(0);
  RIGID_REQUIRE_AS(f.function, m > 0.0, "the density integrates to a mass of {} kg; expected a positive mass", m);
  const Eigen::Vector3d F = total.segment<3>(1);
  Eigen::Matrix3d S;
  S << total(4), total(7), total(8), total(7), total(5), total(9), total(8), total(9), total(6);
  const Eigen::Vector3d c = F / m;
  const Eigen::Matrix3d S_c = S - m * c * c.transpose();
  const Eigen::Matrix3d I = S_c.trace() * Eigen::Matrix3d::Identity() - S_c;
  // error propagation (first order): c = F/m; S_c = S − F Fᵀ/m; I = tr(S_c) 1 − S_c.
  const double eF = total_error.segment<3>(1).maxCoeff();
  const double eS = total_error.tail<6>().maxCoeff();
  const double em = total_error(0);
  const double com_error = eF / m + c.cwiseAbs().maxCoeff() * em / m;
  const double eSc = eS + 2.0 * c.cwiseAbs().maxCoeff() * eF + c.squaredNorm() * em;
  return DensityIntegration{MassProperties(m, c, I), em, com_error, 4.0 * eSc,
                            active, converged};
}

void require_size(const char* fn, const char* name, double v) {
  if (!std::isfinite(v) || !(v > 0.0)) {
    detail::throw_error(fn, fmt::format("{} must be positive and finite, got {} m", name, v));
  }
}

}  // namespace

DensityIntegration integrate_density_over_box(const DensityFunction& rho, double lx, double ly,
                                              double lz, const CubatureOptions& options) {
  require_size(__func__, "lx", lx);
  require_size(__func__, "ly", ly);
  require_size(__func__, "lz", lz);
  const ParameterMap map = [](const Eigen::Vector3d& t, Eigen::Vector3d& x) {
    x = t;
    return 1.0;
  };
  const Eigen::Vector3d half(lx / 2, ly / 2, lz / 2);
  return integrate(Integrand{rho, map, __func__}, -half, half, half.norm(), options);
}

DensityIntegration integrate_density_over_cylinder(const DensityFunction& rho, double r, double h,
                                                   const CubatureOptions& options) {
  require_size(__func__, "radius", r);
  require_size(__func__, "height", h);
  // (s, θ, z) ↦ (s cos θ, s sin θ, z), dV = s ds dθ dz
  const ParameterMap map = [](const Eigen::Vector3d& t, Eigen::Vector3d& x) {
    x = Eigen::Vector3d(t(0) * std::cos(t(1)), t(0) * std::sin(t(1)), t(2));
    return t(0);
  };
  return integrate(Integrand{rho, map, __func__}, Eigen::Vector3d(0, 0, -h / 2),
                   Eigen::Vector3d(r, 2 * pi, h / 2), std::hypot(r, h / 2), options);
}

DensityIntegration integrate_density_over_sphere(const DensityFunction& rho, double r,
                                                 const CubatureOptions& options) {
  require_size(__func__, "radius", r);
  // (s, θ, φ) ↦ s (sin θ cos φ, sin θ sin φ, cos θ), dV = s² sin θ ds dθ dφ
  const ParameterMap map = [](const Eigen::Vector3d& t, Eigen::Vector3d& x) {
    const double st = std::sin(t(1));
    x = t(0) * Eigen::Vector3d(st * std::cos(t(2)), st * std::sin(t(2)), std::cos(t(1)));
    return t(0) * t(0) * st;
  };
  return integrate(Integrand{rho, map, __func__}, Eigen::Vector3d::Zero(),
                   Eigen::Vector3d(r, pi, 2 * pi), r, options);
}

}  // namespace rigid::mass
