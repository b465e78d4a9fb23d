// Python bindings of scene files: rigid.Scene(path, set=[...]) builds the model of a TOML
// scene (docs/scene-format.md); .run() returns the trajectory as a dict of numpy columns and
// the summary as a dict — the same numbers `rigid run` writes — and, given an output
// directory, writes the same files. A run releases the GIL and stops on Ctrl-C.
#include <atomic>
#include <chrono>
#include <cstdint>
#include <numeric>
#include <filesystem>
#include <optional>

#include <fmt/format.h>

#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>
#include <pybind11/stl/filesystem.h>

#include "convert.hpp"
#include "interrupt.hpp"
#include "rigid/io/atomic_file.hpp"
#include "rigid/lagrange/export.hpp"
#include "rigid/io/run_output.hpp"
#include "rigid/common/escape.hpp"
#include "rigid/report/report.hpp"
#include "rigid/report/sweep_page.hpp"
#include "rigid/scene/export.hpp"
#include "rigid/scene/model.hpp"
#include "rigid/scene/scene.hpp"
#include "rigid/scene/sweep.hpp"
#include "rigid/common/wording.hpp"

namespace py = pybind11;
namespace cv = rigid::python::convert;

namespace {

using rigid::scene::Model;

// A run's schema as Python sees it: the JSON summary.json holds, as dicts and lists.
py::object to_python(const rigid::io::RunSchema& schema) {
  return py::module_::import("json").attr("loads")(rigid::io::schema_json(schema));
}

py::dict to_python(const rigid::io::RunResult& r) {
  const rigid::io::Table& t = r.trajectory;
  py::dict columns;
  for (std::size_t c = 0; c < t.columns().size(); ++c) {
    py::array_t<double> a(static_cast<py::ssize_t>(t.rows()));
    auto v = a.mutable_unchecked<1>();
    for (std::size_t k = 0; k < t.rows(); ++k) v(static_cast<py::ssize_t>(k)) = t(k, c);
    columns[py::str(t.columns()[c])] = a;
  }
  const rigid::io::RunSummary& s = r.summary;
  py::dict summary;
  summary["scene"] = s.scene;
  summary["kind"] = std::string(rigid::io::to_string(s.kind));
  summary["integrator"] = s.integrator;
  summary["t_end"] = s.t_end;
  summary["dt"] = s.dt;
  summary["tolerance"] = s.tolerance;
  summary["steps"] = s.steps;
  summary["rhs_evaluations"] = s.rhs_evaluations;
  summary["samples"] = s.samples;
  summary["wall_time_s"] = s.wall_seconds;
  py::dict parameters, diagnostics;
  for (const auto& [name, value] : s.parameters) parameters[py::str(name)] = value;
  for (const auto& [name, value] : s.diagnostics) diagnostics[py::str(name)] = value;
  summary["parameters"] = parameters;
  summary["diagnostics"] = diagnostics;
  summary["warnings"] = s.warnings;
  py::dict metrics;  // name → {"value", "unit", "note"}, in file order (NaN: did not happen)
  for (const rigid::io::Metric& m : s.metrics) {
    py::dict e;
    e["value"] = m.value;
    e["unit"] = m.unit;
    e["note"] = m.note;
    metrics[py::str(m.name)] = e;
  }
  summary["metrics"] = metrics;
  py::dict out;
  out["columns"] = columns;
  out["summary"] = summary;
  out["schema"] = to_python(r.schema);
  return out;
}

// max_memory=: a number of bytes or a size such as "512MiB" (rigid::io::parse_memory_size).
std::optional<std::uint64_t> memory_of(const py::object& value) {
  if (value.is_none()) return std::nullopt;
  if (py::isinstance<py::str>(value)) return rigid::io::parse_memory_size(value.cast<std::string>());
  if (py::isinstance<py::int_>(value) && !py::isinstance<py::bool_>(value)) {
    const auto bytes = value.cast<long long>();
    if (bytes <= 0) throw rigid::Error(fmt::format("max_memory = {} bytes; expected a positive size", bytes));
    return static_cast<std::uint64_t>(bytes);
  }
  throw rigid::Error("max_memory must be a number of bytes or a size such as \"512MiB\"");
}

// report=: None or False (no page), True (report.html in `output`, with the run's files) or a
// path (the page alone, written there).
struct ReportRequest {
  bool in_output = false;
  std::optional<std::filesystem::path> path;
  rigid::report::ReportOptions options;
};

std::optional<ReportRequest> report_of(const py::object& value, const py::object& frames, bool has_output) {
  if (value.is_none() || (py::isinstance<py::bool_>(value) && !value.cast<bool>())) {
    if (!frames.is_none()) throw rigid::Error("report_frames sets the frames of the report: give report= with it");
    return std::nullopt;
  }
  if (!rigid::report::available()) {
    throw rigid::Error("this rigid module was built without the report page (CMake option RIGID_REPORT=OFF, "
                       "a build without node): rebuild with the ci or release preset to write reports");
  }
  ReportRequest r;
  if (py::isinstance<py::bool_>(value)) {
    if (!has_output) {
      throw rigid::Error("report=True writes report.html into the output directory: give output= too, or "
                         "report=PATH for the page alone");
    }
    r.in_output = true;
  } else if (py::isinstance<py::str>(value) || py::isinstance(value, py::module_::import("pathlib").attr("PurePath"))) {
    r.path = value.cast<std::filesystem::path>();
  } else {
    throw rigid::Error("report must be True (report.html in output) or the path of the page");
  }
  if (!frames.is_none()) {
    if (!py::isinstance<py::int_>(frames) || py::isinstance<py::bool_>(frames)) {
      throw rigid::Error("report_frames must be a whole number of frames");
    }
    const auto n = frames.cast<long long>();
    if (n < static_cast<long long>(rigid::report::kMinMaxFrames) ||
        n > static_cast<long long>(rigid::report::kMaxMaxFrames)) {
      throw rigid::Error(fmt::format("report_frames = {}: expected a number of frames from {} to {}", n,
                                     rigid::report::kMinMaxFrames, rigid::report::kMaxMaxFrames));
    }
    r.options.max_frames = static_cast<std::size_t>(n);
  }
  return r;
}

py::dict run(const Model& model, const std::string& integrator, std::optional<std::filesystem::path> output,
             const std::vector<std::string>& formats, const py::object& max_memory, const py::object& report,
             const py::object& report_frames) {
  const std::optional<ReportRequest> page = report_of(report, report_frames, output.has_value());
  rigid::python::Interruptible interrupt;
  rigid::scene::RunOptions options;
  options.integrator = integrator;
  options.control = interrupt.control();
  options.max_memory = memory_of(max_memory);
  // formats and the directory are checked before the run, so a typo costs no simulation
  const std::vector<rigid::io::OutputFormat> chosen = output ? model.output_formats(formats)
                                                             : std::vector<rigid::io::OutputFormat>{};
  if (output) rigid::io::check_output_directory(*output);
  rigid::io::RunResult r;
  std::vector<std::filesystem::path> paths;
  {
    // a Model is immutable and each run has its own state: other Python threads run meanwhile
    py::gil_scoped_release release;
    r = model.run(options);
    std::vector<rigid::io::ExtraFile> extra;
    if (page) {
      std::string html = rigid::report::report_page(model, r, page->options);
      if (page->in_output) {
        extra.push_back({std::string(rigid::io::kReportFileName), std::move(html)});
      } else {
        rigid::io::write_file_atomically(*page->path, html);
      }
    }
    if (output) paths = rigid::io::write_run(*output, r, chosen, extra);
  }
  py::dict out = to_python(r);
  if (output) {
    py::list written;
    for (const auto& p : paths) written.append(py::str(p.string()));
    out["written"] = written;
  }
  if (page) out["report"] = py::str((page->in_output ? *output / rigid::io::kReportFileName : *page->path).string());
  return out;
}

// rigid.sweep: the runs of `rigid sweep` (no journal: a Python sweep is not resumed), rows as
// numpy columns, the summary as a dict; Ctrl-C stops it (KeyboardInterrupt) after the runs in
// flight.
py::dict sweep(const py::object& scene_arg, const std::vector<std::string>& grid, const std::vector<std::string>& sample,
               std::size_t samples, std::uint64_t seed, const std::vector<std::string>& set,
               const std::string& integrator, std::size_t threads, const py::object& output_arg,
               const py::object& report_arg) {
  namespace sc = rigid::scene;
  const char* f = "rigid.sweep";
  const std::string file = cv::path(scene_arg, {f, "scene"});
  std::optional<std::filesystem::path> output;
  if (!output_arg.is_none()) output = cv::path(output_arg, {f, "output"});
  sc::SweepSpec spec;
  for (const auto& g : grid) {
    try {
      spec.grid.push_back(sc::parse_grid_axis(g));
    } catch (const rigid::Error& e) {
      throw rigid::Error(fmt::format("{}(): grid: {}", f, rigid::strip_function_names(e.what())));
    }
  }
  for (const auto& a : sample) {
    try {
      spec.sample.push_back(sc::parse_sample_axis(a));
    } catch (const rigid::Error& e) {
      throw rigid::Error(fmt::format("{}(): sample: {}", f, rigid::strip_function_names(e.what())));
    }
  }
  spec.samples = samples;
  spec.seed = seed;
  if (spec.grid.empty() == spec.sample.empty()) {
    throw rigid::Error(fmt::format("{}(): give the runs as grid=['NAME=START:STOP:COUNT', ...] or "
                                   "sample=['NAME=DIST(A,B)', ...] with samples=N (one of them)", f));
  }
  if (!spec.sample.empty() && samples == 0) throw rigid::Error(fmt::format("{}(): sample= needs samples=N, the number of runs", f));
  if (!spec.grid.empty() && samples > 0) throw rigid::Error(fmt::format("{}(): samples= is for sample=; a grid axis has its own count", f));
  if (threads == 0) throw rigid::Error(fmt::format("{}(): threads must be at least 1", f));
  sc::check_spec(spec);
  const sc::SweepIdentity id{.scene = file, .set = set, .integrator = integrator, .spec = spec};
  cv::reading(f, file, [&] {
    sc::Scene parsed = sc::load_scene(file);
    sc::apply_overrides(parsed, set);
    sc::check_overrides(id);
  });
  if (output) rigid::io::check_output_directory(*output);
  std::optional<std::filesystem::path> report;
  if (!report_arg.is_none()) {
    report = cv::path(report_arg, {f, "report"});
    if (!rigid::report::available()) {
      throw rigid::Error(fmt::format("{}(): report: this build of rigid has no report page (built with "
                                     "RIGID_REPORT=OFF); rebuild with RIGID_REPORT=ON to write pages", f));
    }
    (void)rigid::io::check_output_file(*report);
  }
  const std::size_t runs = sc::run_count(spec);
  std::vector<std::size_t> indices(runs);
  std::iota(indices.begin(), indices.end(), std::size_t{0});
  std::atomic<bool> cancel{false};
  sc::SweepRunOptions options;
  options.threads = threads;
  options.wording = rigid::Surface::kPython;
  options.cancel = &cancel;
  // Ctrl-C is looked for at most every 20 ms: taking the GIL for each row would make it the
  // serial part of a sweep of short runs (calls to on_row are serialized, so `last` needs no lock)
  auto last = std::chrono::steady_clock::now() - std::chrono::seconds(1);
  options.on_row = [&cancel, &last](const sc::SweepRow&) {
    const auto now = std::chrono::steady_clock::now();
    if (now - last < std::chrono::milliseconds(20)) return;
    last = now;
    py::gil_scoped_acquire gil;
    if (PyErr_CheckSignals() != 0) {
      PyErr_Clear();  // raised again as KeyboardInterrupt from rigid::Cancelled
      cancel = true;
    }
  };
  std::vector<sc::SweepRow> rows;
  {
    py::gil_scoped_release release;
    // run 0, checked once (run_sweep would); its schema gives the page's units
    options.first_run = sc::check_first_run(id);
    rows = sc::run_sweep(id, indices, options);
  }
  // the units of run 0's schema, in summary.json and on the page
  const sc::SweepUnits units = options.first_run ? sc::sweep_units(options.first_run->schema()) : sc::SweepUnits{};
  const sc::SweepOutputs outputs = sc::make_outputs(sc::swept_names(spec), runs, std::move(rows), units);
  py::dict columns;
  const rigid::io::Table& t = outputs.numbers;
  for (std::size_t c = 0; c < t.columns().size(); ++c) {
    py::array_t<double> a(static_cast<py::ssize_t>(t.rows()));
    auto v = a.mutable_unchecked<1>();
    for (std::size_t k = 0; k < t.rows(); ++k) v(static_cast<py::ssize_t>(k)) = t(k, c);
    columns[py::str(t.columns()[c])] = a;
  }
  py::dict out;
  out["columns"] = columns;
  out["errors"] = outputs.errors;
  out["summary"] = py::module_::import("json").attr("loads")(outputs.summary_json);
  if (output) {
    py::list written;
    std::filesystem::create_directories(*output);
    for (const auto& p : sc::write_outputs(*output, outputs, options.threads)) written.append(py::str(p.string()));
    out["written"] = written;
  }
  if (report) {
    // the page from the runs in memory: the same data `rigid report DIR` reads from the files
    rigid::report::SweepData data;
    data.names = t.columns();
    data.columns.assign(t.columns().size(), std::vector<double>(t.rows()));
    for (std::size_t c = 0; c < t.columns().size(); ++c) {
      for (std::size_t k = 0; k < t.rows(); ++k) data.columns[c][k] = t(k, c);
    }
    data.errors = outputs.errors;
    data.swept = sc::swept_names(spec);
    data.summary_json = outputs.summary_json;
    data.units = units;
    data.description = sc::describe(id);
    data.title = rigid::escaped(std::filesystem::path(file).stem().string());
    rigid::io::write_file_atomically(*report, rigid::report::sweep_page(data));
    out["report"] = py::str(report->string());
  }
  return out;
}

}  // namespace

