// The N-link planar pendulum (point masses m_k = 1 kg on massless rods l_k = 1 m, g = 9.81):
// (a) deriving the equations (rigid::lagrange::System: parse, assemble T and V from bodies,
//     Euler–Lagrange derivatives, compile the tape),
// (b) one right-hand-side evaluation q̈(q, q̇) with the mass-matrix solve, and
// (c) the same right-hand side written by hand in C++ (closed-form M and f, Eigen LLT).
// SymPy's side of the comparison is bench/lagrange_sympy.py.
#include <cmath>
#include <cstdio>
#include <cstdlib>

#include <Eigen/Cholesky>
#include <benchmark/benchmark.h>
#include <fmt/format.h>

#include "rigid/lagrange/system.hpp"

namespace {

constexpr double kG = 9.81;

rigid::lagrange::SystemSpec chain_spec(int n) {
  rigid::lagrange::SystemSpec spec;
  std::string x = "0", y = "0";
  for (int i = 1; i <= n; ++i) {
    spec.parameters.push_back({fmt::format("l{}", i), 1.0});
    spec.coordinates.push_back({fmt::format("q{}", i), 0.1 * i, 0.0});
    x = fmt::format("{} + l{}*sin(q{})", x, i, i);
    y = fmt::format("{} - l{}*cos(q{})", y, i, i);
    spec.bodies.push_back(rigid::lagrange::Body{
        fmt::format("bob{}", i),
        rigid::MassProperties(1.0, Eigen::Vector3d::Zero(), Eigen::Matrix3d::Zero()),
        {x, y, "0"}, {}});
  }
  spec.gravity_W = Eigen::Vector3d(0, -kG, 0);
  return spec;
}

// hand-written: with μ_k = Σ_{j ≥ k} m_j,
//   M_ij = μ_max(i,j) l_i l_j cos(q_i − q_j),
//   f_i  = −Σ_j μ_max(i,j) l_i l_j sin(q_i − q_j) q̇_j² − g μ_i l_i sin q_i
struct HandChain {
  int n;
  Eigen::VectorXd m, l, mu;
  Eigen::MatrixXd M;
  Eigen::VectorXd f;
  Eigen::LLT<Eigen::MatrixXd> llt;
  explicit HandChain(int n_) : n(n_), m(Eigen::VectorXd::Ones(n_)), l(Eigen::VectorXd::Ones(n_)),
                               mu(n_), M(n_, n_), f(n_), llt(n_) {
    double s = 0;
    for (int k = n - 1; k >= 0; --k) mu[k] = (s += m[k]);
  }
  void accelerations(const Eigen::VectorXd& q, const Eigen::VectorXd& qd, Eigen::VectorXd& qdd) {
    for (int i = 0; i < n; ++i) {
      f[i] = -kG * mu[i] * l[i] * std::sin(q[i]);
      M(i, i) = mu[i] * l[i] * l[i];
      for (int j = 0; j < n; ++j) {
        if (j == i) continue;
        const double d = q[i] - q[j];
        const double c = mu[std::max(i, j)] * l[i] * l[j];
        if (j > i) M(i, j) = M(j, i) = c * std::cos(d);
        f[i] -= c * std::sin(d) * qd[j] * qd[j];
      }
    }
    llt.compute(M);
    qdd = llt.solve(f);
  }
};

void sample_state(int n, Eigen::VectorXd& q, Eigen::VectorXd& qd) {
  q.resize(n);
  qd.resize(n);
  for (int i = 0; i < n; ++i) {
    q[i] = 0.3 * std::sin(1.7 * i + 0.4);
    qd[i] = 0.5 * std::cos(2.3 * i);
  }
}

void BM_Lagrange_derive(benchmark::State& state) {
  const int n = static_cast<int>(state.range(0));
  const auto spec = chain_spec(n);
  std::size_t tape = 0;
  for (auto _ : state) {
    rigid::lagrange::System sys(spec);
    tape = sys.tape_size();
    benchmark::DoNotOptimize(tape);
  }
  state.counters["tape_instructions"] = static_cast<double>(tape);
}

// derivation with the printing a reader sees: System + equations() (canonical order, the
// textbook simplification of every printed quantity)
void BM_Lagrange_derive_and_print(benchmark::State& state) {
  const int n = static_cast<int>(state.range(0));
  const auto spec = chain_spec(n);
  for (auto _ : state) {
    const rigid::lagrange::Equations eq = rigid::lagrange::System(spec).equations();
    benchmark::DoNotOptimize(eq.text.data());
  }
}

void BM_Lagrange_rhs(benchmark::State& state) {
  const int n = static_cast<int>(state.range(0));
  const rigid::lagrange::System sys(chain_spec(n));
  Eigen::VectorXd q, qd, qdd(n), lambda;
  sample_state(n, q, qd);
  // agreement with the hand-written form before timing
  HandChain hand(n);
  Eigen::VectorXd ref(n);
  hand.accelerations(q, qd, ref);
  // one workspace for the loop, as a simulation's right-hand side uses it
  rigid::lagrange::Workspace w = sys.make_workspace();
  sys.accelerations(w, 0.0, q, qd, qdd, lambda);
  if ((qdd - ref).norm() > 1e-10 * (1 + ref.norm())) {
    std::fprintf(stderr, "lagrange_bench: compiled and hand-written accelerations disagree\n");
    std::exit(1);
  }
  for (auto _ : state) {
    sys.accelerations(w, 0.0, q, qd, qdd, lambda);
    benchmark::DoNotOptimize(qdd.data());
  }
}

void BM_Handwritten_rhs(benchmark::State& state) {
  const int n = static_cast<int>(state.range(0));
  HandChain hand(n);
  Eigen::VectorXd q, qd, qdd(n);
  sample_state(n, q, qd);
  for (auto _ : state) {
    hand.accelerations(q, qd, qdd);
    benchmark::DoNotOptimize(qdd.data());
  }
}

BENCHMARK(BM_Lagrange_derive)->Arg(2)->Arg(4)->Arg(8)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_Lagrange_derive_and_print)->Arg(2)->Arg(4)->Arg(8)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_Lagrange_rhs)->Arg(2)->Arg(4)->Arg(8)->Unit(benchmark::kMicrosecond);
BENCHMARK(BM_Handwritten_rhs)->Arg(2)->Arg(4)->Arg(8)->Unit(benchmark::kMicrosecond);

}  // namespace
