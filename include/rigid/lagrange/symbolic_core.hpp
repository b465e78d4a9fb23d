#pragma once

/// The symbolic core's use: how often it was entered and how long it was held. GiNaC and CLN are
/// not thread-safe, so rigid::lagrange enters them behind one process-wide lock (deriving a
/// System or destroying it, printing equations, normal modes, export, a constant expression
/// that is more than a number or a name). Whatever runs under it is serial whatever the number
/// of threads: these counters are the serial work of a multi-threaded use of rigid (a sweep's
/// runs, Python threads), measured rather than estimated.

#include <cstdint>

namespace rigid::lagrange {

struct SymbolicCoreUsage {
  std::uint64_t entries = 0;   ///< outermost entries (an entry nested in another is not counted)
  double seconds_held = 0.0;   ///< wall time the lock was held, all threads together (s)
};

/// The counters since the process started (they only grow; subtract two readings).
[[nodiscard]] SymbolicCoreUsage symbolic_core_usage();

}  // namespace rigid::lagrange
