// Memory linear in the state's size for every method but the implicit midpoint, whose dense
// Jacobian is refused beyond its bound before the run.
#include <cmath>

#include <gtest/gtest.h>

#include "rigid/integrate/integrator.hpp"
#include "support/expect_error.hpp"

namespace rigid::integrate {
namespace {

// y' = −y for 200,000 components: an n × n matrix would be 320 GB, beyond any allocation here.
Problem large_decay() {
  Problem p;
  p.rhs = [](double, const Eigen::VectorXd& y, Eigen::VectorXd& dydt) { dydt = -y; };
  p.y0 = Eigen::VectorXd::Ones(200'000);
  p.t_end = 0.02;
  return p;
}

TEST(SolveMemory, ExplicitAndSymplecticMethodsRunALargeState) {
  for (const Method m : {Method::kRk4, Method::kStormerVerlet}) {
    Options o;
    o.method = m;
    o.dt = 0.01;
    const Solution s = integrate(large_decay(), o);
    ASSERT_EQ(s.t.size(), 3u);
    // rk4: e^{−0.02} to O(h⁵) = 1e-10 per step; Störmer–Verlet here is (q, v) = two halves of
    // the decay, so only its finiteness and size are checked
    EXPECT_EQ(s.y.back().size(), 200'000);
    EXPECT_TRUE(s.y.back().allFinite());
    if (m == Method::kRk4) {
      EXPECT_NEAR(s.y.back()[12345], std::exp(-0.02), 1e-10);
    }
  }
}

TEST(SolveMemory, TheImplicitMidpointRefusesAJacobianBeyondItsBound) {
  Options o;
  o.method = Method::kImplicitMidpoint;
  o.dt = 0.01;
  EXPECT_RIGID_ERROR((void)integrate(large_decay(), o),
                     "implicit midpoint keeps a dense n × n Jacobian and its LU: a state of size "
                     "200000 needs 640 GB");
}

}  // namespace
}  // namespace rigid::integrate
