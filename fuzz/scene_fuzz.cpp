// Fuzz target: a TOML scene parsed and built into a Model (parameters evaluated, equations
// derived, bodies checked), its equations printed, its run checked and run for a short span.
// Runs are bounded here so that a slow input is a finding of the parser or the model, not of
// the time span the input asked for: t_end at most 0.05 s, output rows at least 1e-3 s
// apart (or every step), at most 20 000 steps.
#include <string>
#include <string_view>

#include "fuzz_support.hpp"
#include "rigid/scene.hpp"

namespace {

constexpr double kMaxEnd = 0.05;       // s
constexpr double kMinOutputDt = 1e-3;  // s
constexpr std::size_t kMaxSteps = 20'000;

rigid::scene::Expression number(double value, const rigid::SourceLocation& where) {
  rigid::scene::Expression e;
  e.text = std::to_string(value);
  e.where = where;
  e.number = value;
  return e;
}

// Bounds the span and the output rows of a run (only what the file asked for beyond them).
void bound_run(rigid::scene::Simulation& s) {
  if (!s.t_end.number || !(*s.t_end.number <= kMaxEnd)) s.t_end = number(kMaxEnd, s.t_end.where);
  if (s.output_dt && !(s.output_dt->number && *s.output_dt->number >= kMinOutputDt)) {
    s.output_dt = number(kMinOutputDt, s.output_dt->where);
  }
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string_view input = rigid::fuzz::as_text(data, size);
  const auto file = rigid::fuzz::scratch_dir() / "scene.toml";
  rigid::fuzz::refuse_or_return(input, [&] {
    rigid::scene::Scene scene = rigid::scene::parse_scene(input, file);
    bound_run(scene.simulation);
    const rigid::scene::Model model(scene);
    (void)model.equations(false);
    (void)model.equations(true);
    rigid::scene::RunOptions options;
    options.control.max_steps = kMaxSteps;
    model.check(options);
    (void)model.run(options);
  });
  return 0;
}
