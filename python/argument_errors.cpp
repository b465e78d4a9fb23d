// Calls whose arguments match no signature: rigid's TypeError instead of pybind11's
// "incompatible function arguments. The following argument types are supported: ...".
//
// pybind11 raises that message in its dispatcher, before any binding runs, so neither a binding
// nor an exception translator sees it. Every pybind11 function object of the module shares one
// C entry point (cpp_function::dispatcher, the ml_meth of its PyMethodDef); once the module is
// built, plain_argument_errors() points each of them at `dispatch` below, which calls pybind11's
// dispatcher and, when it refused the arguments, replaces the message by one in the module's
// words (and refuses None as the self of an unbound method, which pybind11 would pass on as
// a null `this`):
//
//   rigid.mass.cylinder(): got (str); expected (mass: float, radius: float, height: float)
//   -> rigid.MassProperties
//
// naming the function as Python users call it, the types that came (not their reprs: an array
// argument's repr can be megabytes) and each accepted signature. A call that matched proceeds
// untouched: the extra cost is one C call and one pointer comparison.
#include <Python.h>
#include <fmt/format.h>
#include <pybind11/pybind11.h>

#include <string>
#include <string_view>
#include <unordered_map>
#include <unordered_set>
#include <vector>

namespace py = pybind11;

