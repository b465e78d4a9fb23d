#include "rigid/mass/density.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <numbers>
#include <queue>
#include <span>
#include <vector>

#include <Eigen/Geometry>
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

// The mass properties of the moments `total` about `origin` (m, F, S relative to it), with the
// first-order propagation of their estimated errors.
DensityIntegration finish(const char* function, const Moments& total, const Moments& total_error,
                          const Eigen::Vector3d& origin, int cells, bool converged) {
  const double m = total(0);
  RIGID_REQUIRE_AS(function, m > 0.0, "the density integrates to a mass of {} kg; expected a positive mass", m);
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
  return DensityIntegration{MassProperties(m, origin + c, I), em, com_error, 4.0 * eSc,
                            cells, converged};
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
  return finish(f.function, total, total_error, Eigen::Vector3d::Zero(), active, converged);
}


// ---- a closed triangle mesh: signed tetrahedra from a reference point ----
//
// The solid a closed, consistently oriented mesh bounds is the signed sum of the tetrahedra
// (O, a, b, c) from any point O to its triangles (a triangle seen from O's side takes a
// negative volume): ∫_V g = Σ_faces ∫_{tet(O, face)} g for any g defined on those
// tetrahedra, the volume formula of the mesh module with g = ρ·(1, x, x xᵀ) in place of 1. On
// each tetrahedron the Grundmann–Möller rules of degree 7 (35 points) and 9 (70 points)
// [A. Grundmann, H. M. Möller, "Invariant integration formulas for the n-simplex by
// combinatorial methods", SIAM J. Numer. Anal. 15(2), 1978, Theorem 4] give the moments and,
// by their difference, an error estimate; the tetrahedron with the worst is split into eight
// (its corners and the central octahedron cut along a diagonal, each 1/8 of the volume) until
// the estimate meets the tolerance.

// A Grundmann–Möller rule on the standard tetrahedron (volume 1/6): barycentric points and
// weights; exact for polynomials of degree 2s + 1 (the weights of odd i are negative).
struct SimplexRule {
  std::vector<std::array<double, 4>> lambda;
  std::vector<double> weight;
};

SimplexRule grundmann_moeller(int s) {
  constexpr int n = 3;
  const int d = 2 * s + 1;
  SimplexRule r;
  double factorial_i = 1;
  for (int i = 0; i <= s; ++i) {
    if (i > 0) factorial_i *= i;
    const int den = d + n - 2 * i;
    double factorial_rest = 1;  // (d + n − i)!
    for (int k = 2; k <= d + n - i; ++k) factorial_rest *= k;
    const double w = (i % 2 == 0 ? 1.0 : -1.0) * std::ldexp(1.0, -2 * s) *
                     std::pow(static_cast<double>(den), d) / (factorial_i * factorial_rest);
    const int k = s - i;  // the points: β ∈ ℕ⁴ with |β| = k, λ = (2β + 1) / den
    for (int b0 = 0; b0 <= k; ++b0) {
      for (int b1 = 0; b0 + b1 <= k; ++b1) {
        for (int b2 = 0; b0 + b1 + b2 <= k; ++b2) {
          const int b3 = k - b0 - b1 - b2;
          r.lambda.push_back({(2.0 * b0 + 1) / den, (2.0 * b1 + 1) / den, (2.0 * b2 + 1) / den,
                              (2.0 * b3 + 1) / den});
          r.weight.push_back(w);
        }
      }
    }
  }
  return r;
}

struct Tetrahedron {
  std::array<Eigen::Vector3d, 4> p;  // relative to the reference point
  double det = 0;                    // signed: 6 × the volume
  Moments value;                     // the degree-9 moments, relative to the reference point
  Moments error;
  double worst = 0;
};

