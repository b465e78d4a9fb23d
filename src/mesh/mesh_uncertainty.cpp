#include "rigid/mesh/mesh_uncertainty.hpp"

#include <cmath>
#include <vector>

#include <Eigen/Geometry>

#include "rigid/common/error.hpp"
#include "rigid/mass/uncertainty.hpp"

namespace rigid::mesh {
namespace {

using Vector10d = Eigen::Matrix<double, 10, 1>;

// the 10 volume moments (V, ∫r, ∫r rᵀ as xx yy zz xy xz yz) of a mesh's triangles about R
// to (m, c, I about `about`): m = ρV or the given mass, c = R + F/V,
// Σ_C = (m/V)(S − F Fᵀ/V), I_C = tr(Σ_C) 1 − Σ_C, then the parallel-axis shift
Vector10d properties_of_moments(const Vector10d& raw, const Eigen::Vector3d& R, const MassSpec& spec,
                                const std::optional<Eigen::Vector3d>& about) {
  const double V = raw(0);
  const Eigen::Vector3d F = raw.segment<3>(1);
  Eigen::Matrix3d S;
  S << raw(4), raw(7), raw(8), raw(7), raw(5), raw(9), raw(8), raw(9), raw(6);
  const double m = spec.mass ? *spec.mass : *spec.density * V;
  const Eigen::Vector3d c = R + F / V;
  const Eigen::Matrix3d Sigma_C = (m / V) * (S - F * F.transpose() / V);
  Eigen::Matrix3d I = Sigma_C.trace() * Eigen::Matrix3d::Identity() - Sigma_C;
  if (about) {
    const Eigen::Vector3d d = c - *about;
    I += m * (d.squaredNorm() * Eigen::Matrix3d::Identity() - d * d.transpose());
  }
  Vector10d y;
  y << m, c, I(0, 0), I(1, 1), I(2, 2), I(0, 1), I(0, 2), I(1, 2);
  return y;
}

// the 6 stored elements (xx yy zz xy xz yz) of a symmetric matrix
Eigen::Matrix<double, 6, 1> upper(const Eigen::Matrix3d& M) {
  Eigen::Matrix<double, 6, 1> u;
  u << M(0, 0), M(1, 1), M(2, 2), M(0, 1), M(0, 2), M(1, 2);
  return u;
}

}  // namespace

MeshUncertainty vertex_noise_uncertainty(const TriangleMesh& mesh, const MassSpec& spec, double sigma,
                                         const std::optional<Eigen::Vector3d>& about) {
  RIGID_REQUIRE(!spec.shell, "vertex noise is propagated for solid meshes only, not shells");
  RIGID_REQUIRE(std::isfinite(sigma) && sigma >= 0.0,
                "the vertex standard deviation must be finite and non-negative, got {} m", sigma);
  MeshMassResult nominal = mesh_mass_properties(mesh, spec);  // checks closedness and the spec
  const MeshMoments mom = volume_moments(mesh);
  const Eigen::Vector3d& R = mom.p_OR_M;
  Vector10d raw;
  raw << mom.measure, mom.first, upper(mom.second);

  // ∂raw/∂x for every vertex coordinate, triangle by triangle, about R: with det = a·(b×c)
  // (six times the signed volume of the tetrahedron R a b c) and s = a + b + c,
  //   V = det/6, F = det s/24, S = det Q/120, Q = a aᵀ + b bᵀ + c cᵀ + s sᵀ [Tonon2005],
  // ∂det/∂a = b×c (cyclic), ∂s/∂a_d = e_d, ∂Q/∂a_d = e_d aᵀ + a e_dᵀ + e_d sᵀ + s e_dᵀ
  std::vector<Vector10d> grad(3 * mesh.vertices.size(), Vector10d::Zero());
  for (const auto& t : mesh.triangles) {
    const Eigen::Vector3d p[3] = {mesh.vertices[t[0]] - R, mesh.vertices[t[1]] - R, mesh.vertices[t[2]] - R};
    const double det = p[0].dot(p[1].cross(p[2]));
    const Eigen::Vector3d s = p[0] + p[1] + p[2];
    const Eigen::Matrix3d Q = p[0] * p[0].transpose() + p[1] * p[1].transpose() + p[2] * p[2].transpose() +
                              s * s.transpose();
    for (int k = 0; k < 3; ++k) {
      const Eigen::Vector3d& a = p[k];
      const Eigen::Vector3d ddet = p[(k + 1) % 3].cross(p[(k + 2) % 3]);
      for (int d = 0; d < 3; ++d) {
        const Eigen::Vector3d e = Eigen::Vector3d::Unit(d);
        const Eigen::Matrix3d dQ = e * a.transpose() + a * e.transpose() + e * s.transpose() + s * e.transpose();
        Vector10d g;
        g << ddet(d) / 6.0, (ddet(d) * s + det * e) / 24.0, upper((ddet(d) * Q + det * dQ) / 120.0);
        grad[3 * t[k] + static_cast<std::size_t>(d)] += g;
      }
    }
  }
  // the Jacobian of (m, c, I) in the moments, by central differences at steps scaled by each
  // moment's natural size (V, V·L, V·L²; L the bounding-box diagonal), since a moment may be 0
  const auto box = mesh.bounding_box();
  const double L = (box[1] - box[0]).norm();
  const double V = mom.measure;
  Vector10d scale;
  scale << V, V * L, V * L, V * L, V * L * L, V * L * L, V * L * L, V * L * L, V * L * L, V * L * L;
  const mass::Propagated jac = mass::propagate(
      [&](const Eigen::VectorXd& x) -> Eigen::VectorXd { return properties_of_moments(x, R, spec, about); }, raw,
      scale);
  Vector10d var = Vector10d::Zero();
  for (const Vector10d& g : grad) var += (jac.jacobian * g).cwiseAbs2();
  return MeshUncertainty{std::move(nominal), properties_of_moments(raw, R, spec, about), sigma * var.cwiseSqrt()};
}

}  // namespace rigid::mesh
