#pragma once

// The one guard of the symbolic core. GiNaC and CLN are not thread-safe: expressions share
// nodes whose reference counts are not atomic, and the library keeps global tables (the
// flyweight numbers 0, 1, −1, …, symbol serial numbers, the print and evaluation state). Two
// threads that copy or destroy expressions at once corrupt the heap. So every entry into them
// — deriving a System and destroying it, printing its equations, linearising, exporting,
// evaluating a constant expression, printing a free body's equations — holds this lock, and
// nothing outside rigid::lagrange includes GiNaC. Numeric work (tapes, workspaces, simulation)
// never takes it.
//
// The mutex is recursive: an entry may call another (emit → emit_cpp, normal_modes →
// evaluate_constant) without knowing whether it already holds the guard. The outermost entry
// of a thread is counted, with the time it holds the lock (rigid/lagrange/symbolic_core.hpp).

#include <chrono>

namespace rigid::lagrange::detail {

/// Holds the symbolic core's lock for its lifetime.
class SymbolicLock {
 public:
  SymbolicLock();
  ~SymbolicLock();
  SymbolicLock(const SymbolicLock&) = delete;
  SymbolicLock& operator=(const SymbolicLock&) = delete;

 private:
  bool outermost_ = false;
  std::chrono::steady_clock::time_point since_{};
};

}  // namespace rigid::lagrange::detail
