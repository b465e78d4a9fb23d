#include "rigid/lagrange/function.hpp"

#include <atomic>
#include <cctype>
#include <cmath>
#include <cstdint>
#include <map>

#include <fmt/format.h>

#include "rigid/common/error.hpp"
#include "rigid/common/number_literal.hpp"
#include "rigid/lagrange/names.hpp"

#include "detail/parser.hpp"
#include "detail/symbolic_lock.hpp"
#include "detail/tape.hpp"

namespace rigid::lagrange {

struct CompiledFunction::Impl {
  std::string text;
  std::vector<std::string> variables;
  detail::Tape tape;
  std::uint64_t id = 0;  // tells one function's scratch from another's in a thread
};

namespace {

std::atomic<std::uint64_t> g_next_id{1};

bool is_identifier(std::string_view name) {
  if (name.empty() || !(std::isalpha(static_cast<unsigned char>(name[0])) || name[0] == '_')) {
    return false;
  }
  for (const char c : name) {
    if (!(std::isalnum(static_cast<unsigned char>(c)) || c == '_')) return false;
  }
  return true;
}

}  // namespace

double CompiledFunction::operator()(std::span<const double> x) const {
  RIGID_REQUIRE_AS("CompiledFunction", x.size() == impl_->variables.size(),
                   "'{}' takes {} value{} ({}), got {}", impl_->text, impl_->variables.size(),
                   impl_->variables.size() == 1 ? "" : "s", fmt::join(impl_->variables, ", "),
                   x.size());
  // the scratch holds the tape's constants in place, so it is remade when this thread turns to
  // another function (told apart by an id, not an address a later function may reuse)
  thread_local std::uint64_t scratch_of = 0;
  thread_local std::vector<double> scratch;
  if (scratch_of != impl_->id) {
    scratch = impl_->tape.make_scratch();
    scratch_of = impl_->id;
  }
  double out = 0.0;
  impl_->tape.evaluate(x.data(), &out, scratch);
  return out;
}

const std::vector<std::string>& CompiledFunction::variables() const { return impl_->variables; }

const std::string& CompiledFunction::text() const { return impl_->text; }

CompiledFunction compile_function(const Expression& expression,
                                  const std::vector<std::string>& variables,
                                  const std::vector<Parameter>& parameters,
                                  std::string_view context) {
  detail::SymbolicLock lock;
  std::map<std::string, GiNaC::ex> names;
  for (const Parameter& p : parameters) {
    // inf, NaN and subnormals are outside CLN's double-floats
    if (!(std::isfinite(p.value) && (p.value == 0.0 || std::abs(p.value) >= kSmallestLiteral))) {
      detail::throw_at(expression, 0, context,
                       fmt::format("parameter '{}' = {:.17g}: expected a finite number, 0 or of "
                                   "magnitude at least {:.17g}",
                                   p.name, p.value, kSmallestLiteral));
    }
    names[p.name] = GiNaC::numeric(p.value);
  }
  std::vector<GiNaC::symbol> symbols;
  symbols.reserve(variables.size());
  for (const std::string& v : variables) {
    RIGID_REQUIRE_AS("compile_function", is_identifier(v) && !is_reserved_name(v),
                     "variable '{}' is not an identifier, or is reserved; expected a name such "
                     "as x",
                     v);
    RIGID_REQUIRE_AS("compile_function", names.count(v) == 0,
                     "variable '{}' is also a parameter's name", v);
    symbols.emplace_back(v);
    names[v] = symbols.back();
  }
  if (expression.text.find_first_not_of(" \t") == std::string::npos) {
    detail::throw_at(expression, 0, context, "empty expression; expected a number, a name or '('");
  }
  const GiNaC::ex parsed = detail::parse_expression(expression, names, context);
  auto impl = std::make_shared<CompiledFunction::Impl>();
  impl->text = expression.text;
  impl->variables = variables;
  detail::TapeBuilder builder(symbols);
  try {
    builder.add_output(parsed);
    impl->tape = builder.build();
  } catch (const Error&) {
    throw;
  } catch (const std::exception& e) {  // a GiNaC or CLN failure: named, not shown raw
    detail::throw_at(expression, 0, context,
                     fmt::format("'{}' cannot be compiled to a function of ({}): it is not a real "
                                 "expression of them",
                                 expression.text, fmt::join(variables, ", ")));
  }
  impl->id = g_next_id.fetch_add(1, std::memory_order_relaxed);
  CompiledFunction f;
  f.impl_ = std::move(impl);
  return f;
}

}  // namespace rigid::lagrange
