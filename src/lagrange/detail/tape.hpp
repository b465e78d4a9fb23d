#pragma once

#include <cstdint>
#include <map>
#include <string>
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
class Tape {
 public:
  /// Scratch slots for evaluate(), with the constants in place (one per thread or run).
  [[nodiscard]] std::vector<double> make_scratch() const;
  /// Evaluates; `inputs` has num_inputs() values, `outputs` receives num_outputs(); `scratch`
  /// comes from make_scratch() of this tape.
  void evaluate(const double* inputs, double* outputs, std::vector<double>& scratch) const;
  /// The same with a scratch made for this call.
  void evaluate(const double* inputs, double* outputs) const;
  [[nodiscard]] std::size_t size() const { return code_.size(); }
  [[nodiscard]] std::size_t num_inputs() const { return num_inputs_; }
  [[nodiscard]] std::size_t num_outputs() const { return outputs_.size(); }
  /// How many instructions perform `op` (for tests of the sharing).
  [[nodiscard]] std::size_t count(Op op) const {
    std::size_t k = 0;
    for (const Instruction& in : code_) k += in.op == op ? 1 : 0;
    return k;
  }

 private:
  friend class TapeBuilder;
  std::size_t num_inputs_ = 0;
  std::vector<double> constants_;
  std::vector<Instruction> code_;
  std::vector<std::int32_t> outputs_;
};

/// Compiles GiNaC expressions to a Tape, sharing every repeated subexpression (GiNaC
/// expressions are hash-consed trees; a map from subexpression to slot finds the repeats).
class TapeBuilder {
 public:
  /// `inputs` are the symbols read from the input array, in order.
  explicit TapeBuilder(const std::vector<GiNaC::symbol>& inputs);
  /// Adds an output; returns its index.
  std::size_t add_output(const GiNaC::ex& e);
  [[nodiscard]] Tape build() const;

 private:
  std::int32_t slot_of(const GiNaC::ex& e);
  std::int32_t constant_slot(double value);
  std::int32_t emit(Op op, std::int32_t a, std::int32_t b = 0);
  std::int32_t emit_power(std::int32_t base, const GiNaC::ex& exponent);
  const std::string& key_of(const GiNaC::ex& e);
  GiNaC::exvector sorted_operands(const GiNaC::ex& e);

  std::size_t num_inputs_;
  std::map<GiNaC::ex, std::int32_t, GiNaC::ex_is_less> memo_;
  std::map<GiNaC::ex, std::string, GiNaC::ex_is_less> keys_;
  std::map<double, std::int32_t> constant_slots_;
  std::vector<double> constants_;
  // instructions with operand slots encoded as: input k → k, constant k → -1 - k,
  // result k → kResultBase + k; resolved in build()
  std::vector<Instruction> code_;
  std::vector<std::int32_t> outputs_;
};

}  // namespace rigid::lagrange::detail
