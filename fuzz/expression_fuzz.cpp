// Fuzz target: the expression parser of rigid::lagrange and what follows it. The first byte
// picks the use (its value mod 3; seeds use '0', '1', '2'), the rest is the expression:
//   0: a constant of the parameters a and b (evaluate_constant);
//   1: a potential V(q, t) of one coordinate q with L = ½ q̇²: derived, compiled, evaluated;
//   2: the Lagrangian itself, L(q, q̇, t): derived, compiled, evaluated.
#include <string>
#include <vector>

#include <Eigen/Core>

#include "fuzz_support.hpp"
#include "rigid/lagrange.hpp"

namespace {

namespace lg = rigid::lagrange;

const std::vector<lg::Parameter> kParameters{{"a", 1.5}, {"b", -0.25}};

void derive_and_evaluate(const lg::SystemSpec& spec) {
  const lg::System system(spec);
  (void)system.equations();
  const Eigen::VectorXd q = system.initial_q(), q_dot = system.initial_q_dot();
  Eigen::VectorXd q_ddot, lambda;
  system.accelerations(0.5, q, q_dot, q_ddot, lambda);
  (void)system.energy(0.5, q, q_dot);
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  if (size == 0) return 0;
  const int use = data[0] % 3;
  const std::string_view input = rigid::fuzz::as_text(data, size);
  const std::string text(input.substr(1));
  rigid::fuzz::refuse_or_return(input, [&] {
    if (use == 0) {
      (void)lg::evaluate_constant(lg::Expression(text), kParameters, "fuzz");
      return;
    }
    lg::SystemSpec spec;
    spec.parameters = kParameters;
    spec.coordinates = {{"q", 0.3, 0.2}};
    if (use == 1) {
      spec.lagrangian = "q_dot^2/2";
      spec.potentials = {{"V", lg::Expression(text)}};
    } else {
      spec.lagrangian = lg::Expression(text);
    }
    derive_and_evaluate(spec);
  });
  return 0;
}
