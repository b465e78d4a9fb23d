// Mass-property kernels of rigid next to the same operations in ODE and Bullet (double
// precision builds), in one binary so that the machine and compiler flags are shared.
#include <benchmark/benchmark.h>

#include <BulletCollision/CollisionShapes/btCylinderShape.h>
#include <LinearMath/btMatrix3x3.h>
#include <ode/mass.h>

#include <Eigen/Geometry>

#include "rigid/mass/density.hpp"
#include "rigid/mass/mass_properties.hpp"
#include "rigid/mass/primitives.hpp"

namespace {

const Eigen::Matrix3d kR =
    Eigen::AngleAxisd(0.7, Eigen::Vector3d(1, 2, 3).normalized()).toRotationMatrix();

// --- primitive: solid cylinder of given mass -------------------------------------------
void BM_Rigid_SolidCylinderWithMass(benchmark::State& state) {
  double m = 2.0;
  double r = 0.1;
  double h = 0.5;
  for (auto _ : state) {
    benchmark::DoNotOptimize(m);
    benchmark::DoNotOptimize(r);
    benchmark::DoNotOptimize(h);
    auto mp = rigid::mass::solid_cylinder_with_mass(m, r, h);
    benchmark::DoNotOptimize(mp);
  }
}
BENCHMARK(BM_Rigid_SolidCylinderWithMass);

void BM_ODE_dMassSetCylinderTotal(benchmark::State& state) {
  double m = 2.0;
  double r = 0.1;
  double h = 0.5;
  dMass mass;
  for (auto _ : state) {
    benchmark::DoNotOptimize(m);
    benchmark::DoNotOptimize(r);
    benchmark::DoNotOptimize(h);
    dMassSetCylinderTotal(&mass, m, 3, r, h);
    benchmark::DoNotOptimize(mass);
  }
}
BENCHMARK(BM_ODE_dMassSetCylinderTotal);

void BM_Bullet_CylinderZ_calculateLocalInertia(benchmark::State& state) {
  double m = 2.0;
  const btCylinderShapeZ shape(btVector3(0.1, 0.1, 0.25));
  btVector3 inertia;
  for (auto _ : state) {
    benchmark::DoNotOptimize(m);
    shape.calculateLocalInertia(m, inertia);
    benchmark::DoNotOptimize(inertia);
  }
}
BENCHMARK(BM_Bullet_CylinderZ_calculateLocalInertia);

// --- rotate + translate one body and add it to another ---------------------------------
void BM_Rigid_TransformAndCombine(benchmark::State& state) {
  const auto a = rigid::mass::solid_box_with_mass(1.0, 0.3, 0.5, 0.7);
  const auto b = rigid::mass::solid_cylinder_with_mass(2.0, 0.1, 0.5);
  Eigen::Vector3d p(0.1, 0.2, 0.3);
  for (auto _ : state) {
    benchmark::DoNotOptimize(p);
    auto c = rigid::combine(a, b.transformed(kR, p));
    benchmark::DoNotOptimize(c);
  }
}
BENCHMARK(BM_Rigid_TransformAndCombine);

void BM_ODE_RotateTranslateAdd(benchmark::State& state) {
  dMass a;
  dMass b;
  dMassSetBoxTotal(&a, 1.0, 0.3, 0.5, 0.7);
  dMatrix3 R;
  for (int i = 0; i < 3; ++i) {
    for (int j = 0; j < 3; ++j) R[4 * i + j] = kR(i, j);
    R[4 * i + 3] = 0.0;
  }
  double x = 0.1;
  for (auto _ : state) {
    benchmark::DoNotOptimize(x);
    dMass sum = a;
    dMassSetCylinderTotal(&b, 2.0, 3, 0.1, 0.5);
    dMassRotate(&b, R);
    dMassTranslate(&b, x, 0.2, 0.3);
    dMassAdd(&sum, &b);
    benchmark::DoNotOptimize(sum);
  }
}
BENCHMARK(BM_ODE_RotateTranslateAdd);

// --- principal axes of a general tensor ------------------------------------------------
void BM_Rigid_PrincipalAxes(benchmark::State& state) {
  const auto mp = rigid::mass::solid_box_with_mass(1.0, 0.3, 0.5, 0.7).rotated(kR);
  for (auto _ : state) {
    auto pa = mp.principal_axes();
    benchmark::DoNotOptimize(pa);
  }
}
BENCHMARK(BM_Rigid_PrincipalAxes);

void BM_Bullet_Matrix3x3_diagonalize(benchmark::State& state) {
  const auto mp = rigid::mass::solid_box_with_mass(1.0, 0.3, 0.5, 0.7).rotated(kR);
  const Eigen::Matrix3d& I = mp.inertia_com();
  const btMatrix3x3 tensor(I(0, 0), I(0, 1), I(0, 2), I(1, 0), I(1, 1), I(1, 2), I(2, 0), I(2, 1),
                           I(2, 2));
  for (auto _ : state) {
    btMatrix3x3 d = tensor;
    btMatrix3x3 rot;
    rot.setIdentity();
    d.diagonalize(rot, 1e-12, 20);
    benchmark::DoNotOptimize(d);
    benchmark::DoNotOptimize(rot);
  }
}
BENCHMARK(BM_Bullet_Matrix3x3_diagonalize);

// --- physical validity check -----------------------------------------------------------
void BM_Rigid_Check(benchmark::State& state) {
  const auto mp = rigid::mass::solid_box_with_mass(1.0, 0.3, 0.5, 0.7).rotated(kR);
  for (auto _ : state) {
    auto report = rigid::MassProperties::check(mp.mass(), mp.com(), mp.inertia_com());
    benchmark::DoNotOptimize(report);
  }
}
BENCHMARK(BM_Rigid_Check);

void BM_ODE_dMassCheck(benchmark::State& state) {
  dMass m;
  dMassSetBoxTotal(&m, 1.0, 0.3, 0.5, 0.7);
  for (auto _ : state) {
    benchmark::DoNotOptimize(m);
    int ok = dMassCheck(&m);
    benchmark::DoNotOptimize(ok);
  }
}
BENCHMARK(BM_ODE_dMassCheck);

// --- non-uniform density (no peer has one) ---------------------------------------------
void BM_Rigid_DensityCubatureSphere(benchmark::State& state) {
  for (auto _ : state) {
    auto res = rigid::mass::integrate_density_over_sphere(
        [](const Eigen::Vector3d& p) { return 1.0 + 0.5 * p.z(); }, 0.5);
    benchmark::DoNotOptimize(res);
  }
}
BENCHMARK(BM_Rigid_DensityCubatureSphere)->Unit(benchmark::kMicrosecond);

}  // namespace