// The moments of ρ over t (signed), about the reference point `origin` (ρ is given points
// relative to the world origin: origin + x).
void evaluate(const DensityFunction& rho, const Eigen::Vector3d& origin, const char* function,
              Tetrahedron& t) {
  static const SimplexRule low = grundmann_moeller(3), high = grundmann_moeller(4);
  const auto moments = [&](const SimplexRule& r) {
    Moments sum = Moments::Zero();
    for (std::size_t k = 0; k < r.weight.size(); ++k) {
      const auto& l = r.lambda[k];
      const Eigen::Vector3d x = l[0] * t.p[0] + l[1] * t.p[1] + l[2] * t.p[2] + l[3] * t.p[3];
      const Eigen::Vector3d at = origin + x;
      const double density = rho(at);
      if (!std::isfinite(density) || density < 0.0) {
        detail::throw_error(function,
                            fmt::format("density must be non-negative and finite, got {} kg/m³ "
                                        "at {} m",
                                        density, to_string(at.transpose())));
      }
      Moments v;
      v << 1.0, x(0), x(1), x(2), x(0) * x(0), x(1) * x(1), x(2) * x(2), x(0) * x(1),
          x(0) * x(2), x(1) * x(2);
      sum += (r.weight[k] * density) * v;
    }
    return Moments(t.det * sum);
  };
  t.value = moments(high);
  t.error = (t.value - moments(low)).cwiseAbs();
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

DensityIntegration integrate_density_over_mesh(const DensityFunction& rho,
                                               std::span<const Eigen::Vector3d> vertices,
                                               std::span<const std::array<std::uint32_t, 3>> triangles,
                                               const CubatureOptions& options) {
  RIGID_REQUIRE_AS(__func__, options.relative_tolerance > 0.0 && options.max_cells >= 1,
                   "relative_tolerance must be positive and max_cells at least 1, got {} and {}",
                   options.relative_tolerance, options.max_cells);
  RIGID_REQUIRE_AS(__func__, !triangles.empty(), "the mesh has no triangles");
  // closed and consistently oriented: each directed edge once, and its reverse once (an open or
  // mis-wound mesh bounds no solid, and its tetrahedra would sum to a wrong volume silently)
  {
    std::vector<std::uint64_t> edges, reversed;
    edges.reserve(3 * triangles.size());
    reversed.reserve(3 * triangles.size());
    for (const auto& t : triangles) {
      for (std::size_t k = 0; k < 3; ++k) {
        RIGID_REQUIRE_AS(__func__, t[k] < vertices.size(),
                         "a triangle names vertex {}; the mesh has {}", t[k], vertices.size());
        const std::uint64_t a = t[k], b = t[(k + 1) % 3];
        edges.push_back(a << 32 | b);
        reversed.push_back(b << 32 | a);
      }
    }
    std::sort(edges.begin(), edges.end());
    std::sort(reversed.begin(), reversed.end());
    const auto repeated = std::adjacent_find(edges.begin(), edges.end());
    if (repeated != edges.end() || edges != reversed) {
      const std::uint64_t e = repeated != edges.end() ? *repeated : [&] {
        const auto m = std::mismatch(edges.begin(), edges.end(), reversed.begin());
        return m.first != edges.end() ? *m.first : 0;
      }();
      detail::throw_error(
          __func__, fmt::format("the mesh is not closed and consistently oriented (edge {} → {} "
                                "{}); a density field is integrated over the solid a closed "
                                "mesh bounds: repair it first (mesh::repair_mesh)",
                                e >> 32, e & 0xFFFFFFFFu,
                                repeated != edges.end() ? "is used twice in the same direction"
                                                        : "has no triangle on its other side"));
    }
  }
  // the reference point: the centroid of the vertices, inside a convex solid, so that the
  // tetrahedra stay inside it (and their round-off small)
  Eigen::Vector3d lo = Eigen::Vector3d::Constant(HUGE_VAL), hi = -lo;
  Eigen::Vector3d origin = Eigen::Vector3d::Zero();
  for (const Eigen::Vector3d& v : vertices) {
    RIGID_REQUIRE_AS(__func__, v.allFinite(), "a vertex is not finite: {}", to_string(v.transpose()));
    origin += v;
    lo = lo.cwiseMin(v);
    hi = hi.cwiseMax(v);
  }
  origin /= static_cast<double>(vertices.size());
  const double length = (hi - lo).norm();
  std::vector<Tetrahedron> tets;
  tets.reserve(triangles.size());
  Moments total_error = Moments::Zero();
  for (const auto& tri : triangles) {
    Tetrahedron t;
    t.p[0] = Eigen::Vector3d::Zero();
    for (std::size_t k = 0; k < 3; ++k) {
      t.p[k + 1] = vertices[tri[k]] - origin;
    }
    t.det = t.p[1].dot(t.p[2].cross(t.p[3]));
    if (t.det == 0) continue;  // a triangle in a plane through the reference point: no volume
    evaluate(rho, origin, __func__, t);
    total_error += t.error;
    tets.push_back(t);
  }
  Moments total = Moments::Zero();
  for (const Tetrahedron& t : tets) total += t.value;
  const double mass_scale = std::abs(total(0));
  RIGID_REQUIRE_AS(__func__, mass_scale > 0.0,
                   "the density integrates to a mass of {} kg; expected a positive mass", total(0));
  Moments scale;
  scale << mass_scale, Eigen::Vector3d::Constant(mass_scale * length),
      Eigen::Matrix<double, 6, 1>::Constant(mass_scale * length * length);
  const auto worst = [&](const Moments& e) { return (e.array() / scale.array()).maxCoeff(); };
  auto cmp = [&](std::size_t a, std::size_t b) { return tets[a].worst < tets[b].worst; };
  std::priority_queue<std::size_t, std::vector<std::size_t>, decltype(cmp)> queue(cmp);
  for (std::size_t k = 0; k < tets.size(); ++k) {
    tets[k].worst = worst(tets[k].error);
    queue.push(k);
  }
  bool converged = worst(total_error) <= options.relative_tolerance;
  // the subdivisions a box would get (max_cells cells of 15³ points, 7 added per split) in
  // tetrahedra of 105 points: 32× as many, beyond one per triangle
  const std::size_t limit = tets.size() + 32 * static_cast<std::size_t>(options.max_cells);
  while (!converged && tets.size() + 7 <= limit && !queue.empty()) {
    const std::size_t w = queue.top();
    queue.pop();
    const Tetrahedron parent = tets[w];
    total -= parent.value;
    total_error -= parent.error;
    const auto& P = parent.p;
    const auto mid = [&](int a, int b) -> Eigen::Vector3d { return 0.5 * (P[a] + P[b]); };
    const Eigen::Vector3d m01 = mid(0, 1), m02 = mid(0, 2), m03 = mid(0, 3), m12 = mid(1, 2),
                          m13 = mid(1, 3), m23 = mid(2, 3);
    // the four corners, and the octahedron around its diagonal m02–m13 (its other vertices
    // m01, m03, m23, m12 in order round it)
    const std::array<std::array<Eigen::Vector3d, 4>, 8> children = {{
        {P[0], m01, m02, m03},
        {m01, P[1], m12, m13},
        {m02, m12, P[2], m23},
        {m03, m13, m23, P[3]},
        {m02, m13, m01, m03},
        {m02, m13, m03, m23},
        {m02, m13, m23, m12},
        {m02, m13, m12, m01},
    }};
    for (std::size_t c = 0; c < children.size(); ++c) {
      Tetrahedron t;
      t.p = children[c];
      // each child is 1/8 of the parent, with the parent's orientation
      t.det = parent.det / 8;
      evaluate(rho, origin, __func__, t);
      t.worst = worst(t.error);
      total += t.value;
      total_error += t.error;
      if (c == 0) {
        tets[w] = t;
        queue.push(w);
      } else {
        tets.push_back(t);
        queue.push(tets.size() - 1);
      }
    }
    converged = worst(total_error) <= options.relative_tolerance;
  }
  DensityIntegration out =
      finish(__func__, total, total_error, origin, static_cast<int>(tets.size()), converged);
  out.points_per_cell = 35 + 70;  // the rules of degree 7 and 9
  return out;
}

}  // namespace rigid::mass
