// The _mechflow extension: the mechflow package's C++ half.

#include <cctype>

#include "analysis/interrupted.h"
#include "mech/errors.h"
#include "python/bindings/bindings.h"

namespace mechflow::python {
namespace {

// Raises mechflow.<name>(message): the exception classes are the package's
// (python/mechflow/_errors.py), so they carry file, line and time.
void Raise(const char* name, const char* message) {
  const py::object cls = py::module_::import("mechflow._errors").attr(name);
  PyErr_SetObject(cls.ptr(), py::str(message).ptr());
}

void Translate(std::exception_ptr p) {
  try {
    if (p) std::rethrow_exception(p);
  } catch (const InputError& e) {
    Raise("DiagramError", e.what());
  } catch (const SimulationError& e) {
    Raise("SimulationError", e.what());
  } catch (const analysis::Interrupted& e) {
    PyErr_SetString(PyExc_KeyboardInterrupt, e.what());
  }
}

}  // namespace

Settings ToSettings(const py::handle& mapping) {
  Settings s;
  if (mapping.is_none()) return s;
  if (!py::isinstance<py::dict>(mapping)) throw py::type_error("set= takes a dict {identifier: value}");
  for (const auto& [key, value] : py::reinterpret_borrow<py::dict>(mapping)) {
    const std::string name = py::str(key);
    if (py::isinstance<py::str>(value)) s.expressions.emplace_back(name, value.cast<std::string>());
    else if (py::isinstance<py::bool_>(value) || !(py::isinstance<py::float_>(value) || py::isinstance<py::int_>(value) ||
                                                   py::hasattr(value, "__float__")))
      throw py::type_error("set= " + name + ": a number (in the unit of its definition) or an expression text, not " +
                           std::string(py::str(py::type::of(value).attr("__name__"))));
    else s.numbers.emplace_back(name, value.cast<double>());
  }
  return s;
}

diagrams::LoadOptions WithSettings(diagrams::LoadOptions base, const Settings& settings) {
  // a later setting replaces an earlier one of the same name, number or
  // expression (the loader applies every number before every expression)
  const auto lower = [](std::string s) {
    for (char& c : s) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
    return s;
  };
  const auto replaced = [&](const auto& entry) {
    for (const auto& n : settings.numbers)
      if (lower(n.first) == lower(entry.first)) return true;
    for (const auto& e : settings.expressions)
      if (lower(e.first) == lower(entry.first)) return true;
    return false;
  };
  std::erase_if(base.overrides, replaced);
  std::erase_if(base.expression_overrides, replaced);
  base.overrides.insert(base.overrides.end(), settings.numbers.begin(), settings.numbers.end());
  base.expression_overrides.insert(base.expression_overrides.end(), settings.expressions.begin(),
                                   settings.expressions.end());
  return base;
}

py::array_t<double> ToArray(std::vector<double>&& values) {
  auto* owned = new std::vector<double>(std::move(values));
  const py::capsule free(owned, [](void* p) { delete static_cast<std::vector<double>*>(p); });
  return py::array_t<double>(static_cast<py::ssize_t>(owned->size()), owned->data(), free);
}

}  // namespace mechflow::python

PYBIND11_MODULE(_mechflow, m) {
  m.doc() = "mechflow's C++ core; use the mechflow package, which wraps it.";
  pybind11::register_exception_translator(&mechflow::python::Translate);
  mechflow::python::BindModel(m);
  mechflow::python::BindAnalysis(m);
}
