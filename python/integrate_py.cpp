// rigid.integrate: the library's integrators (rk4, dopri5, implicit midpoint, Störmer–Verlet)
// on any ODE dy/dt = f(t, y) given as a Python function, with the library's step rule, output
// grid and non-finite check: what a scene of coordinates runs, for a right-hand side of one's own.
#include <fmt/format.h>
#include <pybind11/eigen.h>
#include <pybind11/functional.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <string>
#include <vector>

#include "convert.hpp"
#include "interrupt.hpp"
#include "rigid/integrate.hpp"

namespace py = pybind11;
namespace cv = rigid::python::convert;

void bind_integrate(py::module_& m) {
  namespace ri = rigid::integrate;
  auto integrate = m.def_submodule(
      "integrate", "Integrators on Rⁿ: rk4, dopri5, implicit_midpoint, stormer_verlet.");
  integrate.def(
      "solve",
      [](const py::function& rhs, const py::object& y0_arg, double t_end, double t0,
         const std::string& method, double dt, double rtol, double atol, double output_dt,
         int n_position, const std::vector<std::string>& names) {
        const char* f = "rigid.integrate.solve";
        const Eigen::VectorXd y0 = cv::vector(y0_arg, {f, "y0"});
        const Eigen::Index n = y0.size();
        ri::Problem problem;
        problem.y0 = y0;
        problem.t0 = t0;
        problem.t_end = t_end;
        problem.n_position = n_position;
        problem.names = names;

        // the Python function's result: n numbers (a non-finite one is the library's to report,
        // naming the step, t and the component)
        problem.rhs = [&rhs, n, f](double t, const Eigen::VectorXd& y, Eigen::VectorXd& dydt) {
          const py::object out = rhs(t, y);
          const cv::RealArray a = cv::real_array(out, {f, "rhs(t, y) result"},
                                                 fmt::format("({},)", n), cv::Finite::kAllowed);
          if (a.ndim() != 1 || a.shape(0) != n) {
            throw rigid::Error(fmt::format(
                "{}(): rhs(t, y) must return dy/dt of shape ({},), like y0; got shape {} "
                "at t = {} s",
                f, n, cv::shape_text(a), t));
          }
          dydt = Eigen::Map<const Eigen::VectorXd>(a.data(), n);
        };
        rigid::python::Interruptible interrupt;
        ri::Options options;
        options.method = ri::parse_method(method);
        options.dt = dt;
        options.rtol = rtol;
        options.atol = atol;
        options.output_dt = output_dt;
        options.control = interrupt.control();
        const ri::Solution sol = ri::integrate(problem, options);
        Eigen::MatrixXd y(static_cast<Eigen::Index>(sol.y.size()), n);
        for (std::size_t k = 0; k < sol.y.size(); ++k)
          y.row(static_cast<Eigen::Index>(k)) = sol.y[k].transpose();
        py::dict d;
        d["t"] = cv::array(sol.t);
        d["y"] = y;
        d["steps"] = sol.steps;
        d["rhs_evaluations"] = sol.rhs_evaluations;
        return d;
      },
      py::arg("rhs"), py::arg("y0"), py::arg("t_end"), py::kw_only(), py::arg("t0") = 0.0,
      py::arg("method") = "dopri5", py::arg("dt") = 1e-3, py::arg("rtol") = 1e-10,
      py::arg("atol") = 1e-10, py::arg("output_dt") = 0.0, py::arg("n_position") = -1,
      py::arg("names") = std::vector<std::string>{},
      "Integrates dy/dt = rhs(t, y) from y(t0) = y0 (shape (n,)) to t_end (s) with the library's "
      "method: 'rk4' or 'implicit_midpoint' (fixed steps, the fewest equal steps ≤ dt between "
      "outputs), 'dopri5' (adaptive: 2.2e-15 ≤ rtol ≤ 0.1, 0 < atol ≤ 0.1; dt the first step), "
      "'stormer_verlet' (y = (q, v) with the first n_position components q, default half; "
      "rhs's v̇ must not depend on v). Outputs at t0 + k·output_dt and t_end (output_dt = 0: "
      "every step). Returns {'t': (m,), 'y': (m, n), 'steps', 'rhs_evaluations'}. Every step is "
      "checked for a non-finite state (the error names the step, t and the component, by "
      "`names` when given). The GIL is held (rhs is Python); Ctrl-C raises KeyboardInterrupt.");
  integrate.def(
      "methods",
      [] {
        std::vector<std::string> out;
        for (auto k : {ri::Method::kRk4, ri::Method::kDopri5, ri::Method::kImplicitMidpoint,
                       ri::Method::kStormerVerlet}) {
          out.emplace_back(ri::to_string(k));
        }
        return out;
      },
      "The method names solve() accepts.");
}
