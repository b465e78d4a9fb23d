#pragma once

// Independent reference for the mass tests: mass properties of a body described by a
// smooth map from the unit cube u ∈ [0,1]³ to points x(u) with Jacobian |det ∂x/∂u|, by
// tensor-product Gauss–Legendre quadrature (nodes from Boost.Math). Comparing two orders
// (20 and 30 points per axis) gives the error estimate the tests use as a tolerance.

#include <algorithm>
#include <cmath>
#include <functional>
#include <limits>
#include <vector>

#include <Eigen/Core>
#include <boost/math/quadrature/gauss.hpp>

namespace rigid::test {

struct MappedPoint {
  Eigen::Vector3d x;  // m
  double weight;      // density × Jacobian (kg per unit u-volume)
};

using BodyMap = std::function<MappedPoint(const Eigen::Vector3d& u)>;

struct ReferenceMoments {
  double mass = 0.0;
  Eigen::Vector3d com = Eigen::Vector3d::Zero();
  Eigen::Matrix3d inertia_com = Eigen::Matrix3d::Zero();
  // |order-20 − order-30| of mass, com and inertia (element-wise max), plus a round-off
  // floor of 1e3·ε at the quantity's scale (10³ because ~10⁴–10⁵ terms are summed).
  double mass_error = 0.0;
  double com_error = 0.0;
  double inertia_error = 0.0;
};

namespace detail {

template <int N>
void nodes_on_unit_interval(std::vector<double>& x, std::vector<double>& w) {
  using G = boost::math::quadrature::gauss<double, N>;
  const auto& a = G::abscissa();
  const auto& wt = G::weights();
  x.clear();
  w.clear();
  for (std::size_t i = 0; i < a.size(); ++i) {
    if (a[i] == 0.0) {
      x.push_back(0.5);
      w.push_back(0.5 * wt[i]);
    } else {
      x.push_back(0.5 * (1.0 + a[i]));
      w.push_back(0.5 * wt[i]);
      x.push_back(0.5 * (1.0 - a[i]));
      w.push_back(0.5 * wt[i]);
    }
  }
}

template <int N>
void integrate(const BodyMap& map, double& m, Eigen::Vector3d& F, Eigen::Matrix3d& S) {
  std::vector<double> x;
  std::vector<double> w;
  nodes_on_unit_interval<N>(x, w);
  m = 0.0;
  F.setZero();
  S.setZero();
  for (std::size_t i = 0; i < x.size(); ++i) {
    for (std::size_t j = 0; j < x.size(); ++j) {
      for (std::size_t k = 0; k < x.size(); ++k) {
        const MappedPoint p = map(Eigen::Vector3d(x[i], x[j], x[k]));
        const double wq = w[i] * w[j] * w[k] * p.weight;
        m += wq;
        F += wq * p.x;
        S += wq * p.x * p.x.transpose();
      }
    }
  }
}

inline void to_com(double m, const Eigen::Vector3d& F, const Eigen::Matrix3d& S,
                   Eigen::Vector3d& c, Eigen::Matrix3d& I) {
  c = F / m;
  const Eigen::Matrix3d S_c = S - m * c * c.transpose();
  I = S_c.trace() * Eigen::Matrix3d::Identity() - S_c;
}

}  // namespace detail

/// Reference mass properties of a body made of one or more mapped pieces (see the file
/// comment); the pieces' raw moments are summed before the COM is taken.
inline ReferenceMoments reference_moments(const std::vector<BodyMap>& pieces) {
  double m20 = 0.0;
  double m30 = 0.0;
  Eigen::Vector3d F20 = Eigen::Vector3d::Zero();
  Eigen::Vector3d F30 = Eigen::Vector3d::Zero();
  Eigen::Matrix3d S20 = Eigen::Matrix3d::Zero();
  Eigen::Matrix3d S30 = Eigen::Matrix3d::Zero();
  for (const BodyMap& map : pieces) {
    double m = 0.0;
    Eigen::Vector3d F;
    Eigen::Matrix3d S;
    detail::integrate<20>(map, m, F, S);
    m20 += m;
    F20 += F;
    S20 += S;
    detail::integrate<30>(map, m, F, S);
    m30 += m;
    F30 += F;
    S30 += S;
  }
  ReferenceMoments r;
  Eigen::Vector3d c20;
  Eigen::Matrix3d I20;
  detail::to_com(m20, F20, S20, c20, I20);
  detail::to_com(m30, F30, S30, r.com, r.inertia_com);
  r.mass = m30;
  const double eps = std::numeric_limits<double>::epsilon();
  const double length = std::sqrt(std::max(S30.trace() / m30, 0.0)) + r.com.norm();
  r.mass_error = std::abs(m30 - m20) + 1e3 * eps * m30;
  r.com_error = (r.com - c20).cwiseAbs().maxCoeff() + 1e3 * eps * length;
  r.inertia_error = (r.inertia_com - I20).cwiseAbs().maxCoeff() + 1e3 * eps * S30.trace() +
                    1e3 * eps * m30 * r.com.squaredNorm();
  return r;
}

}  // namespace rigid::test