namespace {

// pybind11's dispatcher, read from a function pybind11 builds (set once, before any call).
PyCFunctionWithKeywords pybind11_dispatcher = nullptr;

// A function as Python users call it: its name, and for a method (or a property's getter or
// setter) the class its first argument must be.
struct Function {
  std::string name;
  std::string self_class;  // empty: a module function or a static method
};

// Each function by its PyCFunction self (pybind11's function-record capsule, alive as long as
// the function). Never destroyed: functions may be called while the interpreter shuts down.
auto& python_names() {
  static auto* names = new std::unordered_map<PyObject*, Function>();
  return *names;
}

std::string type_name(PyObject* value) { return Py_TYPE(value)->tp_name; }

// "(str, float, mass=str)": what the call passed (self left out for a constructor).
std::string passed_types(PyObject* args, PyObject* kwargs, bool constructor) {
  std::string out = "(";
  bool first = true;
  const Py_ssize_t n = args ? PyTuple_Size(args) : 0;
  for (Py_ssize_t k = constructor ? 1 : 0; k < n; ++k) {
    out += (first ? "" : ", ") + type_name(PyTuple_GetItem(args, k));
    first = false;
  }
  if (kwargs && PyDict_Check(kwargs)) {
    PyObject* key = nullptr;
    PyObject* value = nullptr;
    Py_ssize_t pos = 0;
    while (PyDict_Next(kwargs, &pos, &key, &value)) {
      const char* name = PyUnicode_Check(key) ? PyUnicode_AsUTF8(key) : nullptr;
      out += fmt::format("{}{}={}", first ? "" : ", ", name ? name : "?", type_name(value));
      first = false;
    }
  }
  return out + ")";
}

// The signatures listed in pybind11's message ("    1. (x: float) -> float"), without the
// numbers.
std::vector<std::string> signatures(std::string_view message) {
  std::vector<std::string> out;
  std::size_t pos = message.find('\n');
  while (pos != std::string_view::npos) {
    const std::size_t end = message.find('\n', pos + 1);
    std::string_view line = message.substr(
        pos + 1, end == std::string_view::npos ? std::string_view::npos : end - pos - 1);
    pos = end;
    const std::size_t dot = line.find(". ");
    if (line.rfind("    ", 0) != 0 || dot == std::string_view::npos) {
      if (!out.empty()) break;  // the list ended
      continue;
    }
    out.emplace_back(line.substr(dot + 2));
  }
  return out;
}

// The function's name as pybind11 put it at the start of its message ("cylinder(): ...").
std::string name_in(std::string_view message) {
  const std::size_t paren = message.find("(): ");
  return std::string(paren == std::string_view::npos ? "" : message.substr(0, paren));
}

// Replaces the pending "incompatible function arguments" TypeError by rigid's wording; any
// other error is left as it is.
void reword(PyObject* self, PyObject* args, PyObject* kwargs) {
  PyObject* type = nullptr;
  PyObject* value = nullptr;
  PyObject* traceback = nullptr;
  PyErr_Fetch(&type, &value, &traceback);
  PyErr_NormalizeException(&type, &value, &traceback);
  std::string message;
  if (value) {
    if (PyObject* text = PyObject_Str(value)) {
      if (const char* utf8 = PyUnicode_AsUTF8(text)) message = utf8;
      Py_DECREF(text);
    }
    PyErr_Clear();
  }
  const bool function = message.find("incompatible function arguments") != std::string::npos;
  const bool constructor = message.find("incompatible constructor arguments") != std::string::npos;
  if (!function && !constructor) {
    PyErr_Restore(type, value, traceback);
    return;
  }
  std::string text;
  try {
    const auto known = python_names().find(self);
    const std::string name = known != python_names().end() ? known->second.name : name_in(message);
    const std::vector<std::string> accepted = signatures(message);
    std::string expected;
    for (std::size_t k = 0; k < accepted.size(); ++k) {
      expected += (k ? "; or " : "") + accepted[k];
    }
    text = fmt::format("{}(): got {}; expected {}{}", name, passed_types(args, kwargs, constructor),
                       accepted.size() > 1 ? "one of " : "", expected);
  } catch (...) {
    PyErr_Restore(type, value, traceback);
    return;
  }
  Py_XDECREF(type);
  Py_XDECREF(value);
  Py_XDECREF(traceback);
  PyErr_SetString(PyExc_TypeError, text.c_str());
}

// A method called unbound with None for self (rigid.SO3.matrix(None)): pybind11 would pass a
// null pointer as `this` to a member-function binding. Refused here, before it gets there.
bool none_for_self(PyObject* self, PyObject* args) {
  if (!args || PyTuple_Size(args) == 0 || PyTuple_GetItem(args, 0) != Py_None) return false;
  const auto known = python_names().find(self);
  if (known == python_names().end() || known->second.self_class.empty()) return false;
  PyErr_SetString(PyExc_TypeError, fmt::format("{}(): self must be a {}; got None",
                                               known->second.name, known->second.self_class)
                                       .c_str());
  return true;
}

PyObject* dispatch(PyObject* self, PyObject* args, PyObject* kwargs) {
  if (none_for_self(self, args)) return nullptr;
  PyObject* result = pybind11_dispatcher(self, args, kwargs);
  if (result == nullptr && PyErr_ExceptionMatches(PyExc_TypeError)) reword(self, args, kwargs);
  return result;
}

// Points one pybind11 function object at `dispatch` and records its Python name.
void redirect(PyObject* f, const std::string& name, const std::string& self_class = "") {
  if (f && PyInstanceMethod_Check(f)) f = PyInstanceMethod_Function(f);  // def_readonly's getter
  if (!f || !PyCFunction_Check(f)) return;
  PyMethodDef* def = reinterpret_cast<PyCFunctionObject*>(f)->m_ml;
  const auto meth =
      reinterpret_cast<PyCFunctionWithKeywords>(reinterpret_cast<void*>(def->ml_meth));
  if (meth != pybind11_dispatcher && meth != &dispatch) return;  // not pybind11's
  def->ml_meth = reinterpret_cast<PyCFunction>(reinterpret_cast<void*>(&dispatch));
  python_names().emplace(PyCFunction_GetSelf(f), Function{name, self_class});
}

// The functions behind a class attribute: a method, static method, property (getter and
// setter) or the function itself.
void redirect_attribute(const py::handle& value, const std::string& name,
                        const std::string& self_class) {
  if (PyInstanceMethod_Check(value.ptr())) {
    redirect(PyInstanceMethod_Function(value.ptr()), name, self_class);
  } else if (PyCFunction_Check(value.ptr())) {
    redirect(value.ptr(), name);
  } else if (py::isinstance<py::staticmethod>(value)) {
    redirect(value.attr("__func__").ptr(), name);
  } else if (PyObject_IsInstance(value.ptr(), reinterpret_cast<PyObject*>(&PyProperty_Type)) == 1) {
    // a static property's getter takes the class, not an instance
    const bool on_class =
        std::string_view(Py_TYPE(value.ptr())->tp_name).find("static") != std::string_view::npos;
    redirect(value.attr("fget").ptr(), name, on_class ? "" : self_class);
    redirect(value.attr("fset").ptr(), name, on_class ? "" : self_class);
  }
}

void redirect_module(const py::module_& m, const std::string& prefix,
                     std::unordered_set<PyObject*>& seen) {
  if (!seen.insert(m.ptr()).second) return;
  for (const auto& [key, value] : py::reinterpret_borrow<py::dict>(m.attr("__dict__"))) {
    const std::string attr = py::str(key);
    const std::string name = prefix + "." + attr;
    if (py::isinstance<py::module_>(value)) {
      redirect_module(py::reinterpret_borrow<py::module_>(value), name, seen);
    } else if (PyType_Check(value.ptr())) {
      if (!seen.insert(value.ptr()).second) continue;
      // a class's __dict__ is a mappingproxy: its items() as a list
      for (const auto& item : py::list(value.attr("__dict__").attr("items")())) {
        const auto pair = py::reinterpret_borrow<py::tuple>(item);
        redirect_attribute(pair[1], name + "." + std::string(py::str(pair[0])), name);
      }
    } else {
      redirect(value.ptr(), name);
    }
  }
}

}  // namespace

/// Points every pybind11 function of `m` (its functions, submodules and classes, as `prefix`
/// names them: "rigid") at the rewording dispatcher. Called once the module is complete.
void plain_argument_errors(py::module_& m, const std::string& prefix) {
  if (!pybind11_dispatcher) {
    const py::cpp_function probe([] {});
    pybind11_dispatcher = reinterpret_cast<PyCFunctionWithKeywords>(
        reinterpret_cast<void*>(reinterpret_cast<PyCFunctionObject*>(probe.ptr())->m_ml->ml_meth));
  }
  std::unordered_set<PyObject*> seen;
  redirect_module(m, prefix, seen);
}
