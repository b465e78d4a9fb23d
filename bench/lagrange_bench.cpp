// The N-link planar pendulum (point masses m_k = 1 kg on massless rods l_k = 1 m, g = 9.81):
// (a) deriving the equations (rigid::lagrange::System: parse, assemble T and V from bodies,
//     Euler–Lagrange derivatives, compile the tape),
// (b) one right-hand-side evaluation q̈(q, q̇) with the mass-matrix solve,
// (c) the same right-hand side written by hand in C++ (closed-form M and f, Eigen LLT),
// (d) the same with M and f from the exported C++ (rigid::lagrange::emit_cpp, generated at
//     build time into generated/chainN.hpp, compiled with the project's flags), Eigen LLT, and
// (e) (b), (c) and (d) timed alternately in one benchmark, whose counters are the ratios to
//     the hand-written code: a slowdown of the tape alone shows there even on a busy machine.
// SymPy's side of the comparison is bench/lagrange_sympy.py.
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>

#include <Eigen/Cholesky>
#include <benchmark/benchmark.h>
#include <fmt/format.h>

#include "chain2.hpp"
#include "chain4.hpp"
#include "chain8.hpp"
#include "lagrange_chain.hpp"
#include "rigid/lagrange/system.hpp"

namespace {

constexpr double kG = rigid::bench::kChainGravity;
using rigid::bench::chain_spec;

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

// M and f from the exported code (rigid::lagrange::emit_cpp), then the same LLT
struct ExportedChain {
  using Function = void (*)(const double* q, const double* q_dot, double* M, double* f);
  int n;
  Function mass_matrix_and_forces;
  Eigen::MatrixXd M;  // the exported M is row-major and symmetric: either storage order holds it
  Eigen::VectorXd f;
  Eigen::LLT<Eigen::MatrixXd> llt;
  explicit ExportedChain(int n_) : n(n_), mass_matrix_and_forces(pick(n_)), M(n_, n_), f(n_), llt(n_) {}
  static Function pick(int n) {
    switch (n) {
      case 2: return [](const double* q, const double* qd, double* M, double* f) {
        chain2::mass_matrix_and_forces(q, qd, 0.0, M, f);
      };
      case 4: return [](const double* q, const double* qd, double* M, double* f) {
        chain4::mass_matrix_and_forces(q, qd, 0.0, M, f);
      };
      case 8: return [](const double* q, const double* qd, double* M, double* f) {
        chain8::mass_matrix_and_forces(q, qd, 0.0, M, f);
      };
      default:
        std::fprintf(stderr, "lagrange_bench: no exported chain with %d links\n", n);
        std::exit(1);
    }
  }
  void accelerations(const Eigen::VectorXd& q, const Eigen::VectorXd& qd, Eigen::VectorXd& qdd) {
    mass_matrix_and_forces(q.data(), qd.data(), M.data(), f.data());
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

void BM_Exported_rhs(benchmark::State& state) {
  const int n = static_cast<int>(state.range(0));
  ExportedChain exported(n);
  Eigen::VectorXd q, qd, qdd(n);
  sample_state(n, q, qd);
  HandChain hand(n);
  Eigen::VectorXd ref(n);
  hand.accelerations(q, qd, ref);
  exported.accelerations(q, qd, qdd);
  if ((qdd - ref).norm() > 1e-10 * (1 + ref.norm())) {
    std::fprintf(stderr, "lagrange_bench: exported and hand-written accelerations disagree\n");
    std::exit(1);
  }
  for (auto _ : state) {
    exported.accelerations(q, qd, qdd);
    benchmark::DoNotOptimize(qdd.data());
  }
}

// The tape, the hand-written and the exported right-hand sides in alternating blocks of calls;
// the counters are the time per call of each (ns) and the ratios to the hand-written one.
void BM_Lagrange_rhs_ratio(benchmark::State& state) {
  using Clock = std::chrono::steady_clock;
  const int n = static_cast<int>(state.range(0));
  const rigid::lagrange::System sys(chain_spec(n));
  rigid::lagrange::Workspace w = sys.make_workspace();
  HandChain hand(n);
  ExportedChain exported(n);
  Eigen::VectorXd q, qd, qdd(n), lambda;
  sample_state(n, q, qd);
  constexpr int kBlock = 64;
  double tape_s = 0, hand_s = 0, exported_s = 0;
  for (auto _ : state) {
    const auto t0 = Clock::now();
    for (int k = 0; k < kBlock; ++k) {
      sys.accelerations(w, 0.0, q, qd, qdd, lambda);
      benchmark::DoNotOptimize(qdd.data());
    }
    const auto t1 = Clock::now();
    for (int k = 0; k < kBlock; ++k) {
      hand.accelerations(q, qd, qdd);
      benchmark::DoNotOptimize(qdd.data());
    }
    const auto t2 = Clock::now();
    for (int k = 0; k < kBlock; ++k) {
      exported.accelerations(q, qd, qdd);
      benchmark::DoNotOptimize(qdd.data());
    }
    const auto t3 = Clock::now();
    tape_s += std::chrono::duration<double>(t1 - t0).count();
    hand_s += std::chrono::duration<double>(t2 - t1).count();
    exported_s += std::chrono::duration<double>(t3 - t2).count();
  }
  const double calls = static_cast<double>(state.iterations()) * kBlock;
  state.counters["tape_ns"] = 1e9 * tape_s / calls;
  state.counters["hand_ns"] = 1e9 * hand_s / calls;
  state.counters["exported_ns"] = 1e9 * exported_s / calls;
  state.counters["tape/hand"] = tape_s / hand_s;
  state.counters["exported/hand"] = exported_s / hand_s;
}

BENCHMARK(BM_Lagrange_derive)->Arg(2)->Arg(4)->Arg(8)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_Lagrange_derive_and_print)->Arg(2)->Arg(4)->Arg(8)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_Lagrange_rhs)->Arg(2)->Arg(4)->Arg(8)->Unit(benchmark::kMicrosecond);
BENCHMARK(BM_Handwritten_rhs)->Arg(2)->Arg(4)->Arg(8)->Unit(benchmark::kMicrosecond);
BENCHMARK(BM_Exported_rhs)->Arg(2)->Arg(4)->Arg(8)->Unit(benchmark::kMicrosecond);
BENCHMARK(BM_Lagrange_rhs_ratio)->Arg(2)->Arg(4)->Arg(8)->Unit(benchmark::kMicrosecond);

}  // namespace
