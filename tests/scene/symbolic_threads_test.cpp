// Every front-end path that reaches the symbolic core (deriving a model, printing its equations
// in every format, normal modes, code export in both layouts, a run and its report's data) called from eight
// threads at once, on several scenes, gives what one thread alone gives. Run under
// ThreadSanitizer by `make test` (test-tsan), where a race on GiNaC's shared expression nodes
// is reported even when it does not crash.

#include <filesystem>
#include <optional>
#include <string>
#include <thread>
#include <vector>

#include <gtest/gtest.h>

#include "rigid/common/error.hpp"
#include "rigid/lagrange/linearize.hpp"
#include "rigid/report/report.hpp"
#include "rigid/scene/export.hpp"
#include "rigid/scene/model.hpp"
#include "rigid/scene/modes.hpp"

namespace rigid::scene {
namespace {

const std::filesystem::path kExamples = RIGID_EXAMPLES_DIR;

// A scene of the examples, with its run shortened (what is tested is the symbolic side and
// the sharing, not the length of the run).
struct Case {
  const char* file;
  std::vector<std::string> overrides;
};

const std::vector<Case>& cases() {
  static const std::vector<Case> kCases = {
      {"double_pendulum.toml", {"simulation.t_end=0.05", "simulation.output_dt=0.01"}},
      {"atwood.toml", {"simulation.t_end=0.05"}},
      {"rolling_disk.toml", {"simulation.t_end=0.05"}},
      {"tennis_racket.toml", {"simulation.t_end=0.5"}},
      {"heavy_top.toml", {"simulation.t_end=0.05"}},
      // a tree read from a URDF: the flat export's closed-form derivatives of its recursion
      {"cart_arm.urdf", {"simulation.t_end=0.05"}},
  };
  return kCases;
}

// What one pass over a scene produces; a refusal is kept as its message (the same refusal
// from every thread is part of the contract).
struct Outputs {
  std::vector<std::string> text;
  std::vector<std::vector<double>> numbers;
  bool operator==(const Outputs&) const = default;
};

template <typename F>
std::string or_refusal(F&& f) {
  try {
    return f();
  } catch (const Error& e) {
    return std::string("refused: ") + e.what();
  }
}

Outputs pass(const Case& c) {
  Outputs out;
  const Model model = load_model(kExamples / c.file, c.overrides);  // derives the equations
  for (auto format : {lagrange::EquationFormat::kText, lagrange::EquationFormat::kLatex,
                      lagrange::EquationFormat::kJson}) {
    out.text.push_back(model.equations(format));
  }
  out.text.push_back(or_refusal([&] { return lagrange::to_text(normal_modes(model)); }));
  out.text.push_back(or_refusal([&] { return emit_code(model, "c++"); }));
  out.text.push_back(or_refusal([&] { return emit_code(model, "python"); }));
  // the flat layout: M, forward dynamics and both derivative functions
  out.text.push_back(or_refusal([&] { return emit_code(model, "c++", "flat", true); }));
  RunResult result = model.run();
  result.summary.wall_seconds = 0.0;  // the one entry that differs from run to run
  out.numbers.push_back(result.trajectory.data());
  out.text.push_back(report::report_json(model, result));
  return out;
}

TEST(SymbolicThreads, EveryPathFromEightThreadsGivesTheSerialOutputs) {
  std::vector<Outputs> serial;
  for (const Case& c : cases()) serial.push_back(pass(c));
  // every scene refused something that the others do: the passes cover modes, export and a
  // refusal of each (rolling_disk has velocity constraints; the free bodies no coordinates)
  for (const Outputs& o : serial) ASSERT_EQ(o.text.size(), 8U);
  // the tree's flat export holds the derivative functions (not a refusal)
  EXPECT_NE(serial.back().text[6].find("void forward_dynamics_derivatives("), std::string::npos);

  constexpr int kThreads = 8;
  std::vector<std::vector<Outputs>> together(kThreads);
  std::vector<std::string> failures(kThreads);
  std::vector<std::thread> threads;
  for (int k = 0; k < kThreads; ++k) {
    threads.emplace_back([&, k] {
      try {
        // each thread starts at another scene, so that different derivations overlap
        for (std::size_t i = 0; i < cases().size(); ++i) {
          together[static_cast<std::size_t>(k)].push_back(
              pass(cases()[(i + static_cast<std::size_t>(k)) % cases().size()]));
        }
      } catch (const std::exception& e) {
        failures[static_cast<std::size_t>(k)] = e.what();
      }
    });
  }
  for (auto& t : threads) t.join();
  for (int k = 0; k < kThreads; ++k) {
    const auto ku = static_cast<std::size_t>(k);
    ASSERT_EQ(failures[ku], "") << "thread " << k;
    for (std::size_t i = 0; i < cases().size(); ++i) {
      const std::size_t scene = (i + ku) % cases().size();
      EXPECT_EQ(together[ku][i], serial[scene]) << "thread " << k << ", " << cases()[scene].file;
    }
  }
}

// Models built on some threads and destroyed on others while yet others derive and print: the
// destruction of a System's expressions is one more entry into the symbolic core.
TEST(SymbolicThreads, ModelsDestroyedWhileOthersDerive) {
  const std::filesystem::path file = kExamples / "double_pendulum.toml";
  const std::string expected = load_model(file).equations(false);
  std::vector<std::optional<Model>> models(8);
  std::vector<std::thread> threads;
  for (std::size_t k = 0; k < models.size(); k += 2) {
    threads.emplace_back([&, k] { models[k].emplace(load_model(file)); });
  }
  for (auto& t : threads) t.join();
  threads.clear();
  // even slots: print, then destroy; odd slots: derive a new model, then print
  std::vector<std::string> printed(models.size());
  for (std::size_t k = 0; k < models.size(); ++k) {
    threads.emplace_back([&, k] {
      if (k % 2 == 1) models[k].emplace(load_model(file));
      printed[k] = models[k]->equations(false);
      if (k % 2 == 0) models[k].reset();
    });
  }
  for (auto& t : threads) t.join();
  for (const std::string& p : printed) EXPECT_EQ(p, expected);
}

}  // namespace
}  // namespace rigid::scene
