#pragma once
// Batch arguments for the rigid.so3 functions: numpy arrays of shape (N, k…) or one (k…)
// element, read by python/convert.hpp (one converter: the same dtype and shape wording as
// every other array argument), then looped over in C++ (without the GIL for large N, on several
// threads for very large N).
#include <fmt/format.h>
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>

#include <algorithm>
#include <array>
#include <atomic>
#include <chrono>
#include <cstdint>
#include <exception>
#include <functional>
#include <string>
#include <string_view>
#include <system_error>
#include <thread>
#include <vector>

#include "convert.hpp"
#include "rigid/common/error.hpp"
#include "rigid/common/wording.hpp"

namespace rigid::python {

namespace py = pybind11;

/// "(N, 3)", "(N, 3, 3)": the shape a batch argument must have, for messages.
inline std::string batch_shape_text(std::initializer_list<py::ssize_t> element) {
  std::string s = "(N";
  for (py::ssize_t k : element) s += fmt::format(", {}", k);
  return s + ")";
}

/// A batch argument: N elements of `element` shape, contiguous float64, row-major.
/// `single` is true when the argument was one element (shape `element`, no leading N): the
/// result then drops its leading axis too.
struct BatchArray {
  convert::RealArray array;  // keeps the data alive
  const double* data = nullptr;
  py::ssize_t row_size = 0;  // doubles per element: 3, 4 or 9
  py::ssize_t n = 0;
  bool single = false;
  [[nodiscard]] const double* row(py::ssize_t i) const { return data + i * row_size; }
};

/// The argument `arg` as a float64 batch of elements of shape `element`, read by
/// convert::real_array (python/convert.hpp: the same dtype, ragged-list and no-array refusals
/// as every other array argument); then a shape that is neither (N, element...) nor (element...)
/// raises rigid::Error: "so3.exp(): argument 'omega' must have shape (N, 3) or (3,); got (5, 4)".
/// Finiteness is left to the row loop, whose refusals name the row.
inline BatchArray batch_argument(const pybind11::handle& obj, const convert::Arg& arg,
                                 std::initializer_list<py::ssize_t> element) {
  std::string one = "(";
  for (py::ssize_t k : element) one += fmt::format("{}{}", one.size() > 1 ? ", " : "", k);
  const std::string expected =
      fmt::format("{} or {}", batch_shape_text(element), one + (element.size() == 1 ? ",)" : ")"));
  const convert::RealArray a = convert::real_array(obj, arg, expected, convert::Finite::kAllowed);
  const auto dims = static_cast<py::ssize_t>(element.size());
  bool ok = a.ndim() == dims || a.ndim() == dims + 1;
  const py::ssize_t lead = a.ndim() == dims + 1 ? 1 : 0;
  if (ok) {
    py::ssize_t d = 0;
    for (py::ssize_t k : element) ok = ok && a.shape(lead + d++) == k;
  }
  if (!ok) {
    convert::refuse(arg,
                    fmt::format("must have shape {}; got {}", expected, convert::shape_text(a)));
  }
  BatchArray b;
  b.array = a;
  b.single = lead == 0;
  b.n = b.single ? 1 : a.shape(0);
  b.data = b.array.data();
  b.row_size = 1;
  for (py::ssize_t k : element) b.row_size *= k;
  return b;
}

/// N of a result from arguments that are each N long or single (broadcast), or rigid::Error
/// naming both lengths.
inline py::ssize_t broadcast_rows(std::string_view function, std::string_view name_a,
                                  const BatchArray& a, std::string_view name_b,
                                  const BatchArray& b) {
  if (a.single || b.single || a.n == b.n) return a.single ? b.n : a.n;
  throw rigid::Error(
      fmt::format("{}(): arguments '{}' and '{}' must have the same number of rows N (or "
                  "one of them a single element); got {} and {}",
                  function, name_a, name_b, a.n, b.n));
}

/// A result array of shape (n, element…), or (element…) when `single`.
inline pybind11::array_t<double> batch_result(py::ssize_t n, bool single,
                                              std::initializer_list<py::ssize_t> element) {
  std::vector<py::ssize_t> shape;
  if (!single) shape.push_back(n);
  shape.insert(shape.end(), element.begin(), element.end());
  return pybind11::array_t<double>(shape);
}

/// A refusal of one element of a batch: the argument it came from and the library's message
/// (rigid::Error's "from_matrix(): matrix … is not a rotation", the function name dropped).
struct RowError {
  std::string_view argument;
  std::string message;
};

/// Calls kernel(i) for i in [0, n). Each call either completes or throws rigid::Error (about
/// the first argument) or RowError; the loop then reports the first refused row, whichever
/// thread met it, as rigid::Error "<function>(): argument '<arg>' row <i>: <message>" (without
/// "row <i>" when the arguments were single elements).
/// Without the GIL from kReleaseGil rows on (the kernel must not touch Python objects); from
/// kThreadRows rows on, split over the hardware threads (at most 8), each row's result being
/// independent of the split. Without the GIL the call stays interruptible: every kBlock rows
/// the calling thread asks Python, at most every 50 ms, whether a signal came
/// (PyErr_CheckSignals, as python/interrupt.hpp does for runs); Ctrl-C stops every thread at
/// its next block and the call raises KeyboardInterrupt (rigid::Cancelled), returning nothing.
/// With `range` (for_each_row's second form): range(begin, end), for blocks of at most kBlock
/// rows, computes them all at once (a vectorised loop) and returns true, or returns false when
/// some row of the block needs kernel; kernel(i) then computes (or refuses) each row of that
/// block, so refusals read as without `range`. range must not throw or touch Python objects.
template <class Kernel, class Range>
void for_each_row(py::ssize_t n, bool single, std::string_view function,
                  std::string_view first_argument, const Kernel& kernel, const Range& range) {
  constexpr py::ssize_t kReleaseGil = 4096;
  constexpr py::ssize_t kThreadRows = 32768;
  constexpr py::ssize_t kBlock = 4096;
  struct Failure {
    py::ssize_t row = -1;
    std::string_view argument;
    std::string message;
  };
  std::atomic<bool> cancel{false};
  auto last_poll = std::chrono::steady_clock::now();
  const auto poll = [&] {
    const auto now = std::chrono::steady_clock::now();
    if (now - last_poll < std::chrono::milliseconds(50)) return;
    last_poll = now;
    pybind11::gil_scoped_acquire gil;
    if (PyErr_CheckSignals() != 0) {
      PyErr_Clear();  // raised again as KeyboardInterrupt from rigid::Cancelled
      cancel = true;
    }
  };
  // rows [begin, end) in blocks; `polls`: the calling thread, which alone may ask Python
  const auto run = [&](py::ssize_t begin, py::ssize_t end, Failure& f, bool polls) {
    for (py::ssize_t b = begin; b < end; b += kBlock) {
      if (cancel.load(std::memory_order_relaxed)) return;
      const py::ssize_t block_end = std::min(end, b + kBlock);
      for (py::ssize_t i = range(b, block_end) ? block_end : b; i < block_end; ++i) {
        try {
          kernel(i);
        } catch (const RowError& e) {
          f = Failure{i, e.argument, e.message};
          return;
        } catch (const rigid::Error& e) {
          f = Failure{i, first_argument, rigid::strip_function_names(e.what())};
          return;
        } catch (const std::exception& e) {  // bad_alloc: reported, never lost in a thread
          f = Failure{i, first_argument, e.what()};
          return;
        }
      }
      if (polls) poll();
    }
  };
  std::vector<Failure> failures;
  if (n < kReleaseGil) {
    failures.resize(1);
    run(0, n, failures[0], false);
  } else {
    pybind11::gil_scoped_release release;
    const auto hw = static_cast<py::ssize_t>(std::max(1u, std::thread::hardware_concurrency()));
    const py::ssize_t threads =
        n < kThreadRows ? 1 : std::clamp<py::ssize_t>(std::min(hw, n / (kThreadRows / 2)), 1, 8);
    failures.resize(static_cast<std::size_t>(threads));
    const py::ssize_t chunk = (n + threads - 1) / threads;
    const auto begin_of = [&](py::ssize_t t) { return std::min(n, t * chunk); };
    std::vector<std::thread> pool;
    py::ssize_t started = 1;  // chunk 0 runs on this thread
    try {
      for (; started < threads; ++started) {
        pool.emplace_back(run, begin_of(started), begin_of(started + 1),
                          std::ref(failures[static_cast<std::size_t>(started)]), false);
      }
    } catch (const std::system_error&) {  // no more threads: this one does the rest
    }
    run(0, begin_of(1), failures[0], true);
    for (py::ssize_t t = started; t < threads; ++t) {
      run(begin_of(t), begin_of(t + 1), failures[static_cast<std::size_t>(t)], true);
    }
    for (auto& th : pool) th.join();
  }
  if (cancel) throw rigid::Cancelled(fmt::format("{}(): interrupted", function));
  for (const Failure& f : failures) {  // chunks in row order: the first refusal is the first found
    if (f.row >= 0) {
      if (single)
        throw rigid::Error(fmt::format("{}(): argument '{}': {}", function, f.argument, f.message));
      throw rigid::Error(
          fmt::format("{}(): argument '{}' row {}: {}", function, f.argument, f.row, f.message));
    }
  }
}

template <class Kernel>
void for_each_row(py::ssize_t n, bool single, std::string_view function,
                  std::string_view first_argument, const Kernel& kernel) {
  for_each_row(n, single, function, first_argument, kernel,
               [](py::ssize_t, py::ssize_t) { return false; });
}

}  // namespace rigid::python
