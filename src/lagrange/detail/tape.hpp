#pragma once

#include <cstdint>
#include <map>
#include <string>
#include <tuple>
#include <vector>

#include <ginac/ginac.h>

namespace rigid::lagrange::detail {

/// One operation of the tape. Every instruction writes its own slot: the slot of
/// instruction k is num_inputs + num_constants + k (static single assignment).
enum class Op : std::uint8_t {
  kAdd, kSub, kMul, kDiv, kNeg, kInv, kSquare, kPow, kPowInt, kSqrt, kInvSqrt,
  kSin, kCos, kTan, kAsin, kAcos, kAtan, kExp, kLog, kAbs, kSinh, kCosh, kTanh,
};

struct Instruction {
  Op op;
  std::int32_t a;
  std::int32_t b;  ///< second operand slot, or the integer exponent of kPowInt
};

/// A flat instruction sequence computing a list of outputs from a list of inputs.
/// Slots: [inputs | constants | instruction results]. Immutable once built: every evaluation
/// writes into a scratch of the caller's, so one tape serves several threads at once.
///
/// Execution order: the instructions are sorted by level (1 + the highest level of their
/// operands; inputs and constants are level 0) and, within a level, by operation, so that
/// runs of one operation form groups with no dependence inside a group. evaluate() dispatches
/// once per group and runs each group as a tight loop, instead of dispatching once per
/// instruction (an unpredictable indirect branch per instruction cost 2–3× the arithmetic).
class Tape {
 public:
  /// Scratch slots for evaluate(), with the constants in place (one per thread or run).
  [[nodiscard]] std::vector<double> make_scratch() const;
  /// Evaluates; `inputs` has num_inputs() values, `outputs` receives num_outputs(); `scratch`
  /// comes from make_scratch() of this tape.
  void evaluate(const double* inputs, double* outputs, std::vector<double>& scratch) const;
  /// The same with a scratch made for this call.
  void evaluate(const double* inputs, double* outputs) const;
  /// Forward-mode derivative: with `scratch` from evaluate(inputs, …) of this tape, writes
  /// Σ_k ∂output/∂input_k · seed_k into `tangent` (num_outputs() values); `dscratch` is a
  /// second scratch of make_scratch()'s size. Exact up to rounding (each operation's own
  /// derivative rule), where the operations are differentiable.
  void tangent(const double* seed, double* tangent, const std::vector<double>& scratch,
               std::vector<double>& dscratch) const;
  [[nodiscard]] std::size_t size() const { return code_.size(); }
  [[nodiscard]] std::size_t num_inputs() const { return num_inputs_; }
  [[nodiscard]] std::size_t num_outputs() const { return outputs_.size(); }
  /// How many instructions perform `op` (for tests of the sharing).
  [[nodiscard]] std::size_t count(Op op) const {
    std::size_t k = 0;
    for (const Instruction& in : code_) k += in.op == op ? 1 : 0;
    return k;
  }
  /// Number of groups evaluate() dispatches on (runs of one operation at one level).
  [[nodiscard]] std::size_t num_groups() const { return groups_.size(); }
  /// The constants, in slot order (slot num_inputs() + k).
  [[nodiscard]] const std::vector<double>& constants() const { return constants_; }
  /// The instructions in execution order; instruction k writes slot
  /// num_inputs() + constants().size() + k and reads only slots below its own.
  [[nodiscard]] const std::vector<Instruction>& instructions() const { return code_; }
  /// The slot of each output.
  [[nodiscard]] const std::vector<std::int32_t>& outputs() const { return outputs_; }

 private:
  friend class TapeBuilder;
  /// Instructions [begin, end) of code_: one operation, no dependence among them.
  struct Group {
    Op op;
    std::uint32_t begin, end;
  };
  std::size_t num_inputs_ = 0;
  std::vector<double> constants_;
  std::vector<Instruction> code_;
  std::vector<Group> groups_;
  std::vector<std::int32_t> outputs_;
};

/// Compiles GiNaC expressions to a Tape, sharing every repeated subexpression (GiNaC
/// expressions are hash-consed trees; a map from subexpression to slot finds the repeats) and
/// every repeated instruction (value numbering: an (operation, operands) already emitted is
/// not emitted again, which shares the partial products of products with a common prefix).
class TapeBuilder {
 public:
  /// `inputs` are the symbols read from the input array, in order; those from
  /// `first_run_constant` on (the parameters) do not change during a run. A product multiplies
  /// its run-constant factors first, so that the terms of a sum share that prefix (l₁l₂ in
  /// every term of a chain's M and f) by value numbering.
  explicit TapeBuilder(const std::vector<GiNaC::symbol>& inputs,
                       std::size_t first_run_constant = static_cast<std::size_t>(-1));
  /// Adds an output; returns its index.
  std::size_t add_output(const GiNaC::ex& e);
  /// Makes `name` stand for the value of `e` in every later expression (an intermediate of a
  /// tree's recursion); `e` may use the inputs and the names defined before it.
  void define(const GiNaC::symbol& name, const GiNaC::ex& e);
  [[nodiscard]] Tape build() const;

 private:
  std::int32_t slot_of(const GiNaC::ex& e);
  std::int32_t constant_slot(double value);
  std::int32_t emit(Op op, std::int32_t a, std::int32_t b = 0);
  std::int32_t emit_power(std::int32_t base, const GiNaC::ex& exponent);
  /// Σ of `terms` as a balanced tree (depth ⌈log₂ n⌉ rather than n − 1: fewer levels, so
  /// fewer and larger groups).
  std::int32_t emit_sum(std::vector<std::int32_t> terms);
  const std::string& key_of(const GiNaC::ex& e);
  GiNaC::exvector sorted_operands(const GiNaC::ex& e);
  bool is_run_constant(const GiNaC::ex& e);

  std::size_t num_inputs_;
  std::size_t first_run_constant_;
  std::map<GiNaC::ex, bool, GiNaC::ex_is_less> run_constant_;
  std::map<GiNaC::ex, std::int32_t, GiNaC::ex_is_less> memo_;
  std::map<GiNaC::ex, GiNaC::ex, GiNaC::ex_is_less> definitions_;  // define(): name → value
  std::map<GiNaC::ex, std::string, GiNaC::ex_is_less> keys_;
  std::map<double, std::int32_t> constant_slots_;
  std::vector<double> constants_;
  // instructions with operand slots encoded as: input k → k, constant k → -1 - k,
  // result k → kResultBase + k; resolved in build()
  std::vector<Instruction> code_;
  std::map<std::tuple<Op, std::int32_t, std::int32_t>, std::int32_t> numbering_;
  std::vector<std::int32_t> outputs_;
};

}  // namespace rigid::lagrange::detail
