// SO3 compose, act, exp and log: rigid::SO3d next to Eigen's Quaternion / AngleAxis, on the
// same pre-generated random inputs (1024 of each, cycled so that nothing is constant-folded).
// Then the dynamic-size SOn exp and log at n = 3 and n = 8 (Gaussian ω, σ = 0.5 per component;
// Haar rotations), to show the cost of the general matrix route.
#include <random>
#include <vector>

#include <Eigen/Geometry>
#include <benchmark/benchmark.h>

#include "rigid/lie.hpp"

namespace {

constexpr std::size_t kN = 1024;

struct Inputs {
  std::vector<rigid::SO3d> r;
  std::vector<Eigen::Quaterniond> q;
  std::vector<Eigen::Vector3d> v, w;
  Inputs() {
    std::mt19937_64 rng(1);
    std::uniform_real_distribution<double> u(-1.0, 1.0);
    for (std::size_t i = 0; i < kN; ++i) {
      const rigid::SO3d R = rigid::SO3d::sample(rng);
      r.push_back(R);
      q.emplace_back(R.w(), R.x(), R.y(), R.z());
      v.emplace_back(u(rng), u(rng), u(rng));
      w.emplace_back(Eigen::Vector3d(u(rng), u(rng), u(rng)) * 1.5);
    }
  }
};
const Inputs& inputs() {
  static const Inputs in;
  return in;
}

void BM_rigid_compose(benchmark::State& s) {
  const auto& in = inputs();
  std::size_t i = 0;
  for (auto _ : s) {
    benchmark::DoNotOptimize(in.r[i] * in.r[(i + 1) % kN]);
    i = (i + 1) % kN;
  }
}
void BM_eigen_compose(benchmark::State& s) {
  const auto& in = inputs();
  std::size_t i = 0;
  for (auto _ : s) {
    benchmark::DoNotOptimize(Eigen::Quaterniond(in.q[i] * in.q[(i + 1) % kN]));
    i = (i + 1) % kN;
  }
}
void BM_rigid_act(benchmark::State& s) {
  const auto& in = inputs();
  std::size_t i = 0;
  for (auto _ : s) {
    benchmark::DoNotOptimize(Eigen::Vector3d(in.r[i] * in.v[i]));
    i = (i + 1) % kN;
  }
}
void BM_eigen_act(benchmark::State& s) {
  const auto& in = inputs();
  std::size_t i = 0;
  for (auto _ : s) {
    benchmark::DoNotOptimize(Eigen::Vector3d(in.q[i] * in.v[i]));
    i = (i + 1) % kN;
  }
}
void BM_rigid_exp(benchmark::State& s) {
  const auto& in = inputs();
  std::size_t i = 0;
  for (auto _ : s) {
    benchmark::DoNotOptimize(rigid::SO3d::exp(in.w[i]));
    i = (i + 1) % kN;
  }
}
void BM_eigen_exp(benchmark::State& s) {
  // Rotation vector → quaternion through AngleAxis (needs the norm and the unit axis).
  const auto& in = inputs();
  std::size_t i = 0;
  for (auto _ : s) {
    const double a = in.w[i].norm();
    benchmark::DoNotOptimize(Eigen::Quaterniond(Eigen::AngleAxisd(a, in.w[i] / a)));
    i = (i + 1) % kN;
  }
}
void BM_rigid_log(benchmark::State& s) {
  const auto& in = inputs();
  std::size_t i = 0;
  for (auto _ : s) {
    benchmark::DoNotOptimize(in.r[i].log());
    i = (i + 1) % kN;
  }
}
void BM_eigen_log(benchmark::State& s) {
  const auto& in = inputs();
  std::size_t i = 0;
  for (auto _ : s) {
    const Eigen::AngleAxisd aa(in.q[i]);
    benchmark::DoNotOptimize(Eigen::Vector3d(aa.angle() * aa.axis()));
    i = (i + 1) % kN;
  }
}

struct DynamicInputs {
  std::vector<rigid::SOn> r;
  std::vector<Eigen::VectorXd> w;
  explicit DynamicInputs(int n) {
    std::mt19937_64 rng(2);
    std::normal_distribution<double> g(0.0, 0.5);
    for (std::size_t i = 0; i < kN; ++i) {
      r.push_back(rigid::SOn::sample(n, rng));
      Eigen::VectorXd v(rigid::SOn::dimension_of(n));
      for (Eigen::Index k = 0; k < v.size(); ++k) v(k) = g(rng);
      w.push_back(v);
    }
  }
};
const DynamicInputs& dynamic_inputs(int n) {
  static const DynamicInputs in3(3), in8(8);
  return n == 3 ? in3 : in8;
}
void BM_rigid_SOn_exp(benchmark::State& s) {
  const auto& in = dynamic_inputs(static_cast<int>(s.range(0)));
  std::size_t i = 0;
  for (auto _ : s) {
    benchmark::DoNotOptimize(rigid::SOn::exp(in.w[i]));
    i = (i + 1) % kN;
  }
}
void BM_rigid_SOn_log(benchmark::State& s) {
  const auto& in = dynamic_inputs(static_cast<int>(s.range(0)));
  std::size_t i = 0;
  for (auto _ : s) {
    benchmark::DoNotOptimize(in.r[i].log());
    i = (i + 1) % kN;
  }
}

BENCHMARK(BM_rigid_compose);
BENCHMARK(BM_eigen_compose);
BENCHMARK(BM_rigid_act);
BENCHMARK(BM_eigen_act);
BENCHMARK(BM_rigid_exp);
BENCHMARK(BM_eigen_exp);
BENCHMARK(BM_rigid_log);
BENCHMARK(BM_eigen_log);
BENCHMARK(BM_rigid_SOn_exp)->Arg(3)->Arg(8);
BENCHMARK(BM_rigid_SOn_log)->Arg(3)->Arg(8);

}  // namespace