void bind_scene(py::module_& m) {
  m.def("sweep", &sweep, py::arg("scene"), py::kw_only(), py::arg("grid") = std::vector<std::string>{},
        py::arg("sample") = std::vector<std::string>{}, py::arg("samples") = 0, py::arg("seed") = 0,
        py::arg("set") = std::vector<std::string>{}, py::arg("integrator") = std::string{},
        py::arg("threads") = 1, py::arg("output") = py::none(), py::arg("report") = py::none(),
        "Runs one scene file many times, as `rigid sweep`: over a grid (grid=['L=0.5:2:4', ...], "
        "every combination, the first axis slowest) or a Monte Carlo sample "
        "(sample=['m=uniform(1,2)', 'k=normal(10,1)', 'c=loguniform(1e-3,1)'], samples=N, seed=S; "
        "reproducible whatever the threads). Each run gets `set` then its own values as overrides. "
        "Returns {'columns': {run, the swept names, each run's metrics and diagnostics: numpy "
        "arrays, NaN for a failed run}, 'errors': [text per run, '' when it succeeded], 'summary': "
        "statistics per column as summary.json}; with `output` (a directory) also writes runs.csv, "
        "runs.npy and summary.json, byte for byte what `rigid sweep` writes; with `report` (a file "
        "name) also writes the sweep's page there, as `rigid sweep --report` (returned as 'report'). "
        "Runs on `threads` "
        "threads with the GIL released; Ctrl-C raises KeyboardInterrupt.");

  py::class_<Model>(m, "Scene",
                    "A scene file turned into a model (parameters evaluated, mass properties and "
                    "equations built). Errors are rigid.Error with file:line:col.")
      .def(py::init([](const py::object& path, const std::vector<std::string>& set,
                       std::optional<bool> pin_free_root, std::optional<bool> inertia_from_geometry,
                       std::optional<double> density, std::optional<bool> symbolic_inertia) {
             const std::string file = cv::path(path, {"rigid.Scene", "path"});
             // a str is always a file name: scene text is refused with the remedy, never parsed
             if ((file.find('\n') != std::string::npos || file.find('[') != std::string::npos) && !cv::is_file(file)) {
               throw rigid::Error("rigid.Scene(): the path looks like TOML text: load a scene given as "
                                  "text with rigid.Scene.from_string(text)");
             }
             const rigid::scene::ModelOptions model{.pin_free_root = pin_free_root,
                                                    .inertia_from_geometry = inertia_from_geometry,
                                                    .density = density,
                                                    .symbolic_inertia = symbolic_inertia};
             return cv::reading("rigid.Scene", file,
                                [&] { return rigid::scene::load_model(file, set, model); });
           }),
           py::arg("path"), py::arg("set") = std::vector<std::string>{}, py::kw_only(),
           py::arg("pin_free_root") = py::none(), py::arg("inertia_from_geometry") = py::none(),
           py::arg("density") = py::none(), py::arg("symbolic_inertia") = py::none(),
           "Loads a TOML scene file or a robot model file (URDF, MJCF; a str or pathlib.Path; mesh "
           "and [model] paths are relative to its directory; errors start with file:line:col); "
           "`set` holds 'name=value' overrides: parameters, simulation.<key>, "
           "<coordinate>.initial/.velocity, <body>.omega (docs/scene-format.md). pin_free_root, "
           "inertia_from_geometry and density (kg/m³, a URDF's collision geometry with "
           "inertia_from_geometry) say how the robot model file is read, the one given or the one "
           "[model] names (over the section's settings; None: the section's, else False, False, "
           "1000); symbolic_inertia keeps each link's mass, COM and inertia as the parameters m_<link>, "
           "com_<link>_x.., I_<link>_xx..; a TOML scene without [model] refuses them. Text is loaded by Scene.from_string.")
      .def_static(
          "from_string",
          [](const std::string& text, const std::vector<std::string>& set, const py::object& name) {
            // messages name `name`; mesh paths resolve against its directory (the current one by default)
            const std::string file = name.is_none() ? std::string("<string>") : cv::path(name, {"rigid.Scene.from_string", "name"});
            rigid::scene::Scene scene = rigid::scene::parse_scene(text, file);
            rigid::scene::apply_overrides(scene, set);
            return Model(scene);
          },
          py::arg("text"), py::arg("set") = std::vector<std::string>{},
          py::arg("name") = py::none(),
          "A scene from TOML text (what a scene file holds): errors start with name:line:col "
          "(name default '<string>'), and mesh paths are relative to name's directory (the "
          "current directory by default); `set` as in rigid.Scene(path, set).")
      .def_property_readonly(
          "kind", [](const Model& mo) { return std::string(rigid::io::to_string(mo.kind())); },
          "'coordinates' (a Lagrangian system of generalized coordinates) or 'free_bodies'.")
      .def_property_readonly(
          "schema", [](const Model& mo) { return to_python(mo.schema()); },
          "What a run returns, known before it runs: {'kind', 'columns': [{'name', "
          "'quantity', 'owner', 'component', 'unit'}, ...] in the order of run()'s "
          "columns, 'parameters' / 'diagnostics' / 'metrics': {name: SI unit}} "
          "('' when dimensionless or not stated; docs/scene-format.md).")
      .def_property_readonly(
          "parameters",
          [](const Model& mo) {
            py::dict d;
            for (const auto& p : mo.parameters()) d[py::str(p.name)] = p.value;
            return d;
          },
          "The scene's parameters after `set` overrides, {name: value} in file order (SI units).")
      .def_property_readonly(
          "bodies",
          [](const Model& mo) {
            py::dict d;
            for (const auto& b : mo.bodies()) d[py::str(b.name)] = b.mass;
            return d;
          },
          "The bodies' mass properties (rigid.MassProperties in each body's frame), by name.")
      .def_property_readonly(
          "warnings", &Model::warnings,
          "What the scene's checks found suspicious but not wrong (the CLI prints them too).")
      .def_property_readonly("t_end", &Model::t_end, "End time of a run (s).")
      .def("integrator", &Model::integrator, py::arg("requested") = std::string{},
           "The method a run uses (the requested one, the scene's, or the kind's default).")
      .def(
          "equations",
          [](const Model& mo, bool latex, const std::string& format) {
            if (format.empty()) return mo.equations(latex);
            const auto f = rigid::lagrange::parse_equation_format(format);
            if (latex && f != rigid::lagrange::EquationFormat::kLatex) {
              throw rigid::Error(
                  fmt::format("latex=True and format='{}' ask for two formats; give one", format));
            }
            return mo.equations(f);
          },
          py::arg("latex") = false, py::arg("format") = std::string{},
          "The equations of motion as `rigid eom` prints them: format 'text' (default), 'latex' "
          "or 'json' (latex=True is format='latex').")
      .def(
          "emit",
          [](const Model& mo, const std::string& language, const std::string& name, bool flat,
             std::optional<std::size_t> max_stack_bytes, const std::string& namespace_) {
            if (max_stack_bytes && !flat) {
              throw rigid::Error("rigid.Scene.emit(): max_stack_bytes bounds the stack of the flat "
                                 "layout's derivatives; give flat=True with it");
            }
            if (!namespace_.empty() && !flat) {
              throw rigid::Error("rigid.Scene.emit(): namespace is the flat layout's (the other "
                                 "C++ layout's namespace is `name`); give flat=True with it");
            }
            return rigid::scene::emit_code(
                mo, language, name, flat,
                max_stack_bytes.value_or(rigid::lagrange::ExportOptions::kDefaultMaxStackBytes),
                namespace_);
          },
          py::arg("language"), py::arg("name") = std::string{}, py::arg("flat") = false,
          py::kw_only(), py::arg("max_stack_bytes") = py::none(), py::arg("namespace") = std::string{},
          "The equations of motion (M, f, G, γ) as one dependency-free source file: 'c++' (a "
          "header, <cmath> only; namespace `name`, default the file's stem) or 'python' (a "
          "module, math only), with the scene's parameters as defaults. flat=True (C++): the "
          "dynamics at global scope without t, as `rigid eom --emit c++ --flat`; "
          "max_stack_bytes (with flat=True): the most stack forward_dynamics_derivatives may "
          "take for M⁻¹ and its products, 16 n² + 8 n bytes (default 66048: n ≤ 64), above "
          "which it solves column by column, as --max-stack-bytes; namespace (with flat=True): "
          "the C++ namespace of its declarations instead of global scope, as --namespace.")
      .def_property_readonly("system", &Model::system, py::return_value_policy::reference_internal,
                             "The rigid.lagrange.System of a coordinate scene.")
      .def(
          "check",
          [](const Model& mo, const std::string& integrator, const py::object& max_memory) {
            rigid::scene::RunOptions o;
            o.integrator = integrator;
            o.max_memory = memory_of(max_memory);
            mo.check(o);
          },
          py::arg("integrator") = std::string{}, py::arg("max_memory") = py::none(),
          "Runs the checks of a run (initial conditions, mass matrix, steps, the trajectory's "
          "memory against max_memory) without integrating.")
      .def("run", &run, py::arg("integrator") = std::string{}, py::arg("output") = py::none(),
           py::arg("formats") = std::vector<std::string>{}, py::arg("max_memory") = py::none(),
           py::arg("report") = py::none(), py::arg("report_frames") = py::none(),
           "Simulates to t_end: {'columns': {name: numpy array}, 'summary': {...}, 'schema': "
           "Scene.schema} with the columns of docs/scene-format.md; summary['metrics'] holds the "
           "scene's [[output.metrics]] as "
           "{name: {'value', 'unit', 'note'}} (value NaN, with a note, when the event did not "
           "happen). "
           "With `output` (a directory), also writes the files `rigid run` "
           "writes (trajectory.csv, trajectory.npy, summary.json; `formats` as in the scene's "
           "[output] by default; summary.json always comes with trajectory.npy) as one set that "
           "replaces the directory, only after the run succeeded; the paths are under 'written'. "
           "`max_memory` (bytes or a size such as \"512MiB\"; default: the scene's [output] "
           "max_memory, else 2 GiB) caps the trajectory, checked before the run. Ctrl-C raises "
           "KeyboardInterrupt and writes nothing. `report=True` adds report.html to the files in "
           "`output` (one self-contained page: 3D motion, plots, equations; docs/report.md), "
           "`report=PATH` writes the page alone; its path is under 'report'. `report_frames` "
           "(default "
           "2000) caps the frames the page keeps.")
      .def("__repr__", [](const Model& mo) {
        return fmt::format("Scene('{}', kind='{}', t_end={} s)", mo.scene().file.string(),
                           rigid::io::to_string(mo.kind()), mo.t_end());
      });
}
