#include "detail/tape.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <sstream>
#include <string_view>

#include <fmt/format.h>

#include "rigid/common/error.hpp"

namespace rigid::lagrange::detail {
namespace {

constexpr std::int32_t kResultBase = 1 << 28;

// x^k, k ≥ 1, by binary powering: ⌈log₂ k⌉ squarings and at most as many products (the code
// export writes the same sequence, so exported code and tape agree bitwise)
double pow_int(double x, std::int32_t k) {
  double v = 1.0;
  while (k > 0) {
    if (k & 1) v *= x;
    x *= x;
    k >>= 1;
  }
  return v;
}

bool is_binary(Op op) {
  return op == Op::kAdd || op == Op::kSub || op == Op::kMul || op == Op::kDiv || op == Op::kPow;
}

}  // namespace

std::vector<double> Tape::make_scratch() const {
  std::vector<double> slots(num_inputs_ + constants_.size() + code_.size(), 0.0);
  std::copy(constants_.begin(), constants_.end(), slots.begin() + static_cast<std::ptrdiff_t>(num_inputs_));
  return slots;
}

void Tape::evaluate(const double* inputs, double* outputs) const {
  std::vector<double> scratch = make_scratch();
  evaluate(inputs, outputs, scratch);
}

// one loop per operation: the body is the instruction's arithmetic on slots a and b
#define RIGID_TAPE_LOOP(expr)                                   \
  for (std::uint32_t k = g.begin; k < g.end; ++k) {             \
    [[maybe_unused]] const double x = s[code[k].a];             \
    r[k] = (expr);                                              \
  }                                                             \
  break

void Tape::evaluate(const double* inputs, double* outputs, std::vector<double>& scratch) const {
  RIGID_ASSERT(scratch.size() == num_inputs_ + constants_.size() + code_.size());
  double* s = scratch.data();
  std::copy(inputs, inputs + num_inputs_, s);
  double* r = s + num_inputs_ + constants_.size();
  const Instruction* code = code_.data();
  // one dispatch per group; a group's instructions do not read each other's results
  for (const Group& g : groups_) {
    switch (g.op) {
      case Op::kAdd: RIGID_TAPE_LOOP(x + s[code[k].b]);
      case Op::kSub: RIGID_TAPE_LOOP(x - s[code[k].b]);
      case Op::kMul: RIGID_TAPE_LOOP(x * s[code[k].b]);
      case Op::kDiv: RIGID_TAPE_LOOP(x / s[code[k].b]);
      case Op::kNeg: RIGID_TAPE_LOOP(-x);
      case Op::kInv: RIGID_TAPE_LOOP(1.0 / x);
      case Op::kSquare: RIGID_TAPE_LOOP(x * x);
      case Op::kPow: RIGID_TAPE_LOOP(std::pow(x, s[code[k].b]));
      case Op::kPowInt: RIGID_TAPE_LOOP(pow_int(x, code[k].b));
      case Op::kSqrt: RIGID_TAPE_LOOP(std::sqrt(x));
      case Op::kInvSqrt: RIGID_TAPE_LOOP(1.0 / std::sqrt(x));
      case Op::kSin: RIGID_TAPE_LOOP(std::sin(x));
      case Op::kCos: RIGID_TAPE_LOOP(std::cos(x));
      case Op::kTan: RIGID_TAPE_LOOP(std::tan(x));
      case Op::kAsin: RIGID_TAPE_LOOP(std::asin(x));
      case Op::kAcos: RIGID_TAPE_LOOP(std::acos(x));
      case Op::kAtan: RIGID_TAPE_LOOP(std::atan(x));
      case Op::kExp: RIGID_TAPE_LOOP(std::exp(x));
      case Op::kLog: RIGID_TAPE_LOOP(std::log(x));
      case Op::kAbs: RIGID_TAPE_LOOP(std::abs(x));
      case Op::kSinh: RIGID_TAPE_LOOP(std::sinh(x));
      case Op::kCosh: RIGID_TAPE_LOOP(std::cosh(x));
      case Op::kTanh: RIGID_TAPE_LOOP(std::tanh(x));
    }
  }
  for (std::size_t k = 0; k < outputs_.size(); ++k) outputs[k] = s[outputs_[k]];
}

#undef RIGID_TAPE_LOOP

// one loop per operation: the body is the derivative of the instruction's result from the
// operands' values x, y, the result v and the operands' derivatives dx, dy
#define RIGID_TANGENT_LOOP(expr)                                                  \
  for (std::uint32_t k = g.begin; k < g.end; ++k) {                               \
    [[maybe_unused]] const double x = s[code[k].a], dx = ds[code[k].a];           \
    [[maybe_unused]] const double v = r[k];                                       \
    [[maybe_unused]] const double y = is_binary(g.op) ? s[code[k].b] : 0.0;       \
    [[maybe_unused]] const double dy = is_binary(g.op) ? ds[code[k].b] : 0.0;     \
    dr[k] = (expr);                                                               \
  }                                                                               \
  break

void Tape::tangent(const double* seed, double* tangent, const std::vector<double>& scratch,
                   std::vector<double>& dscratch) const {
  RIGID_ASSERT(scratch.size() == num_inputs_ + constants_.size() + code_.size());
  RIGID_ASSERT(dscratch.size() == scratch.size());
  const double* s = scratch.data();
  double* ds = dscratch.data();
  std::copy(seed, seed + num_inputs_, ds);
  std::fill(ds + num_inputs_, ds + num_inputs_ + constants_.size(), 0.0);
  const std::size_t first = num_inputs_ + constants_.size();
  const double* r = s + first;
  double* dr = ds + first;
  const Instruction* code = code_.data();
  for (const Group& g : groups_) {
    switch (g.op) {
      case Op::kAdd: RIGID_TANGENT_LOOP(dx + dy);
      case Op::kSub: RIGID_TANGENT_LOOP(dx - dy);
      case Op::kMul: RIGID_TANGENT_LOOP(dx * y + x * dy);
      case Op::kDiv: RIGID_TANGENT_LOOP((dx - v * dy) / y);
      case Op::kNeg: RIGID_TANGENT_LOOP(-dx);
      case Op::kInv: RIGID_TANGENT_LOOP(-v * v * dx);
      case Op::kSquare: RIGID_TANGENT_LOOP(2.0 * x * dx);
      case Op::kPow: RIGID_TANGENT_LOOP(dy == 0.0 ? y * std::pow(x, y - 1.0) * dx
                                                  : v * (dy * std::log(x) + y * dx / x));
      case Op::kPowInt: RIGID_TANGENT_LOOP(code[k].b * pow_int(x, code[k].b - 1) * dx);
      case Op::kSqrt: RIGID_TANGENT_LOOP(0.5 * dx / v);
      case Op::kInvSqrt: RIGID_TANGENT_LOOP(-0.5 * v / x * dx);
      case Op::kSin: RIGID_TANGENT_LOOP(std::cos(x) * dx);
      case Op::kCos: RIGID_TANGENT_LOOP(-std::sin(x) * dx);
      case Op::kTan: RIGID_TANGENT_LOOP((1.0 + v * v) * dx);
      case Op::kAsin: RIGID_TANGENT_LOOP(dx / std::sqrt(1.0 - x * x));
      case Op::kAcos: RIGID_TANGENT_LOOP(-dx / std::sqrt(1.0 - x * x));
      case Op::kAtan: RIGID_TANGENT_LOOP(dx / (1.0 + x * x));
      case Op::kExp: RIGID_TANGENT_LOOP(v * dx);
      case Op::kLog: RIGID_TANGENT_LOOP(dx / x);
      case Op::kAbs: RIGID_TANGENT_LOOP(x < 0.0 ? -dx : dx);
      case Op::kSinh: RIGID_TANGENT_LOOP(std::cosh(x) * dx);
      case Op::kCosh: RIGID_TANGENT_LOOP(std::sinh(x) * dx);
      case Op::kTanh: RIGID_TANGENT_LOOP((1.0 - v * v) * dx);
    }
  }
  for (std::size_t k = 0; k < outputs_.size(); ++k) tangent[k] = ds[outputs_[k]];
}

#undef RIGID_TANGENT_LOOP

TapeBuilder::TapeBuilder(const std::vector<GiNaC::symbol>& inputs, std::size_t first_run_constant)
    : num_inputs_(inputs.size()), first_run_constant_(first_run_constant) {
  for (std::size_t k = 0; k < inputs.size(); ++k) memo_[inputs[k]] = static_cast<std::int32_t>(k);
}

std::size_t TapeBuilder::add_output(const GiNaC::ex& e) {
  outputs_.push_back(slot_of(e));
  return outputs_.size() - 1;
}

void TapeBuilder::define(const GiNaC::symbol& name, const GiNaC::ex& e) {
  RIGID_ASSERT(!memo_.count(name));
  definitions_.emplace(name, e);  // compiled where an output first uses it
}

std::int32_t TapeBuilder::constant_slot(double value) {
  auto it = constant_slots_.find(value);
  if (it != constant_slots_.end()) return it->second;
  constants_.push_back(value);
  const auto slot = -static_cast<std::int32_t>(constants_.size());
  constant_slots_.emplace(value, slot);
  return slot;
}

std::int32_t TapeBuilder::emit(Op op, std::int32_t a, std::int32_t b) {
  // a + b and a·b are exactly commutative in IEEE arithmetic: one order for both
  if ((op == Op::kAdd || op == Op::kMul) && b < a) std::swap(a, b);
  const auto [it, fresh] = numbering_.emplace(std::make_tuple(op, a, b), 0);
  if (!fresh) return it->second;
  code_.push_back({op, a, b});
  it->second = kResultBase + static_cast<std::int32_t>(code_.size() - 1);
  return it->second;
}

std::int32_t TapeBuilder::emit_sum(std::vector<std::int32_t> terms) {
  RIGID_ASSERT(!terms.empty());
  while (terms.size() > 1) {
    std::size_t out = 0;
    for (std::size_t k = 0; k + 1 < terms.size(); k += 2) terms[out++] = emit(Op::kAdd, terms[k], terms[k + 1]);
    if (terms.size() % 2 == 1) terms[out++] = terms.back();
    terms.resize(out);
  }
  return terms.front();
}

std::int32_t TapeBuilder::emit_power(std::int32_t base, const GiNaC::ex& exponent) {
  using GiNaC::numeric;
  if (GiNaC::is_a<numeric>(exponent)) {
    const numeric k = GiNaC::ex_to<numeric>(exponent);
    // integer powers by multiplication while the exponent fits the op's 32 bits (q^(6^63)
    // would wrap: to_long of it negated overflowed); larger ones through pow
    if (k.is_integer() && GiNaC::abs(k) <= numeric(std::numeric_limits<std::int32_t>::max())) {
      const long n = k.to_long();
      if (n == 1) return base;
      if (n == 2) return emit(Op::kSquare, base);
      if (n == -1) return emit(Op::kInv, base);
      if (n > 0) return emit(Op::kPowInt, base, static_cast<std::int32_t>(n));
      if (n == -2) return emit(Op::kInv, emit(Op::kSquare, base));
      return emit(Op::kInv, emit(Op::kPowInt, base, static_cast<std::int32_t>(-n)));
    }
    if (k == numeric(1, 2)) return emit(Op::kSqrt, base);
    if (k == numeric(-1, 2)) return emit(Op::kInvSqrt, base);
    if (k == numeric(3, 2)) return emit(Op::kMul, base, emit(Op::kSqrt, base));
    if (k == numeric(-3, 2)) return emit(Op::kInv, emit(Op::kMul, base, emit(Op::kSqrt, base)));
  }
  return emit(Op::kPow, base, slot_of(exponent));
}

namespace {

// Longest key kept as text (TapeBuilder::key_of).
constexpr std::size_t kMaxKeyLength = 128;

// "#" and two 64-bit hashes of `text` in the manner of FNV-1a (Fowler–Noll–Vo: xor a byte,
// multiply), one with FNV's offset basis and prime, one with other constants (the golden-ratio
// multiplier 0x9e3779b97f4a7c15): the same on every machine and run; two keys of one
// expression that collided would only have their order follow GiNaC's.
std::string digest_key(std::string_view text) {
  std::uint64_t h1 = 14695981039346656037ULL, h2 = ~14695981039346656037ULL;
  for (const char c : text) {
    h1 = (h1 ^ static_cast<unsigned char>(c)) * 1099511628211ULL;
    h2 = (h2 ^ static_cast<unsigned char>(c)) * 0x9e3779b97f4a7c15ULL;
  }
  return fmt::format("#{:016x}{:016x}", h1, h2);
}

}  // namespace

// A key that depends only on the structure and the names, not on GiNaC's term order (which
// follows hash values and symbol serial numbers and so differs between two Systems built in
// one process). Sums and products are emitted in key order, so the same model always gives
// the same tape and bitwise the same trajectories.
const std::string& TapeBuilder::key_of(const GiNaC::ex& e) {
  using namespace GiNaC;
  auto found = keys_.find(e);
  if (found != keys_.end()) return found->second;
  std::string key;
  if (is_a<symbol>(e) || is_a<numeric>(e) || is_a<constant>(e)) {
    std::ostringstream os;
    os << e;
    key = os.str();
  } else {
    std::vector<std::string> parts;
    for (std::size_t k = 0; k < e.nops(); ++k) parts.push_back(key_of(e.op(k)));
    if (is_a<add>(e) || is_a<mul>(e)) std::sort(parts.begin(), parts.end());
    key = is_a<add>(e) ? "+(" : is_a<mul>(e) ? "*(" : is_a<power>(e) ? "^(" :
          is_a<function>(e) ? ex_to<function>(e).get_name() + "(" : "?(";
    for (const auto& part : parts) key += part + ",";
    key += ")";
    // A long key becomes a digest of itself: a key spelled out in full is as long as its
    // expression written as a tree, and an expression that shares subexpressions (a power of a
    // sum whose exponent is a sum) is exponentially longer as a tree than as the graph GiNaC
    // holds; every node's key then costs that length (a fuzz input took minutes). Keys up to
    // kMaxKeyLength keep their text, so short expressions keep their order.
    if (key.size() > kMaxKeyLength) key = digest_key(key);
  }
  return keys_.emplace(e, std::move(key)).first->second;
}

bool TapeBuilder::is_run_constant(const GiNaC::ex& e) {
  using namespace GiNaC;
  if (is_a<numeric>(e) || is_a<constant>(e)) return true;
  auto found = run_constant_.find(e);
  if (found != run_constant_.end()) return found->second;
  bool constant = true;
  if (is_a<symbol>(e)) {
    auto slot = memo_.find(e);
    auto defined = definitions_.find(e);
    constant = defined != definitions_.end()
                   ? is_run_constant(defined->second)
                   : slot != memo_.end() && static_cast<std::size_t>(slot->second) >= first_run_constant_;
  } else {
    for (std::size_t k = 0; k < e.nops() && constant; ++k) constant = is_run_constant(e.op(k));
  }
  run_constant_.emplace(e, constant);
  return constant;
}

GiNaC::exvector TapeBuilder::sorted_operands(const GiNaC::ex& e) {
  GiNaC::exvector ops(e.begin(), e.end());
  std::vector<std::pair<std::string, std::size_t>> order;
  for (std::size_t k = 0; k < ops.size(); ++k) order.emplace_back(key_of(ops[k]), k);
  std::sort(order.begin(), order.end());
  GiNaC::exvector out;
  for (const auto& [key, k] : order) out.push_back(ops[k]);
  return out;
}

std::int32_t TapeBuilder::slot_of(const GiNaC::ex& e) {
  using namespace GiNaC;
  auto found = memo_.find(e);
  if (found != memo_.end()) return found->second;
  std::int32_t s = 0;
  if (is_a<numeric>(e)) {
    RIGID_REQUIRE(ex_to<numeric>(e).is_real(), "complex constant {} in an expression",
                  ex_to<numeric>(e).to_double());
    s = constant_slot(ex_to<numeric>(e).to_double());
  } else if (is_a<constant>(e)) {
    s = constant_slot(ex_to<numeric>(e.evalf()).to_double());
  } else if (auto defined = definitions_.find(e); defined != definitions_.end()) {
    s = slot_of(defined->second);
  } else if (is_a<symbol>(e)) {
    std::ostringstream os;
    os << e;
    RIGID_ASSERT(false && "symbol without an input slot");
    RIGID_THROW("internal: symbol '{}' has no input slot", os.str());
  } else if (is_a<add>(e)) {
    // a sum: Σ positive terms − Σ terms with a negative numeric factor (each a balanced tree)
    std::vector<std::int32_t> plus, minus;
    for (const ex& operand : sorted_operands(e)) {
      ex term = operand;
      bool negative = false;
      if (is_a<mul>(term)) {
        const ex c = term.op(term.nops() - 1);
        if (is_a<numeric>(c) && ex_to<numeric>(c).is_negative()) {
          negative = true;
          term = -term;
        }
      } else if (is_a<numeric>(term) && ex_to<numeric>(term).is_negative()) {
        negative = true;
        term = -term;
      }
      (negative ? minus : plus).push_back(slot_of(term));
    }
    if (plus.empty()) {
      s = emit(Op::kNeg, emit_sum(std::move(minus)));
    } else if (minus.empty()) {
      s = emit_sum(std::move(plus));
    } else {
      s = emit(Op::kSub, emit_sum(std::move(plus)), emit_sum(std::move(minus)));
    }
  } else if (is_a<mul>(e)) {
    // a product: factors with negative powers divide; run-constant factors first
    std::int32_t num = 0, den = 0;
    bool have_num = false, have_den = false;
    exvector factors = sorted_operands(e);
    std::stable_partition(factors.begin(), factors.end(), [&](const ex& f) { return is_run_constant(f); });
    for (const ex& f : factors) {
      if (is_a<power>(f) && is_a<numeric>(f.op(1)) && ex_to<numeric>(f.op(1)).is_negative()) {
        const std::int32_t d = slot_of(pow(f.op(0), -f.op(1)));
        den = have_den ? emit(Op::kMul, den, d) : d;
        have_den = true;
        continue;
      }
      const std::int32_t t = slot_of(f);
      num = have_num ? emit(Op::kMul, num, t) : t;
      have_num = true;
    }
    if (!have_num) {
      s = emit(Op::kInv, den);
    } else {
      s = have_den ? emit(Op::kDiv, num, den) : num;
    }
  } else if (is_a<power>(e)) {
    s = emit_power(slot_of(e.op(0)), e.op(1));
  } else if (is_a<function>(e)) {
    const std::string name = ex_to<function>(e).get_name();
    static const std::map<std::string, Op> kFunctions = {
        {"sin", Op::kSin},   {"cos", Op::kCos},   {"tan", Op::kTan},   {"asin", Op::kAsin},
        {"acos", Op::kAcos}, {"atan", Op::kAtan}, {"exp", Op::kExp},   {"log", Op::kLog},
        {"abs", Op::kAbs},   {"sinh", Op::kSinh}, {"cosh", Op::kCosh}, {"tanh", Op::kTanh}};
    auto it = kFunctions.find(name);
    RIGID_REQUIRE(it != kFunctions.end() && e.nops() == 1,
                  "function '{}' cannot be compiled; supported: sin cos tan asin acos atan exp "
                  "log sqrt abs sinh cosh tanh", name);
    s = emit(it->second, slot_of(e.op(0)));
  } else {
    std::ostringstream os;
    os << e;
    RIGID_THROW("cannot compile the expression '{}'", os.str());
  }
  memo_.emplace(e, s);
  return s;
}

Tape TapeBuilder::build() const {
  Tape tape;
  tape.num_inputs_ = num_inputs_;
  tape.constants_ = constants_;
  const auto nc = static_cast<std::int32_t>(constants_.size());
  const auto ni = static_cast<std::int32_t>(num_inputs_);
  // schedule: level of each instruction (operands come earlier in code_, so one pass), then
  // a stable sort by (level, operation); within a group the emission order is kept
  std::vector<std::int32_t> level(code_.size(), 0);
  auto level_of = [&](std::int32_t slot) {
    return slot >= kResultBase ? level[static_cast<std::size_t>(slot - kResultBase)] : 0;
  };
  for (std::size_t k = 0; k < code_.size(); ++k) {
    const Instruction& in = code_[k];
    level[k] = 1 + std::max(level_of(in.a), is_binary(in.op) ? level_of(in.b) : 0);
  }
  std::vector<std::size_t> order(code_.size());
  for (std::size_t k = 0; k < order.size(); ++k) order[k] = k;
  std::stable_sort(order.begin(), order.end(), [&](std::size_t x, std::size_t y) {
    return std::make_pair(level[x], code_[x].op) < std::make_pair(level[y], code_[y].op);
  });
  std::vector<std::int32_t> position(code_.size());
  for (std::size_t k = 0; k < order.size(); ++k) position[order[k]] = static_cast<std::int32_t>(k);
  auto resolve = [&](std::int32_t s) {
    if (s >= kResultBase) return ni + nc + position[static_cast<std::size_t>(s - kResultBase)];
    if (s < 0) return ni + (-1 - s);
    return s;
  };
  tape.code_.reserve(code_.size());
  for (std::size_t k = 0; k < order.size(); ++k) {
    const Instruction& in = code_[order[k]];
    tape.code_.push_back({in.op, resolve(in.a), is_binary(in.op) ? resolve(in.b) : in.b});
    const auto at = static_cast<std::uint32_t>(k);
    if (tape.groups_.empty() || tape.groups_.back().op != in.op ||
        level[order[tape.groups_.back().begin]] != level[order[k]]) {
      tape.groups_.push_back({in.op, at, at + 1});
    } else {
      tape.groups_.back().end = at + 1;
    }
  }
  for (std::int32_t o : outputs_) tape.outputs_.push_back(resolve(o));
  return tape;
}

}  // namespace rigid::lagrange::detail
