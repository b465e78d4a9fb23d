#pragma once
// Long calls release the GIL and stay interruptible: Ctrl-C becomes KeyboardInterrupt with
// nothing half-written. While the library runs without the GIL, its progress poll
// (rigid::integrate::MarchControl) takes the GIL at most every 50 ms of wall time and asks
// Python whether a signal came (PyErr_CheckSignals); if the signal handler raised, the cancel
// flag stops the run with rigid::Cancelled, which the module's translator turns into
// KeyboardInterrupt (rigid_py.cpp).
#include <atomic>
#include <chrono>

#include <pybind11/pybind11.h>

#include "rigid/integrate/march.hpp"

namespace rigid::python {

class Interruptible {
 public:
  Interruptible() {
    control_.cancel = &cancel_;
    control_.progress = [this](double) { poll(); };
  }
  Interruptible(const Interruptible&) = delete;
  Interruptible& operator=(const Interruptible&) = delete;
  /// The control to pass to the library call (valid while this object lives).
  [[nodiscard]] const integrate::MarchControl& control() const { return control_; }

 private:
  void poll() {
    const auto now = std::chrono::steady_clock::now();
    if (now - last_ < std::chrono::milliseconds(50)) return;
    last_ = now;
    pybind11::gil_scoped_acquire gil;
    if (PyErr_CheckSignals() != 0) {
      PyErr_Clear();  // raised again as KeyboardInterrupt from rigid::Cancelled
      cancel_ = true;
    }
  }
  std::atomic<bool> cancel_{false};
  integrate::MarchControl control_;
  std::chrono::steady_clock::time_point last_ = std::chrono::steady_clock::now();
};

}  // namespace rigid::python
